// relief sweep (eval/sweep.h, tools/sweep_command.cc): the Pareto front's properties, a
// quick sweep of a tiny scene (every configuration measured, finite figures, the default
// marked, the accuracy knobs acting the right way), and bad options refused with nothing
// written.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include <catch2/catch.hpp>

#include "core/scene/scene_json.h"
#include "eval/ground_truth.h"
#include "eval/pareto.h"
#include "eval/sweep.h"
#include "tests/support/cli_support.h"
#include "tests/support/test_support.h"

namespace relief {
namespace {

// The Pareto properties: no front point is dominated by any point, and every point off the
// front is dominated by a point on it.
void require_pareto_properties(const std::vector<ParetoPoint>& points) {
  const std::vector<bool> front = pareto_front(points);
  REQUIRE(front.size() == points.size());
  for (std::size_t k = 0; k < points.size(); ++k) {
    bool dominated = false, dominated_by_front = false;
    for (std::size_t j = 0; j < points.size(); ++j) {
      if (dominates(points[j], points[k])) {
        dominated = true;
        dominated_by_front = dominated_by_front || front[j];
      }
    }
    INFO("point " << k << ": " << points[k].time << ", " << points[k].error);
    CHECK(front[k] == !dominated);
    if (!front[k]) {
      CHECK(dominated_by_front);
    }
  }
}

TEST_CASE("aPointDominatedByLessThanTheMeasurementResolvesIsNotClearlyDominated", "[sweep]") {
  const ParetoPoint base{100.0, 0.2};
  CHECK(dominates_beyond({90.0, 0.2}, base, 0.03, 0.005));           // 10 % faster
  CHECK(dominates_beyond({100.0, 0.19}, base, 0.03, 0.005));         // 5 % less error
  CHECK_FALSE(dominates_beyond({99.0, 0.1999}, base, 0.03, 0.005));  // within both
  CHECK(dominates({99.0, 0.1999}, base));
  CHECK_FALSE(dominates_beyond({90.0, 0.21}, base, 0.03, 0.005));  // faster but worse
  CHECK_FALSE(dominates_beyond(base, base, 0.0, 0.0));             // equal points
}

TEST_CASE("paretoFrontKeepsExactlyTheUndominatedPoints", "[sweep]") {
  // Hand-made: (1, 5) (2, 3) (4, 1) on the front; (3, 4) dominated by (2, 3); (2, 6) by (1, 5)
  // and (2, 3); (4, 2) by (4, 1) (equal time, lower error); (5, 1) by (4, 1).
  const std::vector<ParetoPoint> points = {{1, 5}, {3, 4}, {2, 3}, {2, 6}, {4, 1}, {4, 2}, {5, 1}};
  const std::vector<bool> front = pareto_front(points);
  CHECK(front == std::vector<bool>{true, false, true, false, true, false, false});
  require_pareto_properties(points);

  // Ties: equal points dominate neither other, so both copies of a front point stay on it.
  const std::vector<ParetoPoint> ties = {{1, 1}, {1, 1}, {2, 2}, {2, 2}, {1, 2}, {2, 1}};
  CHECK(pareto_front(ties) == std::vector<bool>{true, true, false, false, false, false});
  require_pareto_properties(ties);

  CHECK(pareto_front(std::vector<ParetoPoint>{}).empty());
  CHECK(pareto_front(std::vector<ParetoPoint>{{3, 3}}) == std::vector<bool>{true});

  // Random clouds on a coarse lattice, so that ties in one or both figures are frequent.
  test::TestRandom random(12);
  for (int cloud = 0; cloud < 50; ++cloud) {
    std::vector<ParetoPoint> cloud_points;
    for (int k = 0; k < 40; ++k) {
      cloud_points.push_back({std::floor(random.uniform(0, 8)), std::floor(random.uniform(0, 8))});
    }
    require_pareto_properties(cloud_points);
  }
}

// 64 x 48 pixels, a 32 x 32 grid: the quick plan varies it to 16 and 64.
const std::vector<std::string> kTinyScene = {
    "--set", "viewport.width=64", "--set", "viewport.height=48",
    "--set", "grid.width=32",     "--set", "grid.height=32"};

std::vector<std::string> split_csv_line(const std::string& line) {
  std::vector<std::string> fields;
  std::string field;
  std::istringstream in(line);
  while (std::getline(in, field, ',')) {
    fields.push_back(field);
  }
  return fields;
}

TEST_CASE("quickSweepOfATinySceneMeasuresEveryConfiguration", "[sweep][cli]") {
  test::TempDir dir("sweep");
  const std::filesystem::path out = dir.path() / "out";
  std::vector<std::string> args = {"sweep"};
  args.insert(args.end(), kTinyScene.begin(), kTinyScene.end());
  args.insert(args.end(), {"--out", out.string(), "--quick", "--repeat", "1",
                           "--reference-supersample", "2", "--reference-grid-scale", "2"});
  const test::CliResult r = test::run(args);
  INFO(r.out << r.err);
  REQUIRE(r.code == kExitOk);

  const Scene scene = resolve_scene(
      "default", {"viewport.width=64", "viewport.height=48", "grid.width=32", "grid.height=32"});
  const SweepPlan plan = plan_sweep(scene, true, std::nullopt);
  REQUIRE(plan.configurations.size() == 9);

  std::ifstream csv(out / "sweep.csv");
  std::string line;
  REQUIRE(std::getline(csv, line));
  CHECK(line ==
        "name,knob,value,backend,supersample,median_ms,psnr_db,rmse,max_error,mean_flip,"
        "height_max,height_rms,on_pareto_front,is_default");
  struct Row {
    std::string name, backend;
    int supersample;
    double flip, rmse, height_max;
    bool front, is_default;
  };
  std::vector<Row> rows;
  while (std::getline(csv, line)) {
    const std::vector<std::string> f = split_csv_line(line);
    REQUIRE(f.size() == 14);
    INFO(line);
    for (int k = 5; k <= 11; ++k) {
      CHECK(std::isfinite(std::stod(f[k])));
    }
    // Every figure is non-negative by construction (a time, a square root, a largest absolute
    // value); what the columns can get wrong is their order and their link: PSNR is
    // 20 log10(1 / RMSE) of the same row (both printed with 9 significant digits), and a time
    // was measured (a configuration that did not run would print 0).
    CHECK(std::stod(f[5]) > 0);
    CHECK(std::stod(f[6]) == Approx(20.0 * std::log10(1.0 / std::stod(f[7]))).margin(1e-6));
    rows.push_back({f[0], f[3], std::stoi(f[4]), std::stod(f[9]), std::stod(f[7]), std::stod(f[10]),
                    f[12] == "1", f[13] == "1"});
  }
  REQUIRE(rows.size() == plan.configurations.size());
  for (std::size_t k = 0; k < rows.size(); ++k) {
    CHECK(rows[k].name == plan.configurations[k].name);
  }
  CHECK(std::count_if(rows.begin(), rows.end(), [](const Row& row) { return row.is_default; }) ==
        1);
  CHECK(rows[0].is_default);
  CHECK(std::any_of(rows.begin(), rows.end(), [](const Row& row) { return row.front; }));
  const auto find = [&](const std::string& name) {
    const auto it =
        std::find_if(rows.begin(), rows.end(), [&](const Row& row) { return row.name == name; });
    REQUIRE(it != rows.end());
    return *it;
  };
  // reference-double's heights are the double ones; the float backend's are a rounding away.
  CHECK(find("reference-double").height_max == 0);
  CHECK(rows[0].height_max > 0);
  CHECK(rows[0].height_max < 1e-3 * scene.terrain.amplitude);
  // Supersampling moves the real-time frame toward the box-filtered reference.
  CHECK(find("2x2 samples").rmse < rows[0].rmse);
  CHECK(find("2x2 samples").flip < rows[0].flip);

  for (const char* name : {"reference.png", "reference.exr", "sweep.gp", "sweep.png"}) {
    CHECK(std::filesystem::exists(out / name));
  }
  // make test installs gnuplot-nox: the plot is required, not optional, here.
  const std::vector<unsigned char> png = test::read_bytes(out / "sweep.png");
  REQUIRE(png.size() > 8);
  CHECK(png[1] == 'P');
  CHECK(png[2] == 'N');
  CHECK(png[3] == 'G');
  CHECK_THAT(r.out, Catch::Matchers::Contains("(default)"));

  // The reference reused: the same figures (the sweep is deterministic but for its times).
  const std::filesystem::path again = dir.path() / "again";
  std::vector<std::string> reuse = {"sweep"};
  reuse.insert(reuse.end(), kTinyScene.begin(), kTinyScene.end());
  reuse.insert(reuse.end(), {"--out", again.string(), "--quick", "--repeat", "1", "--reference",
                             (out / "reference.exr").string()});
  const test::CliResult r2 = test::run(reuse);
  INFO(r2.err);
  REQUIRE(r2.code == kExitOk);
  std::ifstream first(out / "sweep.csv"), second(again / "sweep.csv");
  std::string a, b;
  std::getline(first, a);
  std::getline(second, b);
  while (std::getline(first, a) && std::getline(second, b)) {
    std::vector<std::string> fa = split_csv_line(a), fb = split_csv_line(b);
    fa[5] = fb[5] = "";    // the time
    fa[12] = fb[12] = "";  // the front depends on the times
    CHECK(fa == fb);
  }
}

TEST_CASE("aSweepOfACloudySceneTurnsTheLayersOctavesAndKeepsItsGlRows", "[sweep][clouds]") {
  const Scene scene = resolve_scene("clouds", {"viewport.width=64", "viewport.height=48"});
  const SweepPlan plan = plan_sweep(scene, false, std::nullopt);
  std::vector<std::string> octaves;
  for (const SweepConfiguration& c : plan.configurations) {
    if (c.knob == "cloud_octaves") {
      octaves.push_back(c.value);
      CHECK(configured_scene(scene, c).sky.clouds->octaves == std::stoi(c.value));
    }
  }
  // 5 is the preset's own: it collapses into the default row.
  CHECK(octaves == std::vector<std::string>{"2", "3", "8"});
  // The GL backend draws the layer (gpu/shaders/clouds.glsl): its row is planned, not skipped.
  bool gl_planned = false;
  for (const SweepConfiguration& c : plan.configurations) {
    gl_planned = gl_planned || c.backend == Backend::kGl;
  }
  CHECK(gl_planned);
  for (const SweepSkipped& s : plan.skipped) {
    CHECK(s.reason.find("sky.clouds") == std::string::npos);
  }
  const SweepPlan clear = plan_sweep(resolve_scene("default", {}), false, std::nullopt);
  for (const SweepConfiguration& c : clear.configurations) {
    CHECK(c.knob != "cloud_octaves");
  }
}

TEST_CASE("sweepRefusesBadOptionsWithNothingWritten", "[sweep][cli]") {
  test::TempDir dir("sweep-bad");
  const std::filesystem::path out = dir.path() / "out";
  // A reference of the wrong size, and a PNG in place of linear radiance.
  const std::string small = (dir.path() / "small.exr").string();
  const std::string png = (dir.path() / "ref.png").string();
  REQUIRE(test::run({"render", "--set", "viewport.width=32", "--set", "viewport.height=24", "--set",
                     "grid.width=16", "--set", "grid.height=16", "-o", png, "--float", small})
              .code == kExitOk);
  const auto sweep = [&](std::vector<std::string> extra, bool with_out = true) {
    std::vector<std::string> args = {"sweep"};
    args.insert(args.end(), kTinyScene.begin(), kTinyScene.end());
    if (with_out) {
      args.insert(args.end(), {"--out", out.string()});
    }
    args.insert(args.end(), extra.begin(), extra.end());
    return test::run(args);
  };
  for (const auto& [extra, with_out, message] :
       std::vector<std::tuple<std::vector<std::string>, bool, std::string>>{
           {{"--quick"}, false, "--out is required"},
           {{"--out", ""}, false, "--out is empty"},
           {{"--repeat", "0"}, true, "--repeat"},
           {{"--reference", small}, true, "is 32x24; the scene's viewport is 64x48"},
           {{"--reference", png}, true, "is a png image"},
           {{"--reference", (dir.path() / "missing.exr").string()}, true, "missing.exr"},
           {{"--reference-supersample", "0"}, true, "--reference-supersample 0 is out of range"},
           {{"--max-memory", "1M"}, true, "this sweep"}}) {
    const test::CliResult r = sweep(extra, with_out);
    test::require_refused(r, message, out);
  }
  const test::CliResult preset = test::run({"sweep", "no-such-preset", "--out", out.string()});
  test::require_refused(preset, "no-such-preset", out);
}

}  // namespace
}  // namespace relief
