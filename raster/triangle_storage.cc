#include "raster/triangle_storage.h"

#include <new>

#include "core/frame_memory.h"

#ifdef RELIEF_FRAME_MAPPINGS
#include <cstdint>
#include <mutex>
#endif

namespace relief::raster {

#ifdef RELIEF_FRAME_MAPPINGS
namespace {

constexpr std::size_t kHugePage = kHugePageBytes;
constexpr std::size_t kSlabBytes = 4 * kHugePage;           // aligned to its size
constexpr std::size_t kSmallBytes = std::size_t{64} << 10;  // below: operator new
constexpr std::size_t kBlockAlign = 64;
constexpr std::size_t kHeaderBytes = 64;  // a SlabHeader at the slab's start
constexpr std::size_t kLargestSlabBlock = kSlabBytes - kHeaderBytes;  // above: its own mapping

// Blocks are carved from the current slab in turn and never reused one by one; a slab is
// unmapped when its last block is freed (a frame's chunks are freed together).
struct SlabHeader {
  std::size_t used;  // bytes carved, header included
  std::size_t live;  // blocks not yet freed
};

// Emptied slabs kept mapped for the next frame (up to kSpareSlabs, 64 MiB): a frame's
// triangles take tens of megabytes, and a new mapping costs a fault and the kernel zeroing
// 2 MiB per huge page, about a quarter of the set-up's time when every frame maps afresh. The
// rest are unmapped.
constexpr std::size_t kSpareSlabs = 8;

struct Slabs {
  std::mutex mutex;
  SlabHeader* current = nullptr;
  SlabHeader* spare[kSpareSlabs] = {};
  std::size_t spare_count = 0;
};

Slabs& slabs() {
  static Slabs* const state = new Slabs;  // never destroyed: blocks may outlive statics
  return *state;
}

std::size_t round_up(std::size_t n, std::size_t multiple) {
  return (n + multiple - 1) / multiple * multiple;
}

}  // namespace
#endif

void* allocate_triangle_storage(std::size_t bytes) {
#ifdef RELIEF_FRAME_MAPPINGS
  if (bytes > kLargestSlabBlock) {
    return map_aligned(round_up(bytes, kPageBytes), kHugePage);
  }
  if (bytes >= kSmallBytes) {
    const std::size_t size = round_up(bytes, kBlockAlign);
    Slabs& s = slabs();
    const std::lock_guard<std::mutex> lock(s.mutex);
    if (s.current == nullptr || s.current->used + size > kSlabBytes) {
      // The current slab (if any) stays mapped while it has live blocks.
      s.current = s.spare_count > 0 ? s.spare[--s.spare_count]
                                    : static_cast<SlabHeader*>(map_aligned(kSlabBytes, kSlabBytes));
      s.current->used = kHeaderBytes;
      s.current->live = 0;
    }
    char* const block = reinterpret_cast<char*>(s.current) + s.current->used;
    s.current->used += size;
    ++s.current->live;
    return block;
  }
#endif
  return ::operator new(bytes);
}

void free_triangle_storage(void* block, [[maybe_unused]] std::size_t bytes) noexcept {
#ifdef RELIEF_FRAME_MAPPINGS
  if (bytes > kLargestSlabBlock) {
    unmap(block, round_up(bytes, kPageBytes));
    return;
  }
  if (bytes >= kSmallBytes) {
    auto* const slab = reinterpret_cast<SlabHeader*>(reinterpret_cast<std::uintptr_t>(block) &
                                                     ~(std::uintptr_t{kSlabBytes} - 1));
    Slabs& s = slabs();
    const std::lock_guard<std::mutex> lock(s.mutex);
    if (--slab->live == 0) {
      if (slab == s.current) {
        s.current = nullptr;
      }
      if (s.spare_count < kSpareSlabs) {
        s.spare[s.spare_count++] = slab;
      } else {
        unmap(slab, kSlabBytes);
      }
    }
    return;
  }
#endif
  ::operator delete(block);
}

void release_spare_triangle_storage() noexcept {
#ifdef RELIEF_FRAME_MAPPINGS
  Slabs& s = slabs();
  const std::lock_guard<std::mutex> lock(s.mutex);
  for (std::size_t k = 0; k < s.spare_count; ++k) {
    unmap(s.spare[k], kSlabBytes);
  }
  s.spare_count = 0;
#endif
}

}  // namespace relief::raster
