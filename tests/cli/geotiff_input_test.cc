// terrain.heightfield.georeferenced (pipeline/geotiff_reference.h): a GeoTIFF written here
// from the specifications is placed where its tags say (metres, feet, PixelIsArea and
// PixelIsPoint, either byte order), renders exactly as the same samples with that extent
// given, and every placement Relief cannot use is refused naming the field and the reason.
#include <filesystem>
#include <string>
#include <vector>

#include <stb_image.h>
#include <catch2/catch.hpp>

#include "pipeline/geotiff_reference.h"
#include "tests/support/cli_support.h"
#include "tests/support/geotiff_files.h"
#include "tests/support/heightfield_files.h"
#include "tests/support/test_support.h"
#include "tools/image_library.h"

namespace relief {
namespace {

using test::concat;
using test::run;

HeightFieldSettings tif_settings(const std::string& file) {
  HeightFieldSettings s;
  s.image = file;
  s.georeferenced = true;
  return s;
}

TEST_CASE("aGeoTiffIsPlacedWhereItsTagsSay", "[heightfield]") {
  test::TempDir dir("geotiff");
  test::GeoTiff g;
  g.width = 64, g.height = 48;
  const auto extent_of = [&](const test::GeoTiff& t) {
    const std::string file = test::write_file(dir.path() / "f.tif", test::geotiff_bytes(t));
    return georeferenced_extent(tif_settings(file), t.width, t.height);
  };
  // PixelIsArea (the default): the tie point is the top-left corner; north (+Y) is -z.
  using Extent = std::array<double, 4>;
  CHECK(extent_of(g) == Extent{500000.0, -4200000.0, 500640.0, -4199520.0});
  test::GeoTiff big = g;
  big.big_endian = true;
  CHECK(extent_of(big) == Extent{500000.0, -4200000.0, 500640.0, -4199520.0});
  // PixelIsPoint (GTRasterTypeGeoKey 1025 = 2): the tie point is the first pixel's centre.
  test::GeoTiff point = g;
  point.geo_keys = {1024, 0, 1, 1, 1025, 0, 1, 2};
  CHECK(extent_of(point) == Extent{499995.0, -4200005.0, 500635.0, -4199525.0});
  // A tie point at raster (2, 3), in feet (ProjLinearUnitsGeoKey 3076 = 9002).
  test::GeoTiff feet = g;
  feet.tie_points = {2, 3, 0, 1000.0, 2000.0, 0};
  feet.geo_keys = {3076, 0, 1, 9002};
  const Extent f = extent_of(feet);
  CHECK(f[0] == Approx((1000.0 - 2 * 10.0) * 0.3048));
  CHECK(f[1] == Approx(-(2000.0 + 3 * 10.0) * 0.3048));
  CHECK(f[2] == Approx((1000.0 + 62 * 10.0) * 0.3048));
  CHECK(f[3] == Approx(-(2000.0 - 45 * 10.0) * 0.3048));
}

TEST_CASE("aGeoreferencedFieldRendersAsItsSamplesWithThatExtent", "[heightfield]") {
  test::TempDir dir("geotiff");
  test::GeoTiff g;
  g.width = 40, g.height = 30;
  g.top_row_first = test::random_unit_samples(std::size_t(40 * 30), 5);
  for (float& v : g.top_row_first) {
    v = 300.0f * v;
  }
  const std::string tif = test::write_file(dir.path() / "dem.tif", test::geotiff_bytes(g));
  const std::string pfm =
      test::write_file(dir.path() / "dem.pfm", test::pfm_bytes(40, 30, g.top_row_first));
  const std::vector<std::string> view = {"--set", "camera.position=[500200, 600, -4199900]",
                                         "--set", "viewport.width=96",
                                         "--set", "viewport.height=64",
                                         "--set", "grid.width=64",
                                         "--set", "grid.height=64"};
  const auto render = [&](const std::string& field, const std::string& out) {
    std::vector<std::string> args = {"render", "--set", "terrain.heightfield=" + field, "-o", out};
    args.insert(args.end(), view.begin(), view.end());
    const test::CliResult r = run(args);
    INFO(r.err);
    REQUIRE(r.code == 0);
    // The pixels (the PNG's text holds the scene, which names the file and its extent).
    const std::vector<unsigned char> png = test::read_bytes(out);
    int w = 0, h = 0, channels = 0;
    unsigned char* pixels =
        stbi_load_from_memory(png.data(), int(png.size()), &w, &h, &channels, 3);
    REQUIRE(pixels != nullptr);
    std::vector<unsigned char> rgb(pixels, pixels + 3 * std::size_t(w) * std::size_t(h));
    stbi_image_free(pixels);
    return rgb;
  };
  const auto placed =
      render(concat({R"({"file": ")", tif, R"(", "height": [0, 1], "georeferenced": true})"}),
             (dir.path() / "placed.png").string());
  const auto shifted = render(concat({R"({"file": ")", pfm, R"(", "height": [0, 1],
                                      "extent": [500010, -4200000, 500410, -4199700]})"}),
                              (dir.path() / "shifted.png").string());
  const auto same = render(concat({R"({"file": ")", pfm, R"(", "height": [0, 1],
                                     "extent": [500000, -4200000, 500400, -4199700]})"}),
                           (dir.path() / "given.png").string());
  CHECK(placed == same);
  CHECK(placed != shifted);  // the placement matters: ten metres east is another frame
}

TEST_CASE("unusableGeoreferencingIsRefusedNamingTheField", "[heightfield]") {
  test::TempDir dir("geotiff");
  const std::filesystem::path out = dir.path() / "out.png";
  const auto refused = [&](const test::GeoTiff& g, const std::string& message) {
    const std::string file = test::write_file(dir.path() / "f.tif", test::geotiff_bytes(g));
    test::require_refused(
        run({"render", "--set",
             concat({R"(terrain.heightfield={"file": ")", file, R"(", "georeferenced": true})"}),
             "--set", "viewport.width=32", "--set", "viewport.height=32", "-o", out.string()}),
        message, out);
  };
  test::GeoTiff g;
  g.top_row_first.assign(12, 0.5f);
  test::GeoTiff none = g;
  none.pixel_scale.clear();
  refused(none, "terrain.heightfield.georeferenced");
  refused(none, "has no ModelPixelScale with one ModelTiePoint");
  test::GeoTiff warped = g;
  warped.tie_points.insert(warped.tie_points.end(), {1, 1, 0, 500010.0, 4199990.0, 0});
  refused(warped, "has several tie points");
  test::GeoTiff rotated = g;
  rotated.transformation.assign(16, 0.0);
  refused(rotated, "ModelTransformation");
  test::GeoTiff degrees = g;
  degrees.geo_keys = {1024, 0, 1, 2};
  refused(degrees, "geographic degrees");
  test::GeoTiff miles = g;
  miles.geo_keys = {3076, 0, 1, 9035};
  refused(miles, "ProjLinearUnitsGeoKey 9035");
  test::GeoTiff vertical_feet = g;
  vertical_feet.geo_keys = {4099, 0, 1, 9002};
  refused(vertical_feet, "VerticalUnitsGeoKey 9002");
  test::GeoTiff elsewhere = g;  // the model type's value stored outside the directory
  elsewhere.geo_keys = {1024, 34736, 1, 0};
  refused(elsewhere, "GTModelTypeGeoKey nan");
  test::GeoTiff flat = g;
  flat.pixel_scale = {0.0, 10.0, 0.0};
  refused(flat, "ModelPixelScale 0, 10");
  test::GeoTiff far = g;
  far.tie_points = {0, 0, 0, 2e12, 0, 0};
  refused(far, "allowed within +-1e12");
  // Not a GeoTIFF at all: refused by the scene's rules before any file is read.
  const std::string pfm =
      test::write_file(dir.path() / "f.pfm", test::pfm_bytes(2, 2, {0, 1, 1, 0}));
  test::require_refused(
      run({"render", "--set",
           concat({R"(terrain.heightfield={"file": ")", pfm, R"(", "georeferenced": true})"}), "-o",
           out.string()}),
      "allowed only for a GeoTIFF", out);
  // A BigTIFF header, and a directory past the file's end.
  const std::string bigtiff =
      test::write_file(dir.path() / "b.tif", std::string("II\x2b\0\x08\0\0\0", 8));
  HeightFieldSettings s = tif_settings(bigtiff);
  CHECK_THROWS_WITH(georeferenced_extent(s, 4, 3), Catch::Contains("is a BigTIFF"));
  s.image = test::write_file(dir.path() / "c.tif", std::string("II\x2a\0\xff\0\0\0", 8));
  CHECK_THROWS_WITH(georeferenced_extent(s, 4, 3), Catch::Contains("reaching past its end"));
}

}  // namespace
}  // namespace relief
