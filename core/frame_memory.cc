#include "core/frame_memory.h"

#include <new>

#ifdef RELIEF_FRAME_MAPPINGS
#include <sys/mman.h>

#include <cstdint>
#include <limits>
#include <mutex>
#endif

namespace relief {

#ifdef RELIEF_FRAME_MAPPINGS
namespace {

std::size_t round_up(std::size_t n, std::size_t multiple) {
  return (n + multiple - 1) / multiple * multiple;
}

// Freed mapped blocks by size, most recent last.
struct BlockCache {
  static constexpr int kEntries = 64;
  std::mutex mutex;
  void* block[kEntries] = {};
  std::size_t size[kEntries] = {};
  int count = 0;
  std::size_t bytes = 0;
};

BlockCache& cache() {
  static BlockCache* const state = new BlockCache;  // never destroyed: blocks outlive statics
  return *state;
}

// Blocks of at most half a huge page (so, from kMinMappedBytes up, those of exactly a
// mebibyte) aligned to at most a page share one: a block takes the next bytes of the current
// 2 MiB arena where they fit, so that the default grid's 1 MiB streams (and clip coordinates)
// lie two to a huge page (a huge page faults in at once; each 4 KiB page of a 1 MiB mapping
// faulted alone: 10 MiB of grid streams took some 30 ms of page faults and first writes on a
// 2-core VM, 0.2 ms as huge pages). A process keeps at most half a huge page more resident
// than its blocks hold (the arena's free half). Blocks between half a huge page and one are
// mapped alone: two would not share one, and one alone in a huge page would double its
// memory (tests/eval/stress_test.cc). An arena's unused tail is returned when the next arena
// is mapped; a block freed for good is unmapped alone (Linux splits the huge page).
struct SmallBlockArena {
  std::mutex mutex;
  std::uintptr_t next = 0, end = 0;
};

SmallBlockArena& arena() {
  static SmallBlockArena* const state = new SmallBlockArena;  // never destroyed, as above
  return *state;
}

// `size` (a multiple of kPageBytes, at most kHugePageBytes / 2) from the current arena.
void* arena_block(std::size_t size) {
  SmallBlockArena& a = arena();
  const std::lock_guard<std::mutex> lock(a.mutex);
  if (a.end - a.next < size) {
    const auto fresh =
        reinterpret_cast<std::uintptr_t>(map_aligned(kHugePageBytes, kHugePageBytes));
    if (a.end > a.next) {
      munmap(reinterpret_cast<void*>(a.next), a.end - a.next);
    }
    a.next = fresh;
    a.end = fresh + kHugePageBytes;
  }
  void* const block = reinterpret_cast<void*>(a.next);
  a.next += size;
  return block;
}

// A fresh block is written in full by its owner (every buffer here is value-initialised or
// filled): its pages are faulted in by one call rather than one fault per page. Advice only:
// a kernel without MADV_POPULATE_WRITE (before Linux 5.14) faults them in as they are written.
void populate(void* block, std::size_t size) {
#ifdef MADV_POPULATE_WRITE
  madvise(block, size, MADV_POPULATE_WRITE);
#else
  (void)block;
  (void)size;
#endif
}

}  // namespace

void* map_aligned(std::size_t bytes, std::size_t align) {
  const std::size_t padded = bytes + align;
  void* const mapped =
      mmap(nullptr, padded, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (mapped == MAP_FAILED) {
    throw std::bad_alloc();
  }
  const auto start = reinterpret_cast<std::uintptr_t>(mapped);
  const std::uintptr_t aligned = (start + align - 1) & ~(std::uintptr_t{align} - 1);
  const std::uintptr_t end = start + padded, aligned_end = aligned + bytes;
  if (aligned > start) {
    munmap(mapped, aligned - start);
  }
  if (end > aligned_end) {
    munmap(reinterpret_cast<void*>(aligned_end), end - aligned_end);
  }
  madvise(reinterpret_cast<void*>(aligned), bytes, MADV_HUGEPAGE);
  return reinterpret_cast<void*>(aligned);
}

void unmap(void* block, std::size_t bytes) {
  munmap(block, bytes);
}

void* allocate_frame_buffer(std::size_t bytes, std::size_t align) {
  if (bytes < kMinMappedBytes) {
    return ::operator new(bytes, std::align_val_t(align));
  }
  if (bytes > std::numeric_limits<std::size_t>::max() - 2 * kHugePageBytes) {
    throw std::bad_alloc();  // round_up and map_aligned's padding would wrap
  }
  const std::size_t size = round_up(bytes, kPageBytes);
  BlockCache& c = cache();
  {
    const std::lock_guard<std::mutex> lock(c.mutex);
    for (int k = c.count - 1; k >= 0; --k) {
      // An arena's block is page-aligned, not huge-page-aligned: reused only where it is
      // aligned as asked.
      if (c.size[k] == size && reinterpret_cast<std::uintptr_t>(c.block[k]) % align == 0) {
        void* const block = c.block[k];
        for (int m = k; m + 1 < c.count; ++m) {
          c.block[m] = c.block[m + 1];
          c.size[m] = c.size[m + 1];
        }
        --c.count;
        c.bytes -= size;
        return block;
      }
    }
  }
  void* const block = size <= kHugePageBytes / 2 && align <= kPageBytes
                          ? arena_block(size)
                          : map_aligned(size, kHugePageBytes);
  populate(block, size);
  return block;
}

void free_frame_buffer(void* block, std::size_t bytes, std::size_t align) noexcept {
  if (block == nullptr) {
    return;
  }
  if (bytes < kMinMappedBytes) {
    ::operator delete(block, std::align_val_t(align));
    return;
  }
  const std::size_t size = round_up(bytes, kPageBytes);
  BlockCache& c = cache();
  {
    const std::lock_guard<std::mutex> lock(c.mutex);
    if (c.count < BlockCache::kEntries && c.bytes + size <= kMaxCachedBytes) {
      c.block[c.count] = block;
      c.size[c.count] = size;
      ++c.count;
      c.bytes += size;
      return;
    }
  }
  munmap(block, size);
}

void release_cached_frame_buffers() noexcept {
  BlockCache& c = cache();
  const std::lock_guard<std::mutex> lock(c.mutex);
  for (int k = 0; k < c.count; ++k) {
    munmap(c.block[k], c.size[k]);
  }
  c.count = 0;
  c.bytes = 0;
}

#else

void* allocate_frame_buffer(std::size_t bytes, std::size_t align) {
  return ::operator new(bytes, std::align_val_t(align));
}

void free_frame_buffer(void* block, std::size_t /*bytes*/, std::size_t align) noexcept {
  ::operator delete(block, std::align_val_t(align));
}

void release_cached_frame_buffers() noexcept {}

#endif

}  // namespace relief
