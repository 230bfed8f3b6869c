#include "core/frame_memory.h"

#include <new>

#ifdef RELIEF_FRAME_MAPPINGS
#include <sys/mman.h>

#include <cstdint>
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
  const std::size_t size = round_up(bytes, kPageBytes);
  BlockCache& c = cache();
  {
    const std::lock_guard<std::mutex> lock(c.mutex);
    for (int k = c.count - 1; k >= 0; --k) {
      if (c.size[k] == size) {
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
  return map_aligned(size, kHugePageBytes);
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
