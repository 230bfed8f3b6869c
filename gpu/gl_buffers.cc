#include "gpu/gl_buffers.h"

#include <cstring>
#include <stdexcept>
#include <string>

#include <epoxy/gl.h>

#include "gpu/gl_program.h"

namespace relief::gpu {

namespace {

// A buffer object of `bytes` rounded up to whole 4-byte words, holding `data`.
GLuint make_buffer(const void* data, std::size_t bytes, const char* what) {
  const std::size_t size = (bytes + 3) / 4 * 4;
  GLuint buffer = 0;
  glCreateBuffers(1, &buffer);
  glNamedBufferStorage(buffer, static_cast<GLsizeiptr>(size), nullptr, GL_DYNAMIC_STORAGE_BIT);
  glNamedBufferSubData(buffer, 0, static_cast<GLsizeiptr>(bytes), data);
  if (glGetError() != GL_NO_ERROR) {
    glDeleteBuffers(1, &buffer);
    throw std::runtime_error(std::string("gpu: no buffer of ") + std::to_string(size) +
                             " bytes for the " + what);
  }
  return buffer;
}

}  // namespace

GlGridUpload::GlGridUpload(const GridBuffers<float>& grid, std::span<const std::uint8_t> need) {
  try {
    upload(grid, need);
  } catch (...) {
    glDeleteBuffers(static_cast<GLsizei>(owned_.size()), owned_.data());
    throw;
  }
}

void GlGridUpload::upload(const GridBuffers<float>& grid, std::span<const std::uint8_t> need) {
  const std::size_t n = grid.layout.size();
  if (!need.empty() && need.size() != n) {
    throw std::invalid_argument("gpu: the need stream has " + std::to_string(need.size()) +
                                " entries; the grid has " + std::to_string(n) + " vertices");
  }
  streams_.layout = grid.layout;
  const auto floats = [&](const AlignedVector<float>& v, const char* what) {
    if (v.size() != n) {
      throw std::invalid_argument(std::string("gpu: the ") + what + " stream has " +
                                  std::to_string(v.size()) + " entries; the grid has " +
                                  std::to_string(n) + " vertices");
    }
    owned_.push_back(make_buffer(v.data(), n * sizeof(float), what));
    return owned_.back();
  };
  const bool bent = !grid.bent_x.empty();
  streams_.dx = bent ? floats(grid.bent_x, "bent x") : floats(grid.dx, "dx");
  streams_.dz = bent ? floats(grid.bent_z, "bent z") : floats(grid.dz, "dz");
  if (bent) {
    streams_.position_y = floats(grid.bent_y, "bent y");
    streams_.drop = floats(grid.bent_drop, "bent drop");
  }
  streams_.height = floats(grid.height, "height");
  streams_.nx = floats(grid.nx, "nx");
  streams_.ny = floats(grid.ny, "ny");
  streams_.nz = floats(grid.nz, "nz");
  streams_.slope = floats(grid.slope, "slope");
  streams_.water_depth = floats(grid.water_depth, "water depth");
  streams_.nu = floats(grid.nu, "nu");
  if (grid.valid.size() != n) {
    throw std::invalid_argument("gpu: the valid stream does not match the grid");
  }
  owned_.push_back(make_buffer(grid.valid.data(), n, "valid"));
  streams_.valid = owned_.back();
  if (!need.empty()) {
    owned_.push_back(make_buffer(need.data(), n, "need"));
    streams_.need = owned_.back();
  }
  check_gl("grid upload");
}

GlGridUpload::~GlGridUpload() {
  glDeleteBuffers(static_cast<GLsizei>(owned_.size()), owned_.data());
}

GlShadeResources::GlShadeResources(const ShadeResources& resources) {
  try {
    upload(resources);
  } catch (...) {
    glDeleteBuffers(1, &lattice_);
    glDeleteTextures(static_cast<GLsizei>(textures_.size()), textures_.data());
    glDeleteTextures(1, &skybox_);
    throw;
  }
}

void GlShadeResources::upload(const ShadeResources& resources) {
  if (resources.lattice == nullptr || resources.lattice->size <= 0) {
    throw std::invalid_argument("gpu: stage 8 needs the noise lattice");
  }
  const NoiseLattice& lattice = *resources.lattice;
  std::vector<std::uint8_t> bytes(16 + lattice.values.size() * sizeof(float));
  const std::int32_t header[4] = {lattice.size, lattice.mask, 0, 0};
  std::memcpy(bytes.data(), header, sizeof header);
  std::memcpy(bytes.data() + 16, lattice.values.data(), lattice.values.size() * sizeof(float));
  lattice_ = make_buffer(bytes.data(), bytes.size(), "noise lattice");
  for (const ProtoTexture& texture : resources.textures) {
    const auto levels = static_cast<GLsizei>(texture.levels.size());
    const int size = levels > 0 ? texture.levels[0].size : 0;
    if (levels == 0 || (1 << (levels - 1)) != size) {
      throw std::invalid_argument("gpu: a proto-texture needs its whole mip chain down to 1 x 1");
    }
    GLuint name = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &name);
    textures_.push_back(name);
    sizes_.push_back(size);
    glTextureStorage2D(name, levels, GL_RGB32F, size, size);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    for (GLsizei level = 0; level < levels; ++level) {
      const int side = texture.levels[static_cast<std::size_t>(level)].size;
      glTextureSubImage2D(name, level, 0, 0, side, side, GL_RGB, GL_FLOAT,
                          texture.level_texels(level));
    }
    // Only texelFetch reads it; a sampler state that makes the texture complete anyway.
    glTextureParameteri(name, GL_TEXTURE_MIN_FILTER, GL_NEAREST_MIPMAP_NEAREST);
    glTextureParameteri(name, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  }
  if (resources.skybox != nullptr) {
    const Skybox& box = *resources.skybox;
    if (box.size < 1 || box.texels.size() != 18 * std::size_t(box.size) * std::size_t(box.size)) {
      throw std::invalid_argument("gpu: the skybox needs six faces of size x size texels");
    }
    glCreateTextures(GL_TEXTURE_2D_ARRAY, 1, &skybox_);
    glTextureStorage3D(skybox_, 1, GL_RGB32F, box.size, box.size, 6);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTextureSubImage3D(skybox_, 0, 0, 0, 0, box.size, box.size, 6, GL_RGB, GL_FLOAT,
                        box.texels.data());
    // Only texelFetch reads it (sky.glsl).
    glTextureParameteri(skybox_, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(skybox_, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  }
  check_gl("shading resources upload");
}

GlShadeResources::~GlShadeResources() {
  glDeleteBuffers(1, &lattice_);
  glDeleteTextures(static_cast<GLsizei>(textures_.size()), textures_.data());
  glDeleteTextures(1, &skybox_);
}

}  // namespace relief::gpu
