#include "tools/terminal_progress.h"

#include <unistd.h>

#include <cstdio>
#include <utility>

namespace relief {

TerminalProgress::TerminalProgress(std::string label, std::string unit)
    : label_(std::move(label)),
      unit_(std::move(unit)),
      enabled_(isatty(STDERR_FILENO) == 1),
      start_(std::chrono::steady_clock::now()) {}

TerminalProgress::~TerminalProgress() {
  finish();
}

void TerminalProgress::update(int done, int total, std::string_view detail) {
  if (!enabled_) {
    return;
  }
  const double elapsed =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  // The rate so far predicts the rest; nothing is said before the first unit is done (done > 0
  // guards the division).
  if (done > 0 && done < total) {
    std::fprintf(stderr, "\r%s: %d/%d %s, %.1f s, about %.0f s left", label_.c_str(), done, total,
                 unit_.c_str(), elapsed, elapsed / done * (total - done));
  } else {
    std::fprintf(stderr, "\r%s: %d/%d %s, %.1f s", label_.c_str(), done, total, unit_.c_str(),
                 elapsed);
  }
  // The rest of the previous line is cleared (ANSI "erase to end of line").
  std::fprintf(stderr, "%s%.*s\x1b[K", detail.empty() ? "" : ": ", int(detail.size()),
               detail.data());
  std::fflush(stderr);
  open_ = true;
}

void TerminalProgress::finish() {
  if (open_) {
    std::fputc('\n', stderr);
    std::fflush(stderr);
    open_ = false;
  }
}

}  // namespace relief
