// What a backend supplies to the frame runner: the units of work of each stage of the table
// (stage_table.h), and the work of any range of them. The runner schedules; the backend
// computes. Two implement it: the CPU backend (cpu_backend.h), whose kernel table
// (cpu_kernels.h) makes it the reference, reference-double or simd backend, and the GL backend
// (gl_backend.h), which runs the GLSL twins.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "pipeline/frame.h"
#include "pipeline/stage_table.h"

namespace relief {

class FrameBackend {
 public:
  virtual ~FrameBackend() = default;

  // Called once before the units of stage `id` run: allocates the stage's outputs (so that a
  // run that stops early, like relief stages, allocates nothing for the stages it skips).
  virtual void prepare(StageId /*id*/) {}
  // Units of work of stage `id` in this frame (rows, vertices, chunks or tiles); 0 skips it.
  virtual std::size_t units(StageId id) const = 0;
  // Runs units [begin, end) of stage `id`. Called concurrently for disjoint ranges of one
  // stage; a stage starts only when the previous one has finished every unit.
  virtual void run(StageId id, std::size_t begin, std::size_t end) = 0;
  // Called once after every unit of stage `id` has run, before the next stage. May throw
  // MemoryLimitError (the bins are checked here, before they are allocated).
  virtual void after(StageId /*id*/) {}
  // Whether stage `id` did anything and its work counters (docs/stages.md, "Skipped work"),
  // once after(id) has run; `time` arrives with the name, the time and ran = (units > 0).
  virtual void describe(StageId /*id*/, StageTime& /*time*/) const {}
  // Moves the frame's results (image, requested outputs, rasteriser statistics and the
  // per-part times the fused stage measured) into `frame`.
  virtual void finish(Frame& frame) = 0;
};

}  // namespace relief
