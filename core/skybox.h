// A skybox (Mekala's seed, sky.skybox): six square images on the faces of a cube about the
// camera, in place of the sky's gradient (sky.h). A direction is looked up as OpenGL looks up
// a cube map (OpenGL 4.5 §8.13, Table 8.19): the component of largest magnitude picks the face,
// the other two divided by it give (s, t) on that face, and the face is filtered bilinearly
// with its edges clamped (GL_LINEAR, GL_CLAMP_TO_EDGE, no seamless filtering across faces).
// The same files a GL application binds as GL_TEXTURE_CUBE_MAP_POSITIVE_X ... _NEGATIVE_Z,
// each uploaded top row first, show the same sky here.
#pragma once

#include <array>
#include <vector>

#include "core/vec3.h"

namespace relief {

// The faces' texels: linear RGB (the sRGB decode rounded to float) times sky.skybox.intensity,
// rounded to float again. Face f
// (+x, -x, +y, -y, +z, -z), row r (0: the image's top row, t = 0), column c (s = 0) at
// texels[3 ((f size + r) size + c)].
struct Skybox {
  int size = 0;
  std::vector<float> texels;

  const float* texel(int face, int row, int column) const {
    return texels.data() + 3 * ((std::size_t(face) * size + row) * size + column);
  }
};

// Where a direction meets the cube: the face (0 ... 5 as above) and the face's coordinates
// s, t in [0, 1] (s = (sc / |ma| + 1) / 2, t likewise, Table 8.19). Ties between components of
// equal magnitude, which GL leaves to the implementation, go to x, then y. A direction that is
// zero, infinite or has a NaN (outside the domain: the callers pass unit vectors) reads the +x
// face's centre, so that nothing undefined leaves.
template <class Real>
struct CubeFaceCoordinate {
  int face = 0;
  Real s = 0, t = 0;
};
template <class Real>
CubeFaceCoordinate<Real> cube_face_coordinate(const Vec3<Real>& d);

// The faces' bilinear radiance in direction `d` (cube_face_coordinate, then the face filtered
// at (s size - 1/2, t size - 1/2) texels, neighbours past an edge clamped to it).
template <class Real>
Vec3<Real> skybox_radiance(const Skybox& box, const Vec3<Real>& d);

}  // namespace relief
