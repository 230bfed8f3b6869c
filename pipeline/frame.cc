#include "pipeline/frame.h"

#include <chrono>

#include "pipeline/memory_budget.h"
#include "pipeline/render_frame.h"

namespace relief {

std::string_view backend_name(Backend backend) {
  return backend == Backend::kReference ? "reference" : "reference-double";
}

std::optional<Backend> backend_from_name(std::string_view name) {
  for (Backend b : {Backend::kReference, Backend::kReferenceDouble}) {
    if (backend_name(b) == name) {
      return b;
    }
  }
  return std::nullopt;
}

std::vector<std::string_view> backend_names() {
  return {backend_name(Backend::kReference), backend_name(Backend::kReferenceDouble)};
}

Frame render_frame(const Scene& scene, const SceneResources& resources,
                   const FrameRequest& request) {
  if (request.backend != Backend::kReference) {
    throw MemoryLimitError("the reference-double backend is not wired yet");
  }
  const auto start = std::chrono::steady_clock::now();
  FrameTimings t;
  RenderedImage rendered = render_frame(scene, resources, t, {request.max_bin_bytes});
  Frame frame;
  frame.image.width = rendered.width;
  frame.image.height = rendered.height;
  frame.image.srgb = std::move(rendered.rgb);
  if (request.outputs.linear) {
    frame.image.linear = std::move(rendered.linear);
  }
  frame.stats.stages = {{"projected domain", t.terrain.projected_domain_ms},
                        {"fractal", t.terrain.fbm_ms},
                        {"surface", t.terrain.surface_ms},
                        {"vertex transform", t.transform_ms},
                        {"rasterisation", t.raster_ms},
                        {"resolve", t.resolve_ms},
                        {"shading", t.shade_ms},
                        {"sRGB encoding", t.encode_ms}};
  frame.stats.raster = t.raster;
  frame.stats.total_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return frame;
}

}  // namespace relief
