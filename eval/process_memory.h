// The process's resident memory as Linux reports it, for measuring a job's peak against its
// estimate (job_memory.h): the peak resident set (VmHWM) can be reset to the current one
// (/proc/self/clear_refs, "5"), so the peak of one job is measured in a long-lived process.
// What this measures: every page the process touched during the job, from any allocator,
// thread stack or driver (llvmpipe's GL buffers are host memory), minus what was resident
// before it. Pages allocated but never touched do not count; neither does memory that a
// previous job left resident and this one reused, hence release_free_memory() first.
#pragma once

#include <cstdint>
#include <optional>

namespace relief {

// Whether peaks can be measured here: Linux with /proc, and no sanitizer (whose shadow memory
// and quarantine make the resident set a measure of the sanitizer).
bool peak_memory_measurable();

// Gives back what freed memory the process keeps: the frame buffer cache (core/frame_memory.h)
// the rasteriser's spare triangle slabs (raster/triangle_storage.h) and the C library's free
// lists (malloc_trim).
void release_free_memory();

// Starts a measurement: resets the peak to the current resident set and returns that. nullopt
// where peaks cannot be measured.
std::optional<std::uintmax_t> start_peak_measurement();

// The peak resident set since start_peak_measurement, in bytes (nullopt: not measurable).
std::optional<std::uintmax_t> peak_resident_bytes();

}  // namespace relief
