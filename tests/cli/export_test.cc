// relief export (tools/export_command.h): a 16-bit height field exported at its own samples
// gives back its levels bit for bit, and the exported scene renders what the field renders and
// exports the same levels again; every file holds the samples (PFM, OBJ, glTF read back here
// from the formats' own specifications, PNGs by stb), a plane's normal map in its stated
// channels; outputs respect links and the scene's inputs (refusals: export_refusals_test.cc).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <stb_image.h>
#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "core/height_bounds.h"
#include "core/lattice.h"
#include "core/scene/scene_json.h"
#include "pipeline/geotiff_reference.h"
#include "tests/support/cli_support.h"
#include "tests/support/heightfield_files.h"
#include "tests/support/skybox_support.h"
#include "tests/support/test_support.h"

namespace relief {
namespace {

using test::concat;
using test::read_bytes;
using test::run;

using test::require_ok;

std::vector<std::uint16_t> grey16(const std::string& file, int& w, int& h) {
  const std::vector<unsigned char> png = read_bytes(file);
  int channels = 0;
  stbi_us* pixels = stbi_load_16_from_memory(png.data(), int(png.size()), &w, &h, &channels, 1);
  REQUIRE(pixels != nullptr);
  std::vector<std::uint16_t> out(pixels, pixels + std::size_t(w) * std::size_t(h));
  stbi_image_free(pixels);
  return out;
}

std::vector<unsigned char> rgba8(const std::string& file, int& w, int& h) {
  const std::vector<unsigned char> png = read_bytes(file);
  int channels = 0;
  unsigned char* pixels = stbi_load_from_memory(png.data(), int(png.size()), &w, &h, &channels, 4);
  REQUIRE(pixels != nullptr);
  std::vector<unsigned char> out(pixels, pixels + 4 * std::size_t(w) * std::size_t(h));
  stbi_image_free(pixels);
  return out;
}

// A one-channel PFM's values, top row first (PFM stores the bottom row first).
std::vector<float> pfm_top_first(const std::string& file, int w, int h) {
  const std::vector<unsigned char> bytes = read_bytes(file);
  const std::string header = "Pf\n" + std::to_string(w) + " " + std::to_string(h) + "\n-1.0\n";
  REQUIRE(bytes.size() == header.size() + 4 * std::size_t(w) * std::size_t(h));
  std::vector<float> out(std::size_t(w) * std::size_t(h));
  for (int j = 0; j < h; ++j) {
    std::memcpy(&out[std::size_t(j) * w],
                bytes.data() + header.size() + 4 * std::size_t(h - 1 - j) * w, 4 * std::size_t(w));
  }
  return out;
}

double max_code_difference(const std::string& a, const std::string& b) {
  int wa = 0, ha = 0, wb = 0, hb = 0;
  const std::vector<unsigned char> pa = rgba8(a, wa, ha), pb = rgba8(b, wb, hb);
  REQUIRE((wa == wb && ha == hb));
  int worst = 0;
  for (std::size_t k = 0; k < pa.size(); ++k) {
    worst = std::max(worst, std::abs(int(pa[k]) - int(pb[k])));
  }
  return worst;
}

TEST_CASE("a16BitFieldExportedAtItsSamplesGivesBackItsLevels", "[cli]") {
  test::TempDir dir("export");
  const auto file = [&](const std::string& name) { return (dir.path() / name).string(); };
  require_ok(
      run({"generate", "square-square", "--size", "65", "--seed", "4", "-o", file("src.png")}));
  const std::vector<std::string> field = {
      "--set", "terrain.heightfield.file=" + file("src.png"),
      "--set", "terrain.heightfield.extent=[-3000, -2000, 3500, 4500]",
      "--set", "terrain.heightfield.height=[-120, 880]",
      "--set", "terrain.heightfield.interpolating=true",
      "--set", "viewport.width=160",
      "--set", "viewport.height=128"};
  const auto with_field = [&](std::vector<std::string> args) {
    args.insert(args.end(), field.begin(), field.end());
    return run(args);
  };
  require_ok(with_field({"export", "--size", "65", "-o", file("out.png"), "--scene-out",
                         file("out.json"), "--json", file("figures.json")}));
  int w = 0, h = 0, w2 = 0, h2 = 0;
  const std::vector<std::uint16_t> source = grey16(file("src.png"), w, h);
  const std::vector<std::uint16_t> exported = grey16(file("out.png"), w2, h2);
  REQUIRE((w2 == 65 && h2 == 65));
  CHECK(exported == source);
  // The exported scene: the same levels again, and the same field (its range and base height
  // kept, export_files.cc), so the same picture bit for bit.
  require_ok(run({"export", file("out.json"), "--size", "65", "-o", file("again.png")}));
  CHECK(grey16(file("again.png"), w2, h2) == source);
  require_ok(with_field({"render", "-o", file("field.png")}));
  require_ok(run({"render", file("out.json"), "--set", "viewport.width=160", "--set",
                  "viewport.height=128", "-o", file("round_trip.png")}));
  CHECK(max_code_difference(file("field.png"), file("round_trip.png")) == 0);
  // A float map round-trips within float rounding.
  require_ok(with_field(
      {"export", "--size", "65", "-o", file("out.pfm"), "--scene-out", file("pfm.json")}));
  require_ok(run({"export", file("pfm.json"), "--size", "65", "-o", file("again.pfm")}));
  const std::vector<float> first = pfm_top_first(file("out.pfm"), 65, 65);
  const std::vector<float> second = pfm_top_first(file("again.pfm"), 65, 65);
  for (std::size_t k = 0; k < first.size(); ++k) {
    CHECK(second[k] == Approx(first[k]).margin(2e-3));
  }
}

TEST_CASE("aGeoTiffExportIsPlacedWhereItWasTaken", "[cli]") {
  test::TempDir dir("export");
  const auto file = [&](const std::string& name) { return (dir.path() / name).string(); };
  const std::vector<std::string> region = {"--region", "-1250",  "300",  "1750",
                                           "2100",     "--size", "40x24"};
  const auto export_with = [&](std::vector<std::string> args) {
    args.insert(args.begin(), region.begin(), region.end());
    args.insert(args.begin(), "export");
    return run(args);
  };
  require_ok(export_with({"-o", file("h.pfm")}));
  require_ok(export_with({"-o", file("h.tif"), "--scene-out", file("tif.json")}));
  HeightFieldSettings s;
  s.image = file("h.tif");
  s.georeferenced = true;
  const std::array<double, 4> placed = georeferenced_extent(s, 40, 24);
  CHECK(placed[0] == -1250.0);
  CHECK(placed[1] == 300.0);
  CHECK(placed[2] == Approx(1750.0).epsilon(1e-15));
  CHECK(placed[3] == Approx(2100.0).epsilon(1e-15));
  // Read back through its own placement (the scene names no extent it would use): the heights
  // again, within the interpolation's float rounding.
  require_ok(run({"export", file("tif.json"), "--size", "40x24", "-o", file("again.pfm")}));
  const std::vector<float> first = pfm_top_first(file("h.pfm"), 40, 24);
  const std::vector<float> again = pfm_top_first(file("again.pfm"), 40, 24);
  for (std::size_t k = 0; k < first.size(); ++k) {
    CHECK(again[k] == Approx(first[k]).margin(2e-3));
  }
}

// A gradient over the terrain's height bounds (shading.gradient.range null) keeps the source's
// bounds in the exported scene: the exported field's own bounds would move every stop.
TEST_CASE("anExportedSceneKeepsTheGradientsHeights", "[cli]") {
  test::TempDir dir("export");
  const auto file = [&](const std::string& name) { return (dir.path() / name).string(); };
  const std::vector<std::string> region = {
      "export", "--region", "-2000", "-2000", "2000",
      "2000",   "--size",   "33",    "--set", "shading.mode=\"gradient\""};
  const auto export_with = [&](std::vector<std::string> args) {
    args.insert(args.begin(), region.begin(), region.end());
    return run(args);
  };
  require_ok(export_with({"-o", file("h.pfm"), "--scene-out", file("bounds.json")}));
  const Scene source = resolve_scene("default", {"shading.mode=\"gradient\""});
  const HeightBounds bounds = derive_height_bounds(
      make_noise_lattice(source.terrain.seed, source.terrain.lattice_size), source.terrain);
  const Scene exported = resolve_scene(file("bounds.json"), {});
  REQUIRE(exported.shading.gradient.range);
  CHECK((*exported.shading.gradient.range)[0] == bounds.world_min);
  CHECK((*exported.shading.gradient.range)[1] == bounds.world_max);
  // A range the scene gives is kept as it is.
  require_ok(export_with({"-o", file("r.pfm"), "--scene-out", file("range.json"), "--set",
                          "shading.gradient.range=[-5, 600]"}));
  const Scene ranged = resolve_scene(file("range.json"), {});
  REQUIRE(ranged.shading.gradient.range);
  CHECK((*ranged.shading.gradient.range)[1] == 600.0);
}

TEST_CASE("everyExportedFileHoldsTheSamples", "[cli]") {
  test::TempDir dir("export");
  const auto file = [&](const std::string& name) { return (dir.path() / name).string(); };
  const int w = 21, h = 13;
  require_ok(run({"export", "--region", "-500", "300", "1600", "1600", "--size", "21x13", "-o",
                  file("h.pfm"), "--normals", file("n.png"), "--splat", file("splat"), "--mesh",
                  file("m.obj"), "--json", file("f.json")}));
  require_ok(run({"export", "--region", "-500", "300", "1600", "1600", "--size", "21x13", "--mesh",
                  file("m.glb")}));
  const std::vector<float> heights = pfm_top_first(file("h.pfm"), w, h);
  const auto x_of = [&](int i) { return -500.0 + (i + 0.5) * 2100.0 / w; };
  const auto z_of = [&](int j) { return 300.0 + (j + 0.5) * 1300.0 / h; };
  {  // OBJ: v, vn and vt per sample, two faces per cell
    std::ifstream in(file("m.obj"));
    std::string line;
    std::vector<std::array<double, 3>> v;
    std::vector<std::array<int, 3>> faces;
    std::vector<std::array<double, 2>> vt;
    while (std::getline(in, line)) {
      std::istringstream s(line);
      std::string kind;
      s >> kind;
      if (kind == "v") {
        std::array<double, 3> p{};
        s >> p[0] >> p[1] >> p[2];
        v.push_back(p);
      } else if (kind == "vt") {
        std::array<double, 2> t{};
        s >> t[0] >> t[1];
        vt.push_back(t);
      } else if (kind == "f") {
        std::array<int, 3> f{};
        for (int& index : f) {
          std::string corner;
          s >> corner;
          index = std::stoi(corner.substr(0, corner.find('/'))) - 1;
        }
        faces.push_back(f);
      }
    }
    REQUIRE(v.size() == std::size_t(w * h));
    REQUIRE(vt.size() == v.size());
    for (int j = 0; j < h; ++j) {  // OBJ's v runs up the picture: row 0 (z0, the top) near 1
      for (int i = 0; i < w; ++i) {
        CHECK(vt[std::size_t(j * w + i)][0] == Approx((i + 0.5) / w).margin(1e-6));
        CHECK(vt[std::size_t(j * w + i)][1] == Approx(1.0 - (j + 0.5) / h).margin(1e-6));
      }
    }
    CHECK(faces.size() == std::size_t(2 * (w - 1) * (h - 1)));
    for (int j = 0; j < h; ++j) {
      for (int i = 0; i < w; ++i) {
        const auto& p = v[std::size_t(j * w + i)];
        CHECK(p[0] == x_of(i));
        CHECK(float(p[1]) == heights[std::size_t(j * w + i)]);
        CHECK(p[2] == z_of(j));
      }
    }
    for (const auto& f : faces) {  // counter-clockwise seen from above: the normal's y > 0
      const auto& a = v[std::size_t(f[0])];
      const auto& b = v[std::size_t(f[1])];
      const auto& c = v[std::size_t(f[2])];
      const double ux = b[0] - a[0], uz = b[2] - a[2], vx = c[0] - a[0], vz = c[2] - a[2];
      CHECK(uz * vx - ux * vz > 0);
    }
  }
  {  // glTF 2.0 binary: header, JSON chunk, BIN chunk (the specification's section 4.4)
    const std::vector<unsigned char> glb = read_bytes(file("m.glb"));
    const auto u32 = [&](std::size_t at) {
      std::uint32_t v = 0;
      std::memcpy(&v, glb.data() + at, 4);
      return v;
    };
    REQUIRE(glb.size() > 28);
    CHECK(u32(0) == 0x46546C67u);
    CHECK(u32(4) == 2u);
    CHECK(u32(8) == glb.size());
    const std::uint32_t json_bytes = u32(12);
    CHECK(u32(16) == 0x4E4F534Au);
    const nlohmann::json gltf =
        nlohmann::json::parse(glb.begin() + 20, glb.begin() + 20 + json_bytes);
    const std::size_t bin = 20 + json_bytes + 8;
    CHECK(u32(20 + json_bytes + 4) == 0x004E4942u);
    const auto& position = gltf["accessors"][0];
    CHECK(position["count"] == w * h);
    CHECK(gltf["accessors"][3]["count"] == 6 * (w - 1) * (h - 1));
    const double cx = gltf["nodes"][0]["translation"][0], cz = gltf["nodes"][0]["translation"][2];
    CHECK(cx == 550.0);
    CHECK(cz == 950.0);
    for (int k = 0; k < w * h; ++k) {
      float p[3];
      std::memcpy(p, glb.data() + bin + 12 * std::size_t(k), 12);
      CHECK(p[1] == heights[std::size_t(k)]);
      CHECK(p[0] == Approx(x_of(k % w) - cx).margin(1e-4));
      CHECK(p[2] == Approx(z_of(k / w) - cz).margin(1e-4));
    }
  }
  {  // splat maps: the layers' bytes sum to 255; the normal map faces up
    int sw = 0, sh = 0;
    const std::vector<unsigned char> first = rgba8(file("splat_0.png"), sw, sh);
    const std::vector<unsigned char> second = rgba8(file("splat_1.png"), sw, sh);
    REQUIRE((sw == w && sh == h));
    for (std::size_t k = 0; k < std::size_t(w * h); ++k) {
      int sum = 0;
      for (int c = 0; c < 4; ++c) {
        sum += first[4 * k + c] + second[4 * k + c];
      }
      CHECK(sum == 255);
    }
    const std::vector<unsigned char> normals = rgba8(file("n.png"), sw, sh);
    for (std::size_t k = 0; k < std::size_t(w * h); ++k) {
      CHECK(normals[4 * k + 2] >= 128);  // B = n_y >= 0
    }
  }
}

TEST_CASE("theNormalMapOfAPlaneHoldsItsNormalInTheStatedChannels", "[cli]") {
  test::TempDir dir("export");
  const auto file = [&](const std::string& name) { return (dir.path() / name).string(); };
  const int n = 40;
  std::vector<float> ramp(std::size_t(n) * n);
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      ramp[std::size_t(j) * n + i] = float(i) / 64.0f + float(j) / 256.0f;
    }
  }
  const std::string pfm = test::write_file(dir.path() / "ramp.pfm", test::pfm_bytes(n, n, ramp));
  // 100 units a texel, 12800 units of height: rises 2 along x and 0.5 along z (height grows
  // with z, row j; no byte of the normal falls on a rounding tie); well inside the extent the
  // B-spline keeps the plane exactly.
  require_ok(run({"export", "--set",
                  concat({R"(terrain.heightfield={"file": ")", pfm,
                          R"(", "extent": [0, 0, 4000, 4000], "height": [0, 12800]})"}),
                  "--region", "1000", "1000", "3000", "3000", "--size", "16", "--normals",
                  file("n.png"), "--splat", file("s")}));
  const double norm = std::sqrt(4.0 + 1.0 + 0.25);
  const double nx = -2.0 / norm, ny = 1.0 / norm, nz = -0.5 / norm;
  const auto byte = [](double v) { return int(std::lround((v + 1.0) * 127.5)); };
  int w = 0, h = 0;
  const std::vector<unsigned char> rgba = rgba8(file("n.png"), w, h);
  REQUIRE((w == 16 && h == 16));
  for (std::size_t k = 0; k < rgba.size() / 4; ++k) {
    CHECK(int(rgba[4 * k]) == byte(nx));       // R = n_x
    CHECK(int(rgba[4 * k + 1]) == byte(-nz));  // G = -n_z: the picture's up is -z
    CHECK(int(rgba[4 * k + 2]) == byte(ny));   // B = n_y
  }
}

TEST_CASE("exportOutputsRespectLinksAndEveryInputOfTheScene", "[cli]") {
  test::TempDir dir("export");
  const auto file = [&](const std::string& name) { return (dir.path() / name).string(); };
  const std::vector<std::string> region = {"--region", "0", "0", "100", "100", "--size", "8"};
  const auto export_with = [&](std::vector<std::string> args) {
    args.insert(args.begin(), region.begin(), region.end());
    args.insert(args.begin(), "export");
    return run(args);
  };
  // A link among the outputs is written through: the link stays, its target gets the file.
  test::write_file(file("target.json"), "original");
  std::filesystem::create_symlink("target.json", file("link.json"));
  require_ok(export_with({"-o", file("h.png"), "--json", file("link.json")}));
  CHECK(std::filesystem::is_symlink(file("link.json")));
  const std::vector<unsigned char> json = read_bytes(file("target.json"));
  CHECK(nlohmann::json::parse(json.begin(), json.end())["samples"][0] == 8);
  // A link to nothing is refused up front, not replaced by a file.
  std::filesystem::create_symlink("nothere.json", file("dangling.json"));
  test::require_refused(export_with({"-o", file("d.png"), "--json", file("dangling.json")}),
                        "which does not exist", file("d.png"));
  CHECK(std::filesystem::is_symlink(file("dangling.json")));
  // Heights a height field cannot hold (below -1e7 here, where the fractal dips 1100 to 1600):
  // --scene-out refused before anything is written.
  test::require_refused(
      export_with({"--set", "terrain.base_height=-1e7", "--set", "terrain.amplitude=2000", "-o",
                   file("hi.png"), "--scene-out", file("hi.json")}),
      "beyond the +-1e7", file("hi.png"));
  CHECK_FALSE(std::filesystem::exists(file("hi.json")));
  // A skybox face is an input of the scene: never an output.
  const std::array<std::string, 6> faces = test::write_checker_faces(dir.path(), 8);
  const std::vector<unsigned char> face = read_bytes(faces[0]);
  test::require_refused(export_with({"--set", test::skybox_override(faces), "-o", faces[0]}),
                        "sky.skybox.faces[0]", file("never.png"));
  CHECK(read_bytes(faces[0]) == face);
  // The exported scene finds its map through any spelling of its own path (a linked folder).
  std::filesystem::create_directories(dir.path() / "real" / "deep");
  std::filesystem::create_directory_symlink(std::filesystem::path("real") / "deep",
                                            dir.path() / "L");
  require_ok(export_with({"-o", file("map.png"), "--scene-out", file("L/s.json")}));
  require_ok(run({"export", file("L/s.json"), "--size", "8", "-o", file("again1.png")}));
  require_ok(run({"export", file("real/deep/s.json"), "--size", "8", "-o", file("again2.png")}));
}

}  // namespace
}  // namespace relief
