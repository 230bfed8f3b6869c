// relief stages on a planet writes the bend (bent.pfm, drop.pfm) beside the unbent buffers,
// and the bent positions lie where docs/planet.md puts them, checked from the files alone:
// the sphere's centre is camera-relative (0, -D, 0) with D = R + (camera y - base_height); a
// vertex at arc offset (dx, dz) and camera-relative height h lies at distance D + h from it,
// at the polar angle |(dx, dz)| / R, in the direction of (dx, dz).
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "tests/support/cli_support.h"
#include "tests/support/test_support.h"

namespace relief {
namespace {

struct Pfm {
  int width = 0, height = 0, channels = 0;
  std::vector<float> values;  // rows bottom to top, channels interleaved
};

// The PFM layout of the docs (docs/using-relief.md, "Float outputs" and "Stage outputs"): "PF"
// or "Pf", "W H", "-1.0", then floats.
Pfm read_pfm(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  REQUIRE(in);
  std::string magic, scale;
  Pfm pfm;
  in >> magic >> pfm.width >> pfm.height >> scale;
  in.get();  // the single white-space character after the scale
  REQUIRE((magic == "PF" || magic == "Pf"));
  REQUIRE(scale == "-1.0");
  pfm.channels = magic == "PF" ? 3 : 1;
  const std::vector<char> bytes((std::istreambuf_iterator<char>(in)),
                                std::istreambuf_iterator<char>());
  pfm.values.resize(std::size_t(pfm.width) * pfm.height * pfm.channels);
  REQUIRE(bytes.size() == pfm.values.size() * sizeof(float));
  std::memcpy(pfm.values.data(), bytes.data(), bytes.size());
  return pfm;
}

TEST_CASE("stagesOnAPlanetWriteTheBendWhereTheSphereHasIt", "[planet][cli]") {
  test::TempDir dir("planet-stages");
  for (const char* backend : {"simd", "reference-double"}) {
    INFO(backend);
    const std::filesystem::path out = dir.path() / backend;
    const test::CliResult r =
        test::run({"stages", "planet", "--backend", backend, "--out", out.string(), "--set",
                   "grid.width=48", "--set", "grid.height=40"});
    INFO(r.err);
    REQUIRE(r.code == 0);
    const nlohmann::json manifest = nlohmann::json::parse(std::ifstream(out / "stages.json"));
    REQUIRE(manifest["files"].contains("bent"));
    REQUIRE(manifest["files"].contains("drop"));
    const double R = manifest["scene"]["terrain"]["planet"]["radius"];
    const double base = manifest["scene"]["terrain"]["base_height"];
    const double D = R + (double(manifest["camera_position"][1]) - base);
    const Pfm domain = read_pfm(out / "domain.pfm");
    const Pfm height = read_pfm(out / "height.pfm");
    const Pfm bent = read_pfm(out / "bent.pfm");
    const Pfm drop = read_pfm(out / "drop.pfm");
    REQUIRE(bent.channels == 3);
    REQUIRE(bent.values.size() == 3 * height.values.size());
    std::size_t valid = 0;
    for (std::size_t k = 0; k < height.values.size(); ++k) {
      if (domain.values[3 * k + 2] != 1.0f) {
        continue;
      }
      ++valid;
      const double dx = domain.values[3 * k], dz = domain.values[3 * k + 1];
      const double h = height.values[k];
      const double x = bent.values[3 * k], y = bent.values[3 * k + 1], z = bent.values[3 * k + 2];
      const double rho = std::hypot(dx, dz), across = std::hypot(x, z);
      // Each file value is a float: a coordinate of magnitude up to D + |h| carries 2^-24 of it
      // from its own rounding, and the float bend a few times that (sin_cos_det, the sqrt,
      // three products): 16 of them bound both distances here; in angle, 16 relative to the
      // distance from the centre.
      const double ulp = std::ldexp(D + std::abs(h), -24);
      CHECK(std::abs(std::hypot(across, y + D) - (D + h)) <= 16 * ulp);
      CHECK(std::abs(std::atan2(across, y + D) - rho / R) <=
            16 * ulp / (D + h) + 16 * rho / R * 0x1p-24);
      // In the direction of (dx, dz): the cross product of the two is zero up to rounding.
      CHECK(std::abs(x * dz - z * dx) <= 16 * ulp * (rho + 1));
      // The drop is how far the bend lowered the vertex: h - y.
      CHECK(std::abs((h - y) - drop.values[k]) <= 4 * ulp);
      CHECK(drop.values[k] >= 0.0f);
    }
    CHECK(valid > 100);
  }
}

}  // namespace
}  // namespace relief
