// GlTerrain's streams to and from the CPU: the need flags, a stream's upload and read-back,
// and stage 3's parameters as the GPU holds them (gl_terrain.h).
#include <stdexcept>
#include <string>

#include <epoxy/gl.h>

#include "gpu/gl_checks.h"
#include "gpu/gl_terrain.h"

namespace relief::gpu {

namespace {

void upload_bytes(const GlName& buffer, const void* data, std::size_t bytes) {
  glNamedBufferSubData(buffer.get(), 0, static_cast<GLsizeiptr>(bytes), data);
}

}  // namespace

void GlTerrain::set_need(std::span<const std::uint8_t> need) {
  require_context("set_need");
  if (need.empty()) {
    use_need_ = false;
    return;
  }
  require_grid_size("GlTerrain::set_need", "the need flags' count", need.size(), layout_.size());
  if (need_.get() == 0) {
    need_ = make_storage_buffer(layout_.size(), "the need flags");
  }
  upload_bytes(need_, need.data(), need.size());
  check_gl("uploading the need flags");
  use_need_ = true;
}

void GlTerrain::check_stream_size(const char* who, GlStream stream, std::size_t count) const {
  require_grid_size(
      who, (std::string("the size of stream ") + std::string(gl_stream_name(stream))).c_str(),
      count, layout_.size());
}

void GlTerrain::upload(GlStream stream, std::span<const float> values) {
  require_context("upload");
  if (stream == GlStream::kValid) {
    throw std::invalid_argument("GlTerrain::upload: the valid stream holds bytes (upload_valid)");
  }
  check_stream_size("GlTerrain::upload", stream, values.size());
  upload_bytes(streams_[static_cast<int>(stream)], values.data(), values.size_bytes());
  check_gl("uploading stream " + std::string(gl_stream_name(stream)));
}

void GlTerrain::upload_valid(std::span<const std::uint8_t> valid) {
  require_context("upload_valid");
  check_stream_size("GlTerrain::upload_valid", GlStream::kValid, valid.size());
  upload_bytes(streams_[static_cast<int>(GlStream::kValid)], valid.data(), valid.size());
  check_gl("uploading stream valid");
}

void GlTerrain::read(GlStream stream, std::span<float> out) const {
  require_context("read");
  if (stream == GlStream::kValid) {
    throw std::invalid_argument("GlTerrain::read: the valid stream holds bytes (read_valid)");
  }
  check_stream_size("GlTerrain::read", stream, out.size());
  glGetNamedBufferSubData(buffer(stream), 0, static_cast<GLsizeiptr>(out.size_bytes()), out.data());
  check_gl("reading stream " + std::string(gl_stream_name(stream)));
}

void GlTerrain::read_valid(std::span<std::uint8_t> out) const {
  require_context("read_valid");
  check_stream_size("GlTerrain::read_valid", GlStream::kValid, out.size());
  glGetNamedBufferSubData(buffer(GlStream::kValid), 0, static_cast<GLsizeiptr>(out.size()),
                          out.data());
  check_gl("reading stream valid");
}

void GlTerrain::read_all(GridBuffers<float>& out) const {
  require_grid_size("GlTerrain::read_all", "GridBuffers::layout.pitch", out.layout.pitch,
                    layout_.pitch);
  require_grid_size("GlTerrain::read_all", "GridBuffers::layout.height", out.layout.height,
                    layout_.height);
  read(GlStream::kDx, out.dx);
  read(GlStream::kDz, out.dz);
  read(GlStream::kSigma, out.sigma);
  read(GlStream::kNu, out.nu);
  read_valid(out.valid);
  read(GlStream::kHeight, out.height);
  read(GlStream::kNx, out.nx);
  read(GlStream::kNy, out.ny);
  read(GlStream::kNz, out.nz);
  read(GlStream::kSlope, out.slope);
  read(GlStream::kWaterDepth, out.water_depth);
  if (!out.bent_x.empty() && buffer(GlStream::kBentX) != 0) {
    read(GlStream::kBentX, out.bent_x);
    read(GlStream::kBentY, out.bent_y);
    read(GlStream::kBentZ, out.bent_z);
    read(GlStream::kBentDrop, out.bent_drop);
  }
}

FbmParams<float> GlTerrain::fbm_params() const {
  require_context("fbm_params");
  FbmParams<float> params;
  glGetNamedBufferSubData(fbm_params_.get(), 0, sizeof params, &params);
  check_gl("reading stage 3's parameters");
  return params;
}

unsigned int GlTerrain::buffer(GlStream stream) const {
  return streams_[static_cast<int>(stream)].get();
}

}  // namespace relief::gpu
