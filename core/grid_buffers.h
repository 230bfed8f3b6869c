// Structure-of-arrays buffers for the grid stages: one planar array per field, each row
// padded to a whole number of widest vectors and 64-byte aligned (as Highway's planar images are),
// so a kernel may always load full vectors. Index of vertex (i, j) = j * pitch + i; padding entries
// hold finite, unused values (valid = 0).
#pragma once

#include <cstddef>
#include <cstdint>
#include <new>
#include <span>
#include <vector>

#include "core/frame_memory.h"
#include "core/limits.h"

namespace relief {

template <class T>
struct AlignedAllocator {
  using value_type = T;
  AlignedAllocator() = default;
  template <class U>
  AlignedAllocator(const AlignedAllocator<U>&) {}  // NOLINT: allocator rebind
  // Large buffers are kept for the next frame (core/frame_memory.h).
  T* allocate(std::size_t n) {
    return static_cast<T*>(allocate_frame_buffer(n * sizeof(T), limits::kBufferAlignBytes));
  }
  void deallocate(T* p, std::size_t n) {
    free_frame_buffer(p, n * sizeof(T), limits::kBufferAlignBytes);
  }
  template <class U>
  bool operator==(const AlignedAllocator<U>&) const {
    return true;
  }
};

template <class T>
using AlignedVector = std::vector<T, AlignedAllocator<T>>;

struct GridLayout {
  int width = 0;
  int height = 0;
  int pitch = 0;  // width rounded up to kRowAlignFloats

  std::size_t size() const { return static_cast<std::size_t>(pitch) * height; }
  std::size_t index(int i, int j) const { return static_cast<std::size_t>(j) * pitch + i; }
};

inline GridLayout make_grid_layout(int width, int height) {
  const int align = limits::kRowAlignFloats;
  return GridLayout{width, height, (width + align - 1) / align * align};
}

// Rows [begin, end) of a grid: the unit of work of the grid stages.
struct RowRange {
  int begin = 0;
  int end = 0;
};

// Elements [begin, end) of a flat buffer: the unit of work of element-wise stages.
struct IndexRange {
  std::size_t begin = 0;
  std::size_t end = 0;
};

// Outputs of stage 2.
template <class Real>
struct DomainSpans {
  std::span<Real> dx;  // camera-relative base-domain position, world units
  std::span<Real> dz;
  std::span<Real> sigma;  // local grid spacing, world units
  std::span<Real> nu;     // octave count in [1, N]
  std::span<std::uint8_t> valid;
};

// Outputs of stage 4.
template <class Real>
struct SurfaceSpans {
  std::span<Real> nx;  // unit normal
  std::span<Real> ny;
  std::span<Real> nz;
  std::span<Real> slope;        // |grad h|, rise over run
  std::span<Real> water_depth;  // max(0, water level - h); 0 without water
};

// The bend of a planet frame (core/planet_bend.h): camera-relative positions on the sphere,
// and how far each lies below its unbent height (what stage 8 subtracts).
template <class Real>
struct BentSpans {
  std::span<Real> x, y, z, drop;
};

// Every per-vertex field of stages 2-4.
template <class Real>
struct GridBuffers {
  GridLayout layout;
  AlignedVector<Real> dx, dz, sigma, nu;
  AlignedVector<std::uint8_t> valid;
  AlignedVector<Real> height;
  AlignedVector<Real> nx, ny, nz, slope, water_depth;
  // A planet frame's bent positions (allocate_bent); empty on the plane.
  AlignedVector<Real> bent_x, bent_y, bent_z, bent_drop;

  explicit GridBuffers(GridLayout grid)
      : layout(grid),
        dx(grid.size()),
        dz(grid.size()),
        sigma(grid.size()),
        nu(grid.size()),
        valid(grid.size()),
        height(grid.size()),
        nx(grid.size()),
        ny(grid.size()),
        nz(grid.size()),
        slope(grid.size()),
        water_depth(grid.size()) {}

  DomainSpans<Real> domain() { return {dx, dz, sigma, nu, valid}; }
  SurfaceSpans<Real> surface() { return {nx, ny, nz, slope, water_depth}; }
  BentSpans<Real> bent() { return {bent_x, bent_y, bent_z, bent_drop}; }
  void allocate_bent() {
    for (AlignedVector<Real>* v : {&bent_x, &bent_y, &bent_z, &bent_drop}) {
      v->resize(layout.size());
    }
  }
};

}  // namespace relief
