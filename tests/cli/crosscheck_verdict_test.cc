// relief crosscheck's verdict (tools/crosscheck.h) on frames made by hand, where the answer is
// known without GL: a colour difference where both frames draw the same triangle fails; a
// changed triangle fails only away from a triangle boundary of the CPU's frame; a bilinear
// mip-level switch is explained by the trilinear frame's distance and nothing beyond it.
// Also the file identity behind every command's refusal of outputs that alias (distinct_paths.h).
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <optional>
#include <vector>

#include <catch2/catch.hpp>

#include "core/srgb.h"
#include "pipeline/frame.h"
#include "tests/support/cli_support.h"
#include "tests/support/test_support.h"
#include "tools/commands.h"
#include "tools/crosscheck.h"
#include "tools/distinct_paths.h"

namespace relief {
namespace {

constexpr int kSide = 8;

// An 8 x 8 frame: the left half drawn by triangle 1, the right half by triangle 2, every pixel
// of linear radiance `value` (sRGB codes from it).
FrameImage halves(float value = 0.2f) {
  FrameImage f;
  f.width = f.height = kSide;
  const std::size_t pixels = kSide * kSide;
  f.primitive.resize(pixels);
  f.linear.assign(3 * pixels, value);
  f.srgb.assign(3 * pixels, srgb_byte(value));
  // Every output, as crosscheck renders both frames (compare_pixels reads them).
  f.depth.assign(pixels, 0.5f);
  f.normal.assign(3 * pixels, 0.0f);
  f.world_height.assign(pixels, 10.0f);
  f.octaves.assign(pixels, 4.0f);
  for (std::size_t k = 0; k < pixels; ++k) {
    f.normal[3 * k + 1] = 1.0f;
  }
  for (std::size_t k = 0; k < pixels; ++k) {
    f.primitive[k] = (k % kSide) < kSide / 2 ? 1u : 2u;
  }
  return f;
}

std::size_t at(int x, int y) {
  return std::size_t(y) * kSide + std::size_t(x);
}

void set_code(FrameImage& f, std::size_t pixel, int delta) {
  for (int c = 0; c < 3; ++c) {
    f.srgb[3 * pixel + c] = std::uint8_t(int(f.srgb[3 * pixel + c]) + delta);
  }
}

const CompareThresholds kDefault = CrosscheckOptions{}.thresholds;

}  // namespace

TEST_CASE("crosscheckPassesEqualFramesAndFailsTwoCodesOnTheSameTriangle", "[crosscheck]") {
  const FrameImage cpu = halves();
  CHECK(compare_frames(cpu, cpu, kDefault).verdict == CompareVerdict::kPass);
  FrameImage gl = cpu;
  set_code(gl, at(1, 3), 2);  // interior of triangle 1, the same triangle on both sides
  const FrameDifference d = compare_frames(cpu, gl, kDefault);
  CHECK(d.verdict == CompareVerdict::kFailure);
  CHECK(d.srgb.fail_pixels == 1);
  CHECK(d.unexplained_changes == 0);
  // One code apart is within the documented shading bound.
  gl = cpu;
  set_code(gl, at(1, 3), 1);
  CHECK(compare_frames(cpu, gl, kDefault).verdict == CompareVerdict::kPass);
}

TEST_CASE("aChangedTriangleIsJudgedOnlyByWhereItLies", "[crosscheck]") {
  const FrameImage cpu = halves();
  // On the boundary between the halves (x = 3 has a neighbour of triangle 2): GL's tie-break
  // or snapping may hand it over, with another surface's colour: no colour bound there.
  FrameImage gl = cpu;
  gl.primitive[at(3, 4)] = 2;
  set_code(gl, at(3, 4), 100);
  FrameDifference d = compare_frames(cpu, gl, kDefault);
  CHECK(d.verdict == CompareVerdict::kPass);
  CHECK(d.unexplained_changes == 0);
  CHECK(d.pixels.primitive_mismatch == 1);
  CHECK(d.srgb_all.fail_pixels == 1);  // the whole-image figures still show it
  // --all-pixels judges it as idiff judges the files.
  CHECK(compare_frames(cpu, gl, kDefault, nullptr, true).verdict == CompareVerdict::kFailure);
  // In the interior (every 8-neighbour triangle 1, not the border): no snapping explains it.
  gl = cpu;
  gl.primitive[at(1, 4)] = 2;
  d = compare_frames(cpu, gl, kDefault);
  CHECK(d.verdict == CompareVerdict::kFailure);
  CHECK(d.unexplained_changes == 1);
  // The framebuffer's border is a boundary: (0, 4) may change.
  gl = cpu;
  gl.primitive[at(0, 4)] = 7;
  CHECK(compare_frames(cpu, gl, kDefault).verdict == CompareVerdict::kPass);
  // The boundary pixels of two halves: the border's ring (28) and columns 3 and 4 inside it
  // (2 x 6).
  CHECK(compare_frames(cpu, cpu, kDefault).boundary_pixels == 28 + 12);
}

TEST_CASE("aBilinearLevelSwitchIsExplainedWithinTheTrilinearFramesReach", "[crosscheck]") {
  // The CPU took level n (0.2); the trilinear blend at the switch lies half-way to level n + 1
  // (0.25), so the other level is 0.3. GL at 0.3 took that level: explained. GL at 0.45 lies
  // beyond 0.05 / (1/2 - kLodTolerance) of 0.2: not explained.
  const FrameImage cpu = halves(0.2f);
  FrameImage trilinear = halves(0.25f);
  const std::size_t pixel = at(1, 3);
  for (const auto& [value, explained] : {std::pair{0.3f, true}, std::pair{0.45f, false}}) {
    FrameImage gl = cpu;
    for (int c = 0; c < 3; ++c) {
      gl.linear[3 * pixel + c] = value;
      gl.srgb[3 * pixel + c] = srgb_byte(value);
    }
    INFO("GL " << value);
    const FrameDifference with = compare_frames(cpu, gl, kDefault, &trilinear);
    CHECK((with.verdict == CompareVerdict::kPass) == explained);
    CHECK(with.level_switch_channels == (explained ? 3u : 0u));
    // Without the trilinear frame (a trilinear scene) nothing is explained.
    CHECK(compare_frames(cpu, gl, kDefault).verdict == CompareVerdict::kFailure);
  }
  // Where the trilinear frame equals the bilinear one (no level switch near), nothing beyond
  // one code is explained.
  FrameImage gl = cpu;
  set_code(gl, pixel, 2);
  CHECK(compare_frames(cpu, gl, kDefault, &cpu).verdict == CompareVerdict::kFailure);
}

TEST_CASE("aShorelineStepIsExplainedOnlyWhereTheHeightsStraddleTheWaterLevel", "[crosscheck]") {
  // One pixel's colours differ by far more than a code. The camera stands 2600 above a water
  // level of 0 (the clouds preset). Where the CPU's height and GL's lie on both sides of the
  // level (each within a float ulp) and within kShorelineUlps ulps of the camera-relative
  // height (2.4e-4 at 2600) of each other, one is water and the other dry ground: explained.
  // Elsewhere, without water, with every pixel judged, or with heights that are not finite:
  // not explained.
  const std::size_t pixel = at(5, 4);
  const Shoreline shore{0.0, 2600.0};
  const auto judge = [&](float cpu_height, float gl_height, std::optional<Shoreline> s,
                         bool all_pixels = false) {
    FrameImage cpu = halves(0.2f), gl = halves(0.2f);
    cpu.world_height[pixel] = cpu_height;
    gl.world_height[pixel] = gl_height;
    for (int c = 0; c < 3; ++c) {
      gl.linear[3 * pixel + c] = 0.45f;
      gl.srgb[3 * pixel + c] = srgb_byte(0.45f);
    }
    return compare_frames(cpu, gl, kDefault, nullptr, all_pixels, s);
  };
  const float below = -0.000244140625f;  // one ulp of 2600 below the level
  const FrameDifference shore_step = judge(below, 0.0f, shore);
  CHECK(shore_step.verdict == CompareVerdict::kPass);
  CHECK(shore_step.water_edge_pixels == 1);
  CHECK(judge(0.0f, below, shore).verdict == CompareVerdict::kPass);       // either way round
  CHECK(judge(-0.01f, 0.005f, shore).verdict == CompareVerdict::kPass);    // 62 ulps apart
  CHECK(judge(-0.01f, 0.01f, shore).verdict == CompareVerdict::kFailure);  // 82 ulps apart
  CHECK(judge(9.0f, 10.0f, Shoreline{9.5, 2600.0}).verdict == CompareVerdict::kFailure);
  CHECK(judge(below, 0.0f, std::nullopt).verdict == CompareVerdict::kFailure);  // no water
  CHECK(judge(below, 0.0f, shore, true).verdict == CompareVerdict::kFailure);   // every pixel
  const FrameDifference dry = judge(10.0f, 10.0f, shore);                       // both above
  CHECK(dry.verdict == CompareVerdict::kFailure);
  CHECK(dry.water_edge_pixels == 0);
  CHECK(judge(-5.0f, -4.0f, shore).verdict == CompareVerdict::kFailure);  // both under water
  const float inf = std::numeric_limits<float>::infinity();
  for (const float bad : {inf, -inf, std::numeric_limits<float>::quiet_NaN()}) {
    CHECK(judge(below, bad, shore).verdict == CompareVerdict::kFailure);
    CHECK(judge(bad, 0.0f, shore).verdict == CompareVerdict::kFailure);
  }
}

TEST_CASE("pathsNamingOneFileAreFoundThroughLinksAndSpellings", "[crosscheck]") {
  namespace fs = std::filesystem;
  test::TempDir dir("distinct-paths");
  const fs::path file = dir.path() / "a.png";
  test::write_file(file, "x");
  fs::create_symlink(file, dir.path() / "soft.png");
  fs::create_hard_link(file, dir.path() / "hard.png");
  fs::create_directory(dir.path() / "sub");
  CHECK(same_file(file, dir.path() / "soft.png"));
  CHECK(same_file(file, dir.path() / "hard.png"));
  CHECK(same_file(file, dir.path() / "sub" / ".." / "a.png"));
  CHECK_FALSE(same_file(file, dir.path() / "b.png"));
  // Neither exists yet: the same spelling after resolving links and dots.
  CHECK(same_file(dir.path() / "new.png", dir.path() / "sub" / ".." / "new.png"));
  CHECK_FALSE(same_file(dir.path() / "new.png", dir.path() / "new2.png"));
  // Two inputs may be one file; an output may not be an input or another output.
  CHECK_FALSE(same_file_conflict({{"A", file, false}, {"B", dir.path() / "soft.png", false}}));
  const auto conflict =
      same_file_conflict({{"A", file, false}, {"--json", dir.path() / "hard.png", true}});
  REQUIRE(conflict);
  CHECK_THAT(*conflict, Catch::Contains("A ") && Catch::Contains("--json") &&
                            Catch::Contains("name the same file"));
  CHECK(same_file_conflict({{"-o", dir.path() / "x.png"}, {"--float", dir.path() / "x.png"}}));
  // An output not asked for (empty) conflicts with nothing.
  CHECK_FALSE(same_file_conflict({{"-o", ""}, {"--float", ""}}));
}

}  // namespace relief
