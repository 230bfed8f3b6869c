// The ground truth's own error (eval/convergence.h, relief reference --converge): a truth
// against itself differs by nothing in every band; the bands partition the pixels into the sky
// and three runs of terrain by distance, nearest first; the distances are those of the samples'
// depths; a truth at twice the settings differs by a small, finite amount; and the command's
// refusals.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "core/scene/scene_json.h"
#include "eval/convergence.h"
#include "eval/ground_truth.h"
#include "pipeline/frame.h"
#include "tests/support/cli_support.h"
#include "tests/support/test_support.h"

namespace relief {
namespace {

Scene small_scene() {
  return resolve_scene(
      "badlands", {"viewport.width=64", "viewport.height=48", "grid.width=32", "grid.height=32"});
}

GroundTruthSettings small_settings() {
  GroundTruthSettings s;
  s.supersample = 2;
  s.grid_scale = 1;
  s.octave_epsilon = 0.5;
  s.distances = true;
  return s;
}

TEST_CASE("convergenceBandsPartitionThePixelsByDistance", "[ground-truth]") {
  const Scene scene = small_scene();
  const SceneResources resources = load_scene_resources(scene);
  const GroundTruthImage base = render_ground_truth(scene, resources, small_settings());
  REQUIRE(base.distance.size() == std::size_t(64 * 48));
  // The distances: of the supersampled frame's depths, near / depth, where most samples see
  // terrain (an independent render of the supersampled frame's depth).
  FrameRequest request;
  request.backend = Backend::kReferenceDouble;
  request.outputs.depth = true;
  request.octave_count_rule = distance_lod_rule(base.lod.lod);
  const Frame big = render_frame(supersampled_scene(scene, small_settings()), resources, request);
  for (int y = 0; y < 48; ++y) {
    for (int x = 0; x < 64; ++x) {
      double sum = 0;
      int terrain = 0;
      for (int s = 0; s < 4; ++s) {
        const float depth = big.image.depth[std::size_t((2 * y + s / 2) * 128 + 2 * x + s % 2)];
        if (depth > 0) {
          sum += scene.camera.near / double(depth);
          ++terrain;
        }
      }
      const float expected = terrain >= 2 ? float(sum / terrain) : 0.0f;
      REQUIRE(base.distance[std::size_t(y * 64 + x)] == expected);
    }
  }
  const std::vector<int> bands = distance_bands(base);
  std::vector<int> count(kDistanceBands, 0);
  std::vector<float> lo(kDistanceBands, INFINITY), hi(kDistanceBands, 0.0f);
  for (std::size_t k = 0; k < bands.size(); ++k) {
    REQUIRE((bands[k] >= 0 && bands[k] < kDistanceBands));
    CHECK((bands[k] == 0) == (base.distance[k] == 0.0f));
    ++count[bands[k]];
    lo[bands[k]] = std::min(lo[bands[k]], base.distance[k]);
    hi[bands[k]] = std::max(hi[bands[k]], base.distance[k]);
  }
  CHECK(count[0] > 0);  // badlands' sky
  CHECK(count[2] == count[3]);
  CHECK((count[1] - count[2] >= 0 && count[1] - count[2] <= 2));
  CHECK(hi[1] <= lo[2]);
  CHECK(hi[2] <= lo[3]);

  // Against itself: no difference anywhere.
  const ConvergenceReport same = compare_truths(base, base, small_settings());
  CHECK(same.all.mean_flip == 0.0);
  CHECK(std::isinf(same.all.psnr_db));
  for (int b = 0; b < kDistanceBands; ++b) {
    CHECK(same.bands[std::size_t(b)].pixels == std::size_t(count[b]));
    CHECK(same.bands[std::size_t(b)].mean_flip == 0.0);
  }
  // Against twice the settings: a finite difference, the doubled settings reported.
  const GroundTruthImage finer =
      render_ground_truth(scene, resources, doubled_settings(small_settings()));
  const ConvergenceReport r = compare_truths(base, finer, small_settings());
  CHECK(r.doubled.supersample == 4);
  CHECK(r.doubled.grid_scale == 2);
  CHECK(r.doubled.octave_epsilon == 0.25);
  CHECK(r.all.mean_flip > 0.0);
  CHECK(r.all.mean_flip < 0.5);
  CHECK(std::isfinite(r.all.psnr_db));
}

TEST_CASE("referenceConvergeWritesItsFiguresAndRefusesWhatItCannotDouble", "[ground-truth]") {
  test::TempDir dir("converge");
  const auto file = [&](const std::string& name) { return (dir.path() / name).string(); };
  const std::vector<std::string> small = {
      "reference", "badlands",           "--set",        "viewport.width=64",
      "--set",     "viewport.height=48", "--set",        "grid.width=32",
      "--set",     "grid.height=32",     "--grid-scale", "1"};
  // --supersample 2 --octave-epsilon 0.5 unless `extra` gives its own.
  const auto with = [&](std::vector<std::string> extra) {
    std::vector<std::string> a = small;
    if (std::find(extra.begin(), extra.end(), "--supersample") == extra.end()) {
      a.insert(a.end(), {"--supersample", "2"});
    }
    if (std::find(extra.begin(), extra.end(), "--octave-epsilon") == extra.end()) {
      a.insert(a.end(), {"--octave-epsilon", "0.5"});
    }
    a.insert(a.end(), extra.begin(), extra.end());
    return test::run(a);
  };
  const test::CliResult r = with({"--converge", "--json", file("c.json"), "-o", file("r.png")});
  INFO(r.err);
  REQUIRE(r.code == 0);
  CHECK(r.out.find("far third") != std::string::npos);
  const std::vector<unsigned char> bytes = test::read_bytes(file("c.json"));
  const nlohmann::json json = nlohmann::json::parse(bytes.begin(), bytes.end());
  CHECK(json["doubled"]["supersample"] == 4);
  REQUIRE(json["bands"].size() == 4);
  std::size_t pixels = 0;
  for (const auto& band : json["bands"]) {
    pixels += band["pixels"].get<std::size_t>();
    CHECK(band["mean_flip"].get<double>() >= 0.0);
  }
  CHECK(pixels == 64 * 48);
  // The same first image as without --converge: the check does not change the truth.
  REQUIRE(with({"-o", file("plain.png")}).code == 0);
  CHECK(test::read_bytes(file("r.png")) == test::read_bytes(file("plain.png")));
  test::require_refused(with({"--json", file("j.json"), "-o", file("x.png")}),
                        "give --converge too", file("x.png"));
  test::require_refused(with({"--converge", "--shard", "0/1", "-o", file("x.png")}),
                        "leave out --shard", file("x.png"));
  test::require_refused(
      with({"--converge", "--supersample", "16", "-o", file("x.png")}),
      "--supersample 16 leaves no room for --converge, which renders at twice it; allowed 1...8",
      file("x.png"));
  test::require_refused(with({"--converge", "--octave-epsilon", "1.5e-6", "-o", file("x.png")}),
                        "--octave-epsilon 1.5e-06 leaves no room", file("x.png"));
  // A viewport too wide to double at all is named as the problem, not "allowed 1...0".
  test::require_refused(with({"--converge", "--supersample", "1", "--set", "viewport.width=9000",
                              "--set", "viewport.height=9000", "-o", file("x.png")}),
                        "viewport leaves no room", file("x.png"));
  // The user's own value out of range is named as it is, without --converge's doubling.
  test::require_refused(with({"--converge", "--supersample", "17", "-o", file("x.png")}),
                        "--supersample 17 is out of range; allowed 1...16", file("x.png"));
  test::require_refused(with({"--converge", "--json", "", "-o", file("x.png")}), "--json is empty",
                        file("x.png"));
  // An output that cannot be written is found before the slow render.
  test::require_refused(with({"--converge", "-o", file("missing/x.png")}), "does not exist",
                        file("missing/x.png"));
  test::require_refused(
      with({"--converge", "--json", file(std::string(300, 'j') + ".json"), "-o", file("x.png")}),
      "the file system allows at most 255", file("x.png"));
  test::require_refused(with({"--converge", "--json", file("r.png"), "-o", file("r.png")}),
                        "same file", file("nothing"));
}

}  // namespace
}  // namespace relief
