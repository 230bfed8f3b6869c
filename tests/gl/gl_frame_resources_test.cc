// What GL frames keep between them (pipeline/gl_scene_cache.h) never changes a frame: a frame
// drawn from kept programs, streams and uploads has the bytes of a process's first frame, after
// any other scene and after a SceneResources was freed and another made in its place. A frame
// reads back only the outputs it asks for, and reports each GPU pass's time (--stats).
#include <algorithm>
#include <cmath>
#include <cstring>
#include <optional>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <catch2/catch.hpp>

#include "core/scene/scene_json.h"
#include "pipeline/frame.h"
#include "pipeline/gl_backend.h"
#include "pipeline/gl_scene_cache.h"
#include "pipeline/scene_resources.h"
#include "tests/support/cli_support.h"
#include "tests/support/test_support.h"

namespace relief {
namespace {

// Small frames: llvmpipe draws on the CPU.
const std::vector<std::string> kSmallGlFrame = {"viewport.width=96", "viewport.height=64",
                                                "grid.width=48", "grid.height=48"};

std::vector<std::string> small(std::vector<std::string> more) {
  std::vector<std::string> overrides = kSmallGlFrame;
  overrides.insert(overrides.end(), more.begin(), more.end());
  return overrides;
}

FrameRequest gl_request(bool every_output = true) {
  FrameRequest request;
  request.backend = Backend::kGl;
  if (every_output) {
    request.outputs = {true, true, true, true, true, true};
  }
  return request;
}

template <class T>
bool same_bytes(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() &&
         (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

// Every output byte for byte (floats by their bits: -0 is not 0 here).
bool same_image(const FrameImage& a, const FrameImage& b) {
  return a.width == b.width && a.height == b.height && same_bytes(a.srgb, b.srgb) &&
         same_bytes(a.linear, b.linear) && same_bytes(a.depth, b.depth) &&
         same_bytes(a.primitive, b.primitive) && same_bytes(a.normal, b.normal) &&
         same_bytes(a.world_height, b.world_height) && same_bytes(a.octaves, b.octaves);
}

struct Prepared {
  Scene scene;
  SceneResources resources;
};

Prepared prepare(const std::string& preset, const std::vector<std::string>& overrides) {
  Scene scene = resolve_scene(preset, small(overrides));
  SceneResources resources = load_scene_resources(scene);
  return {std::move(scene), std::move(resources)};
}

// The frame as a process's first GL frame draws it: nothing of an earlier scene kept.
FrameImage fresh_frame(const Scene& scene, const SceneResources& resources,
                       const FrameRequest& request = gl_request()) {
  forget_gl_scene();
  return render_frame(scene, resources, request).image;
}

FrameImage frame(const Scene& scene, const SceneResources& resources,
                 const FrameRequest& request = gl_request()) {
  return render_frame(scene, resources, request).image;
}

TEST_CASE("sceneResourcesSerialsNameTheirContents", "[gl]") {
  const Scene scene = resolve_scene("default", small({}));
  SceneResources a = load_scene_resources(scene);
  const SceneResources b = load_scene_resources(scene);
  CHECK(a.serial.value() != 0);
  CHECK(a.serial.value() != b.serial.value());  // equal contents, two objects
  SceneResources copy = a;                      // may be changed apart from `a`: its own serial
  CHECK(copy.serial.value() != a.serial.value());
  const std::uint64_t before = a.serial.value();
  SceneResources moved = std::move(a);  // the contents and their serial move together
  CHECK(moved.serial.value() == before);
  CHECK(a.serial.value() != before);  // NOLINT(bugprone-use-after-move): the serial is defined
  copy = moved;
  CHECK(copy.serial.value() != moved.serial.value());
  moved.contents_changed();
  CHECK(moved.serial.value() != before);
}

TEST_CASE("glFramesOfOneSceneHaveTheBytesOfAProcesssFirstFrame", "[gl]") {
  for (const char* preset : {"default", "island", "planet"}) {
    INFO(preset);
    const Prepared p = prepare(preset, {});
    const FrameImage first = fresh_frame(p.scene, p.resources);
    CHECK(same_image(frame(p.scene, p.resources), first));  // everything kept
    CHECK(same_image(frame(p.scene, p.resources), first));
    CHECK(same_image(fresh_frame(p.scene, p.resources), first));
  }
}

TEST_CASE("glFramesOfAnotherSceneInBetweenChangeNoByteOfTheFirstScenes", "[gl]") {
  const Prepared a = prepare("default", {});
  const FrameImage a_first = fresh_frame(a.scene, a.resources);
  // Another seed and lattice size; a grid of another size; another viewport; a sketch (other
  // stage-3 uploads); a planet (bent streams); the same scene loaded again (equal contents,
  // another SceneResources).
  const std::vector<std::pair<std::string, std::vector<std::string>>> others = {
      {"default", {"terrain.seed=7", "terrain.lattice_size=128"}},
      {"default", {"grid.width=40", "grid.height=56"}},
      {"default", {"viewport.width=80", "viewport.height=72"}},
      {"island", {}},
      {"planet", {}},
      {"default", {}},
  };
  for (const auto& [preset, overrides] : others) {
    const Prepared b = prepare(preset, overrides);
    INFO(preset << " " << Catch::StringMaker<std::vector<std::string>>::convert(overrides));
    CHECK(same_image(frame(a.scene, a.resources), a_first));
    const FrameImage b_after_a = frame(b.scene, b.resources);
    CHECK(same_image(frame(a.scene, a.resources), a_first));
    CHECK(same_image(frame(b.scene, b.resources), b_after_a));
    CHECK(same_image(fresh_frame(b.scene, b.resources), b_after_a));
  }
}

TEST_CASE("glFramesNeverDrawTheUploadsOfAFreedSceneResources", "[gl]") {
  // Each SceneResources is made in the same storage, after the one before was destroyed: its
  // address, and likely its arrays' addresses (same sizes), are the freed one's. Only the
  // seed differs, so every array has the freed one's size.
  const Scene scene = resolve_scene("default", small({}));
  std::optional<SceneResources> slot;
  std::vector<FrameImage> frames;
  const std::vector<std::string> seeds = {"1", "2", "3"};
  std::vector<Scene> scenes;
  std::vector<FrameImage> expected;  // a process's first frame, from resources made elsewhere
  for (const std::string& seed : seeds) {
    scenes.push_back(resolve_scene("default", small({"terrain.seed=" + seed})));
    const SceneResources separate = load_scene_resources(scenes.back());
    expected.push_back(fresh_frame(scenes.back(), separate));
  }
  // Nothing in between: each frame finds the uploads of the resources freed before it kept.
  const SceneResources* address = nullptr;
  for (std::size_t k = 0; k < seeds.size(); ++k) {
    slot.reset();
    slot.emplace(load_scene_resources(scenes[k]));
    CHECK((address == nullptr || address == &*slot));
    address = &*slot;
    frames.push_back(frame(scenes[k], *slot));
    INFO("seed " << seeds[k]);
    CHECK(same_image(frames.back(), expected[k]));
  }
  CHECK_FALSE(same_bytes(frames[0].srgb, frames[1].srgb));  // the seeds do change the frame
  CHECK_FALSE(same_bytes(frames[1].srgb, frames[2].srgb));
  // Contents changed in place, in the same arrays (same addresses and sizes: the key's guard
  // cannot see it), and said so: uploaded again by the serial alone.
  SceneResources changed = load_scene_resources(scene);
  const FrameImage before = frame(scene, changed);
  const GlResourceKey key_before = terrain_resource_key(changed);
  const Scene other = resolve_scene("default", small({"terrain.seed=2"}));
  const SceneResources other_resources = load_scene_resources(other);
  REQUIRE(other_resources.lattice.values.size() == changed.lattice.values.size());
  std::copy(other_resources.lattice.values.begin(), other_resources.lattice.values.end(),
            changed.lattice.values.begin());
  changed.contents_changed();
  CHECK(terrain_resource_key(changed).shape == key_before.shape);
  CHECK(terrain_resource_key(changed).serial != key_before.serial);
  CHECK(same_image(frame(scene, changed), fresh_frame(scene, changed)));
  CHECK_FALSE(same_bytes(frame(scene, changed).srgb, before.srgb));
}

// A frame whose targets exceed what the session keeps (pipeline/gl_backend.cc: 256 MiB, 56 bytes a
// pixel) frees them when it ends: the frames after it, of its size and of another, are the
// frames of a process that never drew it (and the sanitizer build sees no use of what was freed).
TEST_CASE("glFramesAfterOneTooLargeToKeepAreUnchanged", "[gl]") {
  const Prepared a = prepare("default", {});
  const FrameImage a_first = fresh_frame(a.scene, a.resources, gl_request(false));
  // 2300^2 pixels x 56 bytes = 296 MB; a small grid keeps llvmpipe's work to the background.
  const Prepared large = prepare("default", {"viewport.width=2300", "viewport.height=2300",
                                             "grid.width=16", "grid.height=16"});
  const FrameImage large_first = frame(large.scene, large.resources, gl_request(false));
  CHECK(same_image(frame(a.scene, a.resources, gl_request(false)), a_first));
  CHECK(same_image(frame(large.scene, large.resources, gl_request(false)), large_first));
  CHECK(same_image(fresh_frame(large.scene, large.resources, gl_request(false)), large_first));
}

TEST_CASE("glFramesReadBackOnlyTheOutputsTheyAskFor", "[gl]") {
  const Prepared p = prepare("lake", {});  // water, fog: every target holds something
  const FrameImage every = frame(p.scene, p.resources);
  const FrameImage srgb_only = frame(p.scene, p.resources, gl_request(false));
  CHECK(same_bytes(srgb_only.srgb, every.srgb));
  CHECK(srgb_only.srgb.size() == 3u * 96u * 64u);
  CHECK(srgb_only.linear.empty());
  CHECK(srgb_only.depth.empty());
  CHECK(srgb_only.primitive.empty());
  CHECK(srgb_only.normal.empty());
  CHECK(srgb_only.world_height.empty());
  CHECK(srgb_only.octaves.empty());
  // Each output alone: its bytes are those of the frame with every output (a target not
  // written changes no other).
  for (int k = 0; k < 6; ++k) {
    FrameRequest request = gl_request(false);
    bool* const flags[6] = {&request.outputs.linear,       &request.outputs.depth,
                            &request.outputs.primitive,    &request.outputs.normal,
                            &request.outputs.world_height, &request.outputs.octaves};
    *flags[k] = true;
    const FrameImage one = frame(p.scene, p.resources, request);
    INFO("output " << k);
    CHECK(same_bytes(one.srgb, every.srgb));
    CHECK(same_bytes(one.linear, k == 0 ? every.linear : std::vector<float>{}));
    CHECK(same_bytes(one.depth, k == 1 ? every.depth : std::vector<float>{}));
    CHECK(same_bytes(one.primitive, k == 2 ? every.primitive : std::vector<std::uint32_t>{}));
    CHECK(same_bytes(one.normal, k == 3 ? every.normal : std::vector<float>{}));
    CHECK(same_bytes(one.world_height, k == 4 ? every.world_height : std::vector<float>{}));
    CHECK(same_bytes(one.octaves, k == 5 ? every.octaves : std::vector<float>{}));
  }
}

// The passes of a plane frame without a sketch, in the order they run.
const std::vector<std::string> kPlanePasses = {
    "stage 2 (domain.comp)",
    "the octave reach (reach.comp)",
    "the coordinate forms (forms.comp)",
    "stage 3 (fbm.comp)",
    "stage 4 (surface.comp)",
    "triangle indices (triangles.comp)",
    "terrain (terrain.vert, terrain.frag)",
    "background (background.frag)",
    "read-back (CPU wall time)",
};

TEST_CASE("glFramesReportTheGpuTimeOfEveryPass", "[gl]") {
  const Prepared p = prepare("default", {});
  const Frame frame = render_frame(p.scene, p.resources, gl_request(false));
  std::vector<std::string> names;
  for (const StageTime& pass : frame.stats.gpu_passes) {
    INFO(pass.name << ": " << pass.ms << " ms");
    CHECK(std::isfinite(pass.ms));
    CHECK(pass.ms >= 0.0);
    names.push_back(pass.name);
  }
  CHECK(names == kPlanePasses);
  // The GPU passes run inside the frame, one after another: together no longer than it (the
  // read-back is the CPU's wall time, waiting included). Stage 3 does work: its time is not 0,
  // so swapped or unread queries (which read as 0) show.
  double gpu_ms = 0;
  for (const StageTime& pass : frame.stats.gpu_passes) {
    if (pass.name.find("read-back") == std::string::npos) {
      gpu_ms += pass.ms;
    }
    if (pass.name.find("fbm.comp") != std::string::npos) {
      CHECK(pass.ms > 0.0);
    }
  }
  CHECK(gpu_ms <= frame.stats.total_ms);
  // A CPU frame has none.
  FrameRequest cpu;
  cpu.backend = Backend::kSimd;
  CHECK(render_frame(p.scene, p.resources, cpu).stats.gpu_passes.empty());

  // relief render --stats prints each with its median time.
  const test::TempDir dir("gl-passes");
  std::vector<std::string> args = {"render",   "default", "--backend", "gl",
                                   "--repeat", "3",       "--stats"};
  for (const std::string& s : kSmallGlFrame) {
    args.push_back("--set");
    args.push_back(s);
  }
  args.push_back("-o");
  args.push_back((dir.path() / "gl.png").string());
  const test::CliResult result = test::run(args);
  INFO(result.out << result.err);
  REQUIRE(result.code == 0);
  const std::size_t heading = result.out.find("GL passes");
  REQUIRE(heading != std::string::npos);
  for (const std::string& name : kPlanePasses) {
    const std::size_t at = result.out.find(name, heading);
    REQUIRE(at != std::string::npos);
    std::istringstream line(result.out.substr(at + name.size()));
    double ms = -1.0;
    line >> ms;
    INFO(name);
    CHECK(line);
    CHECK(std::isfinite(ms));
    CHECK(ms >= 0.0);
  }
}

}  // namespace
}  // namespace relief
