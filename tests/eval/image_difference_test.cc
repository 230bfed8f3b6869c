// Relief's own ImageBufAlgo::compare figures and absdiff-then-maxchan difference
// (tools/image_compare.cc) against OpenImageIO 2.4.7 itself, which this test binary links: the
// same buffers through both must give the same figures bit for bit (mean, RMS, PSNR, the
// largest difference and its place, the warning and failure counts) and the same per-pixel
// differences, on random images across several 4096-pixel batches, equal images, NaN and
// infinities, huge and denormal values. And compare_images runs in a process that cannot load
// the OpenImageIO module, as relief crosscheck must on a GPU machine without it.
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <catch2/catch.hpp>

#include "tests/support/hashed_draws.h"
#include "tests/support/limited_run.h"
#include "tests/support/test_support.h"
#include "tools/image_compare.h"
#include "tools/image_library.h"

namespace relief {
namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();

FloatImage image(int width, int height, int channels, std::vector<float> values) {
  return FloatImage{width, height, channels, {}, std::move(values)};
}

// An ImageBuf over the image's floats, as librelief_images.so wrapped them before Relief
// computed the figures itself (compare and absdiff only read them).
OIIO::ImageBuf wrap(const FloatImage& image) {
  const OIIO::ImageSpec spec(image.width, image.height, image.channels, OIIO::TypeFloat);
  return OIIO::ImageBuf(spec, const_cast<float*>(image.pixels.data()));
}

std::string bits(double x) {
  std::ostringstream out;
  out << x << " (0x" << std::hex << std::bit_cast<std::uint64_t>(x) << ")";
  return out.str();
}

// Empty when Relief's figures are OpenImageIO's bit for bit, else what differs.
std::string figure_mismatch(const CompareResult& ours,
                            const OIIO::ImageBufAlgo::CompareResults& oiio) {
  std::string text;
  const auto real = [&](const char* name, double x, double y) {
    if (std::bit_cast<std::uint64_t>(x) != std::bit_cast<std::uint64_t>(y)) {
      text += std::string(name) + ": relief " + bits(x) + ", OpenImageIO " + bits(y) + "\n";
    }
  };
  const auto whole = [&](const char* name, std::uint64_t x, std::uint64_t y) {
    if (x != y) {
      text += std::string(name) + ": relief " + std::to_string(x) + ", OpenImageIO " +
              std::to_string(y) + "\n";
    }
  };
  real("mean", ours.mean_error, oiio.meanerror);
  real("rms", ours.rms_error, oiio.rms_error);
  real("psnr", ours.psnr, oiio.PSNR);
  real("max", ours.max_error, oiio.maxerror);
  whole("max x", std::uint64_t(ours.max_x), std::uint64_t(oiio.maxx));
  whole("max y", std::uint64_t(ours.max_y), std::uint64_t(oiio.maxy));
  whole("max channel", std::uint64_t(ours.max_channel), std::uint64_t(oiio.maxc));
  whole("warn pixels", ours.warn_pixels, oiio.nwarn);
  whole("fail pixels", ours.fail_pixels, oiio.nfail);
  return text;
}

// compare_images and largest_channel_difference against ImageBufAlgo::compare (relative
// thresholds 0, one thread, as idiff and the module called it) and absdiff + maxchan, with
// (fail, warn) thresholds 0 and 0, 0.02 and 0.004, 0.004 and 0.02, 1e-6 and 1e-6.
// Returns OpenImageIO's figures at 0 / 0 and at 0.02 / 0.004, for the callers' own checks.
struct OiioFigures {
  OIIO::ImageBufAlgo::CompareResults zero, typical;
};

OiioFigures require_same(const FloatImage& a, const FloatImage& b) {
  OiioFigures figures{};
  for (const auto& [fail, warn] : {std::pair{0.0f, 0.0f}, std::pair{0.02f, 0.004f},
                                   std::pair{0.004f, 0.02f}, std::pair{1e-6f, 1e-6f}}) {
    INFO("fail " << fail << ", warn " << warn);
    CompareThresholds thresholds;
    thresholds.fail = fail;
    thresholds.warn = warn;
    const CompareResult ours = compare_images(a, b, thresholds);
    const OIIO::ImageBufAlgo::CompareResults oiio =
        OIIO::ImageBufAlgo::compare(wrap(a), wrap(b), fail, warn, 0.0f, 0.0f, OIIO::ROI::All(), 1);
    // OpenImageIO sets `error` when some pixel fails (compare_ returns nfail == 0 as its
    // success), and for nothing else here.
    REQUIRE(oiio.error == (oiio.nfail > 0));
    const std::string mismatch = figure_mismatch(ours, oiio);
    INFO(mismatch);
    CHECK(mismatch.empty());
    if (fail == 0.0f) {
      figures.zero = oiio;
    } else if (fail == 0.02f) {
      figures.typical = oiio;
    }
  }
  const std::vector<float> ours = largest_channel_difference(a, b);
  const OIIO::ImageBuf difference = OIIO::ImageBufAlgo::absdiff(wrap(a), wrap(b), {}, 0);
  const OIIO::ImageBuf largest = OIIO::ImageBufAlgo::maxchan(difference, {}, 0);
  std::vector<float> oiio(std::size_t(a.width) * std::size_t(a.height));
  REQUIRE(largest.get_pixels(OIIO::ROI(0, a.width, 0, a.height, 0, 1, 0, 1), OIIO::TypeFloat,
                             oiio.data()));
  REQUIRE(ours.size() == oiio.size());
  std::size_t differing = 0;
  std::string first;
  for (std::size_t i = 0; i < ours.size(); ++i) {
    if (std::bit_cast<std::uint32_t>(ours[i]) != std::bit_cast<std::uint32_t>(oiio[i]) &&
        differing++ == 0) {
      first = "pixel " + std::to_string(i) + ": relief " + bits(ours[i]) + ", OpenImageIO " +
              bits(oiio[i]);
    }
  }
  INFO(differing << " pixels differ; the first: " << first);
  CHECK(differing == 0);
  return figures;
}

// Two images of random values in [0, scale): a third of the values equal, the rest apart by up
// to 1% or 5% of scale.
std::pair<FloatImage, FloatImage> random_pair(std::uint64_t seed, int width, int height,
                                              int channels, double scale) {
  test::HashedDraws draws(seed);
  const std::size_t n = std::size_t(width) * std::size_t(height) * std::size_t(channels);
  std::vector<float> a(n), b(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double x = draws.uniform(0, scale);
    const double kind = draws.uniform(0, 3);
    const double spread = kind < 1 ? 0.0 : kind < 2 ? 0.01 : 0.05;
    a[i] = static_cast<float>(x);
    b[i] = static_cast<float>(x + spread * scale * draws.uniform(-1, 1));
  }
  return {image(width, height, channels, std::move(a)),
          image(width, height, channels, std::move(b))};
}

TEST_CASE("imageDifferenceMatchesOpenImageIOOnRandomImages", "[compare]") {
  // 64 x 64 is one batch exactly; 65 x 64 and larger run on into further, partial batches.
  const std::vector<std::pair<int, int>> sizes = {{1, 1},   {3, 2},    {64, 64},
                                                  {65, 64}, {100, 83}, {129, 97}};
  std::uint64_t seed = 1;
  bool some_failed_partly = false;
  for (const auto& [width, height] : sizes) {
    for (const int channels : {1, 3, 4}) {
      for (const double scale : {1.0, 40.0}) {  // 40: an HDR peak above 1
        INFO(width << " x " << height << " x " << channels << ", scale " << scale);
        const auto [a, b] = random_pair(seed++, width, height, channels, scale);
        const auto typical = require_same(a, b).typical;
        const auto pixels = std::uint64_t(width) * std::uint64_t(height);
        some_failed_partly |= typical.nfail > 0 && typical.nfail < pixels;
      }
    }
  }
  CHECK(some_failed_partly);  // the thresholds split the pixels, not all or none
}

TEST_CASE("imageDifferenceMatchesOpenImageIOOnEqualImages", "[compare]") {
  const FloatImage a = random_pair(77, 70, 61, 3, 1.0).first;
  const auto typical = require_same(a, a).typical;
  CHECK(std::isinf(typical.PSNR));
  CHECK(typical.rms_error == 0);
  const FloatImage zeros = image(5, 4, 1, std::vector<float>(20, 0.0f));
  require_same(zeros, zeros);
}

TEST_CASE("imageDifferenceMatchesOpenImageIOOnNonFiniteValues", "[compare]") {
  SECTION("each kind of pair, one value an image") {
    const std::vector<std::pair<float, float>> pairs = {
        {kNaN, kNaN}, {kInf, kInf}, {kInf, -kInf}, {-kInf, -kInf}, {kNaN, 1.0f},
        {1.0f, kNaN}, {kInf, 0.5f}, {0.5f, -kInf}, {kNaN, kInf},   {-kInf, kNaN}};
    for (const auto& [x, y] : pairs) {
      INFO(x << " against " << y);
      require_same(image(1, 1, 1, {x}), image(1, 1, 1, {y}));
      // Channel 1 and 2 of a pixel whose channel 0 differs by 0.25.
      require_same(image(1, 1, 3, {0.0f, x, x}), image(1, 1, 3, {0.25f, y, 1.0f}));
    }
  }
  SECTION("a NaN difference after the first mismatch becomes the largest, then any after it") {
    // 0: the first mismatch, inf at 0. 1: NaN - Inf is NaN, and !(NaN <= inf) makes it the
    // largest. 2: !(0.5 <= NaN) makes 0.5 the largest. 3: 0.25 <= 0.5 leaves it.
    const FloatImage a = image(4, 1, 1, {1.0f, kNaN, 0.0f, 0.0f});
    const FloatImage b = image(4, 1, 1, {kNaN, kInf, 0.5f, 0.25f});
    const auto typical = require_same(a, b).typical;
    CHECK(typical.maxerror == 0.5);
    CHECK(typical.maxx == 2);
    CHECK(std::isnan(typical.meanerror));
  }
  SECTION("+Inf matches -Inf") {
    const auto zero =
        require_same(image(2, 1, 1, {kInf, 0.0f}), image(2, 1, 1, {-kInf, 0.0f})).zero;
    CHECK(zero.maxerror == 0);
    CHECK(zero.nfail == 0);
  }
  SECTION("scattered through random images, in one or both") {
    std::uint64_t seed = 100;
    for (const double rate : {0.0005, 0.01, 0.2}) {
      for (const int channels : {1, 3, 4}) {
        INFO("rate " << rate << ", " << channels << " channels");
        auto [a, b] = random_pair(seed++, 97, 53, channels, 2.0);
        test::HashedDraws draws(seed++);
        const float specials[] = {kNaN, kInf, -kInf};
        for (std::size_t i = 0; i < a.pixels.size(); ++i) {
          if (draws.uniform(0, 1) >= rate) {
            continue;
          }
          const float special = specials[static_cast<int>(draws.uniform(0, 3))];
          const double where = draws.uniform(0, 3);  // a, b, or both
          if (where < 2) {
            a.pixels[i] = special;
          }
          if (where >= 1) {
            b.pixels[i] = where < 2 ? special : specials[static_cast<int>(draws.uniform(0, 3))];
          }
        }
        require_same(a, b);
      }
    }
  }
}

TEST_CASE("imageDifferenceMatchesOpenImageIOOnHugeAndTinyValues", "[compare]") {
  SECTION("random values of 1e30 and 1e-40 (denormal), of either sign") {
    std::uint64_t seed = 500;
    for (const double scale : {1e30, 3e38, 1e-40}) {
      for (const int channels : {1, 4}) {
        INFO("scale " << scale << ", " << channels << " channels");
        auto [a, b] = random_pair(seed++, 80, 60, channels, scale);
        test::HashedDraws draws(seed++);
        for (float& x : b.pixels) {
          x = draws.uniform(0, 1) < 0.5 ? -x : x;
        }
        require_same(a, b);
      }
    }
  }
  SECTION("by hand") {
    constexpr float kTiny = std::numeric_limits<float>::denorm_min();
    constexpr float kMax = std::numeric_limits<float>::max();
    // The smallest denormal against 0: a difference over threshold 0, yet OpenImageIO's mean
    // of |a| and |b| rounds to 0 as a float, so its relative difference is 0 and the pixel
    // neither warns nor fails.
    const auto tiny =
        require_same(image(2, 1, 1, {kTiny, 0.0f}), image(2, 1, 1, {0.0f, 0.0f})).zero;
    CHECK(tiny.maxerror > 0);
    CHECK(tiny.nfail == 0);
    // Twice that against 0: the mean is the smallest denormal, and the pixel fails.
    const auto two = require_same(image(1, 1, 1, {2 * kTiny}), image(1, 1, 1, {0.0f})).zero;
    CHECK(two.nfail == 1);
    // The smallest denormal against its negative: the mean, taken in double, is the smallest
    // denormal (halving each in float would give 0), and the pixel fails.
    const auto opposite = require_same(image(1, 1, 1, {kTiny}), image(1, 1, 1, {-kTiny})).zero;
    CHECK(opposite.nfail == 1);
    // Finite values whose difference overflows to inf, before and after a NaN mismatch.
    require_same(image(3, 1, 1, {kMax, kNaN, 1e30f}), image(3, 1, 1, {-kMax, 0.0f, -1e30f}));
    require_same(image(3, 1, 1, {kNaN, kMax, 2e-40f}), image(3, 1, 1, {0.0f, -kMax, 1e-40f}));
  }
}

// Run only by the test below, in a process of its own whose $RELIEF_IMAGE_LIBRARY names a file
// that is not the module: loading it fails there (image_library() tries that path first and
// remembers only a success), so compare_images must not need it.
TEST_CASE("childOfCompareImagesNeedsNoImageModule", "[.][compare-child]") {
  REQUIRE(std::getenv("RELIEF_IMAGE_LIBRARY") != nullptr);
  REQUIRE_THROWS_AS(image_library(), ImageLibraryError);
  FloatImage a = image(4, 3, 2, std::vector<float>(24, 0.0f));
  FloatImage b = a;
  b.pixels[(1 * 4 + 2) * 2 + 1] = 0.25f;
  const CompareResult r = compare_images(a, b, {});
  CHECK(r.verdict == CompareVerdict::kFailure);
  CHECK(r.max_error == 0.25);
  CHECK((r.max_x == 2 && r.max_y == 1 && r.max_channel == 1));
  CHECK((r.warn_pixels == 1 && r.fail_pixels == 1));
  CHECK(r.mean_error == 0.25 / 24);
  const std::vector<float> difference = largest_channel_difference(a, b);
  REQUIRE(difference.size() == 12);
  CHECK(difference[1 * 4 + 2] == 0.25f);
  CHECK(difference[0] == 0.0f);
  // Still unloadable: nothing above loaded it some other way.
  CHECK_THROWS_AS(image_library(), ImageLibraryError);
}

TEST_CASE("compareImagesNeedsNoImageModule", "[compare]") {
  test::TempDir dir("no-image-module");
  const std::filesystem::path not_module = dir.path() / "not-a-module.so";
  std::ofstream(not_module) << "not a shared library\n";
  const std::filesystem::path report = dir.path() / "child.txt";
  const test::Exit run = test::run_binary(
      std::filesystem::read_symlink("/proc/self/exe"),
      "RELIEF_IMAGE_LIBRARY='" + not_module.string() + "'; export RELIEF_IMAGE_LIBRARY",
      "childOfCompareImagesNeedsNoImageModule -w NoTests -o '" + report.string() + "'", dir.path());
  const std::vector<unsigned char> bytes = test::read_bytes(report);
  const std::string text(bytes.begin(), bytes.end());
  INFO(text << run.err);
  CHECK_FALSE(run.signalled);
  CHECK(run.code == 0);
  CHECK_THAT(text, Catch::Matchers::Contains("1 test case"));
}

}  // namespace
}  // namespace relief
