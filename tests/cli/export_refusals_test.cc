// relief export's refusals (tools/export_files.h, plan_export): every bad region, size, output
// name and combination refused with exit 2, the option and the value named, nothing written.
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "tests/support/cli_support.h"
#include "tests/support/test_support.h"

namespace relief {
namespace {

using test::run;

TEST_CASE("badExportRequestsAreRefusedWithNothingWritten", "[cli]") {
  test::TempDir dir("export");
  const std::string out = (dir.path() / "h.png").string();
  const std::string region[] = {"--region", "0", "0", "100", "100"};
  const auto refused = [&](std::vector<std::string> args, const std::string& message) {
    args.insert(args.begin(), "export");
    args.push_back("-o");
    args.push_back(out);
    test::require_refused(run(args), message, out);
  };
  refused({"--size", "64"}, "--region is required");
  refused({"planet", region[0], region[1], region[2], region[3], region[4], "--size", "8"},
          "terrain.planet");
  refused({"--region", "0", "0", "0", "100", "--size", "8"}, "reversed or narrower than 0.001");
  refused({"--region", "100", "0", "0", "100", "--size", "8"}, "reversed or narrower than 0.001");
  refused({"--region", "0", "0", "2e12", "100", "--size", "8"}, "x1 2e+12 is out of range");
  refused({"--region", "0", "0", "nan", "100", "--size", "8"}, "--region");
  refused({"--region", "0", "0", "inf", "100", "--size", "8"}, "--region");
  for (const std::string size :
       {"1", "16386", "8x1", "8x", "x8", "1e3", "99999999999", "-4", "8x8x8"}) {
    refused({region[0], region[1], region[2], region[3], region[4], "--size", size},
            "--size " + size + " is not N or WxH with each side 2 to 16385");
  }
  refused({"--region", "0", "0", "1", "1000", "--size", "100"}, "give both");
  refused({region[0], region[1], region[2], region[3], region[4], "--size", "8", "--mesh",
           (dir.path() / "m.stl").string()},
          ".obj or .glb");
  refused({region[0], region[1], region[2], region[3], region[4], "--size", "5000", "--mesh",
           (dir.path() / "m.obj").string()},
          "too large for a mesh");
  refused({region[0], region[1], region[2], region[3], region[4], "--size", "8", "--normals",
           (dir.path() / "n.bmp").string()},
          ".png (8 bits), .pfm or .exr");
  refused({region[0], region[1], region[2], region[3], region[4], "--size", "8", "--json", out},
          "same file");
  refused({region[0], region[1], region[2], region[3], region[4], "--size", "8", "--normals",
           (dir.path() / "no" / "n.png").string()},
          "--normals");
  refused({region[0], region[1], region[2], region[3], region[4], "--size", "16385", "--max-memory",
           "64M"},
          "memory");
  const auto refused_alone = [&](std::vector<std::string> args, const std::string& message) {
    args.insert(args.begin(), "export");
    test::require_refused(run(args), message, out);
  };
  refused_alone({region[0], region[1], region[2], region[3], region[4], "--size", "8"},
                "nothing to export");
  refused_alone({region[0], region[1], region[2], region[3], region[4], "--size", "8", "--normals",
                 (dir.path() / "n.png").string(), "--scene-out", (dir.path() / "s.json").string()},
                "--scene-out needs -o");
  refused({region[0], region[1], region[2], region[3], region[4], "--size", "8", "--splat",
           (dir.path() / "").string()},
          "no file name part");
  refused({region[0], region[1], region[2], region[3], region[4], "--size", "4", "--size", "8"},
          "--size");  // given twice
  // Cells a double cannot tell apart so far out (found by a hostile pass: zero-area triangles).
  refused({"--region", "999999999999.998", "0", "1e12", "0.002", "--size", "64"},
          "too fine for coordinates near 1e+12");
  refused_alone(
      {region[0], region[1], region[2], region[3], region[4], "--size", "8", "--scene-out",
       (dir.path() / "s.json").string(), "-o", (dir.path() / "\xff.png").string()},
      "UTF-8");
  CHECK(dir.empty());
}

}  // namespace
}  // namespace relief
