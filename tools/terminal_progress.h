// Progress of long work on a terminal: "LABEL: 3/8 bands, 12.4 s, about 20 s left[: DETAIL]",
// rewritten in place on standard error, only when standard error is a terminal (never in logs,
// pipes or the tests); finish() ends the line.
#pragma once

#include <chrono>
#include <string>
#include <string_view>

namespace relief {

class TerminalProgress {
 public:
  // `unit`: what is counted ("bands", "configurations").
  TerminalProgress(std::string label, std::string unit);
  ~TerminalProgress();
  TerminalProgress(const TerminalProgress&) = delete;
  TerminalProgress& operator=(const TerminalProgress&) = delete;

  // `detail`: what is being done now ("grid 1024"), shown after the count.
  void update(int done, int total, std::string_view detail = {});
  void finish();

 private:
  std::string label_, unit_;
  bool enabled_;
  bool open_ = false;  // a line was written and not yet ended
  std::chrono::steady_clock::time_point start_;
};

}  // namespace relief
