// Storage for the set-up triangles of a frame (SetupChunk::triangles, bins.h): a few hundred
// kilobytes per chunk, tens of megabytes per frame, allocated afresh by every frame and written
// once. Fresh memory costs a page fault per 4 KiB page, which on the default frame cost about as
// much as setting the triangles up; this storage takes blocks from 2 MiB-aligned slabs that
// Linux may back with transparent huge pages (madvise), a fault per 2 MiB, and keeps up to
// 64 MiB of emptied slabs for the next frame (no fault at all). Small blocks, other
// systems and sanitizer builds take operator new. Where the memory lies never changes what is
// stored in it.
#pragma once

#include <cstddef>
#include <new>
#include <utility>

namespace relief::raster {

// Like operator new / operator delete (bad_alloc when no memory is left); `bytes` must be the
// same in both calls.
void* allocate_triangle_storage(std::size_t bytes);
void free_triangle_storage(void* block, std::size_t bytes) noexcept;

// Unmaps the emptied slabs kept for the next frame (eval/process_memory.h measures a job's
// resident memory from a clean start).
void release_spare_triangle_storage() noexcept;

template <class T>
struct TriangleStorageAllocator {
  using value_type = T;
  TriangleStorageAllocator() = default;
  template <class U>
  TriangleStorageAllocator(const TriangleStorageAllocator<U>&) {}  // NOLINT: allocator rebind
  T* allocate(std::size_t n) { return static_cast<T*>(allocate_triangle_storage(n * sizeof(T))); }
  void deallocate(T* p, std::size_t n) noexcept { free_triangle_storage(p, n * sizeof(T)); }
  // Default-initialisation (resize leaves trivial elements unwritten, to be written by the
  // caller); other constructions as usual.
  template <class U>
  void construct(U* p) {
    ::new (static_cast<void*>(p)) U;
  }
  template <class U, class... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
  template <class U>
  bool operator==(const TriangleStorageAllocator<U>&) const {
    return true;
  }
};

}  // namespace relief::raster
