// GPU time of a frame's passes, from GL timer queries: a GL_TIMESTAMP (glQueryCounter) before
// and after each pass, read once at the end of the frame. glQueryCounter, unlike a
// GL_TIME_ELAPSED query, does not nest-limit (one elapsed query may be active at a time) and
// costs the CPU nothing: the GPU writes the time when it reaches the command. Reading the
// results waits for the GPU to reach the last one, so a frame reads them after its read-back,
// which has waited for the frame's last command already.
//
// What a pass's time holds: GL records a timestamp once every earlier command has completed, so
// a pass's time runs from the end of the work before it to the end of its own, including any
// time the GPU waited for the CPU to submit the pass (none when, as here, a pass is one
// dispatch or draw submitted with its timestamps).
#pragma once

#include <string>
#include <vector>

#include "gpu/gl_objects.h"

namespace relief::gpu {

struct GlPassTime {
  std::string name;
  double ms = 0;
};

class GlPassTimer {
 public:
  // Requires a current GL context; the queries belong to it. available() is false where the GL
  // has no timestamp counter (GL_QUERY_COUNTER_BITS of GL_TIMESTAMP is 0): then begin() and
  // end() do nothing and collect() returns nothing.
  GlPassTimer();
  GlPassTimer(const GlPassTimer&) = delete;
  GlPassTimer& operator=(const GlPassTimer&) = delete;

  bool available() const { return available_; }

  // The pass `name` starts (begin) and ends (end) here in the GL command stream. Passes do not
  // nest: begin() after begin() without end() throws std::logic_error.
  void begin(std::string name);
  void end();

  // The passes since the last collect() in the order they began, their GPU times in
  // milliseconds; waits for the GPU to reach the last timestamp. Forgets them.
  std::vector<GlPassTime> collect();

  // Forgets the passes without reading them (a frame that failed).
  void clear();

 private:
  GlName& query(std::size_t index);

  bool available_ = false;
  std::vector<GlName> queries_;  // two per pass: start, end; kept for the next frame
  std::vector<std::string> names_;
  bool open_ = false;
};

}  // namespace relief::gpu
