// Memory for a frame's large buffers (grid streams, clip coordinates, images, set-up
// triangles). Every frame allocates the same tens of megabytes again; fresh memory from the
// kernel costs a page fault and the zeroing of each 4 KiB page, which on the default frame
// took several milliseconds of serial time in the buffers' value-initialisation. Here blocks of
// a megabyte or more come from 2 MiB-aligned mappings that Linux may back with transparent
// huge pages (madvise), those of at most a megabyte two to a huge page (frame_memory.cc), each
// fresh block's pages faulted in by one call (MADV_POPULATE_WRITE), and freed ones are kept, up
// to kMaxCachedBytes, for the next allocation of the same size: the next frame finds its
// buffers mapped. Smaller blocks, other systems and sanitizer builds (which must see every
// block) take operator new. Where a buffer lies never changes what is stored in it.
#pragma once

#include <cstddef>

// Whether the mappings are used (Linux, no sanitizer).
#if defined(__linux__) && !defined(__SANITIZE_ADDRESS__) && !defined(__SANITIZE_THREAD__)
#define RELIEF_FRAME_MAPPINGS 1
#if defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer) || \
    __has_feature(memory_sanitizer)
#undef RELIEF_FRAME_MAPPINGS
#endif
#endif
#endif

namespace relief {

inline constexpr std::size_t kHugePageBytes = std::size_t{2} << 20;
// Mappings are whole pages, not whole huge pages: a block of 1 MiB + 1 byte rounded up to 2 MiB
// became resident in full (its one huge page faults in whole), twice what the buffer holds and
// what the memory estimates count (pipeline/job_memory.h). Huge pages still back every aligned
// 2 MiB of a block; its tail is ordinary pages.
inline constexpr std::size_t kPageBytes = std::size_t{4} << 10;
inline constexpr std::size_t kMinMappedBytes = std::size_t{1} << 20;
inline constexpr std::size_t kMaxCachedBytes = std::size_t{256} << 20;

// `bytes` (a multiple of kPageBytes) aligned to `align` (a power of two, at least the
// page size), zero-filled, huge pages advised. Throws std::bad_alloc when the system refuses.
// Only on RELIEF_FRAME_MAPPINGS systems.
void* map_aligned(std::size_t bytes, std::size_t align);
void unmap(void* block, std::size_t bytes);

// Like operator new / delete with alignment `align` (at most kHugePageBytes); `bytes` and
// `align` the same in both calls. Throws std::bad_alloc. A fresh block is resident at once:
// for buffers written in full (a value-initialised vector, an image).
void* allocate_frame_buffer(std::size_t bytes, std::size_t align);
void free_frame_buffer(void* block, std::size_t bytes, std::size_t align) noexcept;

// Returns the kept blocks to the system, so that a measurement of the process's resident
// memory (eval/process_memory.h) sees every buffer of the next frame mapped afresh.
void release_cached_frame_buffers() noexcept;

}  // namespace relief
