// The stage table's homes (pipeline/stage_table.h) and the CPU kernel table
// (pipeline/cpu_kernels.h): every stage names a portable, a Highway and a GLSL implementation
// or the reason it has none, its test and its doc section, and they exist; every kernel the
// simd backend runs portable says why, and the table's pointers are the kinds it reports.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <string_view>

#include "pipeline/cpu_kernels.h"
#include "pipeline/stage_table.h"

namespace relief {
namespace {

const std::filesystem::path kSource = RELIEF_SOURCE_DIR;

std::string file_text(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// A home is a path under the repository, or "none: " and a reason of a few words at least.
void check_home(const char* stage, const char* what, const char* home, bool may_be_none) {
  INFO(stage << " / " << what << ": " << (home ? home : "(null)"));
  REQUIRE(home != nullptr);
  const std::string_view text = home;
  if (text.starts_with("none")) {
    CHECK(may_be_none);
    REQUIRE(text.starts_with("none: "));
    CHECK(text.size() - 6 >= 20);  // a reason, not a word
    return;
  }
  CHECK(std::filesystem::is_regular_file(kSource / text));
}

TEST_CASE("everyStageNamesItsImplementationsTestAndDocOrWhyNot", "[pipeline]") {
  for (const StageInfo& stage : kFrameStages) {
    const StageHomes& h = stage.homes;
    check_home(stage.name, "portable", h.portable, false);
    check_home(stage.name, "highway", h.highway, true);
    check_home(stage.name, "glsl", h.glsl, true);
    check_home(stage.name, "test", h.test, false);
    const std::string_view doc = h.doc;
    const std::size_t hash = doc.find('#');
    INFO(stage.name << " doc: " << doc);
    REQUIRE(hash != std::string_view::npos);
    const std::filesystem::path file = kSource / std::string(doc.substr(0, hash));
    REQUIRE(std::filesystem::is_regular_file(file));
    // The heading, at any level, as a line of its own.
    std::string heading(1, ' ');
    heading.append(doc.substr(hash + 1));
    heading.push_back('\n');
    const std::string text = file_text(file);
    bool found = false;
    for (std::size_t at = text.find(heading); at != std::string::npos;
         at = text.find(heading, at + 1)) {
      std::size_t start = at;
      while (start > 0 && text[start - 1] == '#') {
        --start;
      }
      found = found || (start < at && (start == 0 || text[start - 1] == '\n'));
    }
    CHECK(found);
  }
}

// The kind of each reported kernel against the pointer the table holds: Highway exactly where
// the simd table's entry differs from the portable one.
template <class Real>
void check_pointers_match_kinds(const CpuKernels<Real>& table, const CpuKernels<Real>& portable) {
  for (const KernelChoice& c : table.choices) {
    const std::string_view name = c.kernel;
    INFO("kernel " << name);
    const bool highway = c.kind == KernelKind::kHighway;
    if (name == "projected domain") {
      CHECK((table.project_domain != portable.project_domain) == highway);
    } else if (name == "planet domain") {
      CHECK((table.project_planet_domain != portable.project_planet_domain) == highway);
    } else if (name == "planet bend") {
      CHECK((table.bend_vertices != portable.bend_vertices) == highway);
    } else if (name == "planet normals") {
      CHECK((table.bend_normals != portable.bend_normals) == highway);
    } else if (name == "vertex outcodes") {
      CHECK((table.vertex_outcodes != portable.vertex_outcodes) == highway);
    } else if (name == "fBm") {
      CHECK((table.fractal != portable.fractal) == highway);
    } else if (name == "sketch") {
      CHECK((table.sketch != portable.sketch) == highway);
    } else if (name == "surface") {
      CHECK((table.surface != portable.surface) == highway);
    } else if (name == "vertex transform") {
      CHECK((table.transform != portable.transform) == highway);
    } else if (name == "vertex lighting") {
      CHECK((table.light_vertices != portable.light_vertices) == highway);
    } else if (name == "vertex snap") {
      CHECK((table.snap != nullptr) == highway);
    } else if (name == "tile raster") {
      CHECK((table.tiles.raster == KernelKind::kHighway) == highway);
    } else if (name == "tile resolve") {
      CHECK((table.tiles.resolve == KernelKind::kHighway) == highway);
    } else if (name == "sun's share") {
      CHECK((table.tiles.sun == KernelKind::kHighway) == highway);
    } else if (name == "sky's share") {
      CHECK((table.tiles.sky == KernelKind::kHighway) == highway);
    } else if (name == "reflected rays' set-up") {
      CHECK((table.tiles.reflect == KernelKind::kHighway) == highway);
    } else if (name == "tile shade") {
      CHECK((table.tiles.shade == KernelKind::kHighway) == highway);
    } else if (name == "tile encode") {
      CHECK((table.tiles.encode == KernelKind::kHighway) == highway);
    } else {
      // A kernel with one kind only (set-up, binning, the reflected rays' march).
      CHECK_FALSE(highway);
    }
  }
}

TEST_CASE("theReferenceBackendsRunEveryKernelPortableWithoutExcuse", "[pipeline]") {
  for (const bool planet : {false, true}) {
    const CpuKernels<float> f = cpu_kernels<float>(Backend::kReference, planet);
    const CpuKernels<double> d = cpu_kernels<double>(Backend::kReferenceDouble, planet);
    REQUIRE(f.choices.size() == d.choices.size());
    for (const KernelChoice& c : f.choices) {
      CHECK(c.kind == KernelKind::kPortable);
      CHECK(std::string_view(c.reason).empty());
    }
    for (const KernelChoice& c : d.choices) {
      CHECK(c.kind == KernelKind::kPortable);
    }
    check_pointers_match_kinds(f, portable_kernels<float>(planet));
    check_pointers_match_kinds(d, portable_kernels<double>(planet));
  }
}

TEST_CASE("theSimdBackendStatesWhyEachPortableKernelIsNotHighway", "[pipeline][simd]") {
  for (const bool planet : {false, true}) {
    const CpuKernels<float> simd = cpu_kernels<float>(Backend::kSimd, planet);
    check_pointers_match_kinds(simd, portable_kernels<float>(planet));
    for (const KernelChoice& c : simd.choices) {
      INFO((planet ? "planet " : "plane ") << c.kernel);
      CHECK((c.kind == KernelKind::kHighway) == std::string_view(c.reason).empty());
    }
    // The stage table's Highway homes and the kernel table agree: a stage with a Highway file
    // runs one on the plane; a stage whose Highway home is "none" runs none anywhere.
    for (const StageInfo& stage : kFrameStages) {
      bool any_highway = false;
      for (const KernelChoice& c : simd.choices) {
        any_highway = any_highway || (c.stage == stage.id && c.kind == KernelKind::kHighway);
      }
      INFO(stage.name);
      if (std::string_view(stage.homes.highway).starts_with("none")) {
        CHECK_FALSE(any_highway);
      } else if (!planet) {
        CHECK(any_highway);
      }
    }
  }
  // The reported reasons reach the reports (--stats, relief info).
  const std::vector<KernelReport> reports =
      kernel_reports(cpu_kernels<float>(Backend::kSimd, true).choices, false);
  bool binning_reported = false;
  for (const KernelReport& r : reports) {
    if (r.kernel == "binning") {
      binning_reported = r.implementation == "portable loop (float)" && !r.reason.empty();
    }
  }
  CHECK(binning_reported);
}

TEST_CASE("aBackendThatIsNotACpuFloatOneHasNoFloatKernelTable", "[pipeline]") {
  CHECK_THROWS(cpu_kernels<float>(Backend::kGl, false));
  CHECK_THROWS(cpu_kernels<float>(Backend::kReferenceDouble, false));
  CHECK_THROWS(cpu_kernels<double>(Backend::kSimd, false));
}

}  // namespace
}  // namespace relief
