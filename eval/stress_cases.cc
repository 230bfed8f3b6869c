#include "eval/stress_cases.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <utility>

#include "core/fbm.h"
#include "core/frame_plan.h"
#include "core/height_bounds.h"
#include "core/lattice.h"
#include "core/limits.h"
#include "pipeline/basis_resources.h"
#include "pipeline/job_memory.h"

namespace relief {

namespace {

// The shortest text that reads back as `v` (std::to_chars), so the overrides say exactly what
// was rendered.
std::string num(double v) {
  char text[32];
  return std::string(text, std::to_chars(text, text + sizeof text, v).ptr);
}

// Built by appending: GCC 12 warns falsely (-Wrestrict) on "literal" + std::string here.
std::string vec(double x, double y, double z) {
  std::string out(1, '[');
  out.append(num(x)).append(1, ',').append(num(y)).append(1, ',').append(num(z)).append(1, ']');
  return out;
}

std::string position(const Scene& base, double x, double y, double z) {
  std::string out("camera.position=");
  out.append(vec(base.camera.position[0] + x, y, base.camera.position[2] + z));
  return out;
}

// The terrain's period in x and z: P lattice cells of octave 0 (one basis image tile with
// terrain.basis). With an integer lacunarity every octave's lattice repeats within it, so a
// camera moved by whole periods sees the same terrain and the distance axis compares like with
// like.
double terrain_period(const Scene& base) {
  const double r = base.terrain.r;
  if (r != std::floor(r)) {
    return 0.0;
  }
  return base.terrain.basis ? base.terrain.basis->tile_size
                            : base.terrain.lattice_size * base.terrain.horizontal_scale;
}

// `distance` rounded to whole terrain periods (where there is one), within the camera's range.
double period_distance(const Scene& base, double distance) {
  const double period = terrain_period(base);
  double d = distance;
  if (period > 0 && distance >= period) {
    d = std::floor(distance / period) * period;
  }
  while (period > 0 && std::abs(base.camera.position[0] + d) > limits::kMaxCameraCoordinate) {
    d -= period;
  }
  return d;
}

// The world height of the full-detail terrain right under the base camera, in double.
double terrain_under_camera(const Scene& base, const NoiseLattice& lattice) {
  const TerrainPlan plan = make_terrain_plan(base.terrain, lattice, base.camera.position);
  const double octaves = base.terrain.last_octave - base.terrain.first_octave + 1;
  return base.camera.position[1] + fbm_height<double>(plan, 0.0, 0.0, octaves);
}

// The largest n in [lo, hi] for which fits(n) (fits(lo) assumed; fits decreasing in n).
template <class Fits>
int largest_fitting(int lo, int hi, Fits fits) {
  while (lo < hi) {
    const int mid = lo + (hi - lo + 1) / 2;
    if (fits(mid)) {
      lo = mid;
    } else {
      hi = mid - 1;
    }
  }
  return lo;
}

// The largest render estimate over `backends`, every per-pixel output requested (what a
// stress case renders).
std::uintmax_t largest_estimate(const Scene& scene, const std::vector<Backend>& backends) {
  const FrameOutputs all{true, true, true, true, true, true};
  std::uintmax_t bytes = 0;
  for (Backend backend : backends) {
    bytes = std::max(bytes, estimate_render_memory(scene, backend, all).total());
  }
  return bytes;
}

class CaseList {
 public:
  explicit CaseList(std::vector<StressCase>& cases) : cases_(cases) {}
  void add(std::string axis, std::string name, std::vector<std::string> overrides,
           std::string refused_naming = "", bool error_bounded = false) {
    cases_.push_back({std::move(axis),
                      std::move(name),
                      std::move(overrides),
                      std::move(refused_naming),
                      {},
                      error_bounded});
  }
  // The last case added is refused on these backends only.
  void refuse_only_on(std::vector<std::string> backends) {
    cases_.back().refused_backends = std::move(backends);
  }

 private:
  std::vector<StressCase>& cases_;
};

void add_camera_cases(CaseList& list, const Scene& base, const NoiseLattice& lattice) {
  const double y = base.camera.position[1];
  for (double distance : {0.0, 1e3, 1e6, 1e9, 1e12}) {
    const double d = period_distance(base, distance);
    list.add("distance", "x + " + num(d), {position(base, d, y, 0)}, "", true);
  }
  const HeightBounds bounds = derive_height_bounds(lattice, base.terrain);
  const double ground = terrain_under_camera(base, lattice);
  list.add("altitude", "0.01 above the highest possible terrain",
           {position(base, 0, bounds.world_max + 0.01, 0)});
  list.add("altitude", "0.01 above the terrain under the camera",
           {position(base, 0, ground + 0.01, 0)});
  for (double altitude : {1e4, 1e5, 1e6}) {
    list.add("altitude", "y = " + num(altitude), {position(base, 0, altitude, 0)});
  }
  const double lift = limits::kMaxBaseHeight - base.terrain.base_height;
  std::vector<std::string> lifted = {"terrain.base_height=" + num(limits::kMaxBaseHeight),
                                     position(base, 0, y + lift, 0)};
  if (base.terrain.water_level) {
    lifted.push_back("terrain.water_level=" +
                     num(std::min(*base.terrain.water_level + lift, limits::kMaxBaseHeight)));
  }
  list.add("altitude", "base height 1e7, camera lifted with it", lifted);
  // On a planet the water level left behind lies 1e7 below the datum: past the centre of a
  // planet smaller than that, which the scene's rule refuses by name.
  const PlanetSettings* planet = base.terrain.planet ? &*base.terrain.planet : nullptr;
  const bool water_past_centre = planet && planet->radius != 0.0 && base.terrain.water_level &&
                                 !(planet->radius + (*base.terrain.water_level - 1e7) > 0.0);
  list.add("altitude", "base height 1e7, camera not lifted (inside the terrain)",
           {"terrain.base_height=1e7"}, water_past_centre ? "terrain.water_level" : "");
  list.add("altitude", "base height -1e7, camera not lifted", {"terrain.base_height=-1e7"});
  list.add("altitude", "base height 1e7 + 1", {"terrain.base_height=10000001"},
           "terrain.base_height");

  for (double pitch : {-90.0, -45.0, -0.01, 0.0, 0.01, 45.0, 90.0}) {
    list.add("pitch", "pitch " + num(pitch), {"camera.pitch_deg=" + num(pitch)});
  }
  list.add("pitch", "pitch -90.01", {"camera.pitch_deg=-90.01"}, "camera.pitch_deg");
  list.add("position", "below the highest possible terrain",
           {position(base, 0, ground + 0.5 * (bounds.world_max - ground), 0)});
  list.add("position", "10 under the surface", {position(base, 0, ground - 10, 0)});
  list.add("position", "10 under water, 10 above the ground",
           {position(base, 0, ground + 10, 0), "terrain.water_level=" + num(ground + 20)});
}

void add_terrain_cases(CaseList& list, const Scene& base) {
  const std::string on = "terrain.warp.enabled=true";
  list.add("warp", "warped, default c1 c2 c3", {on});
  list.add("warp", "c3 = 0", {on, "terrain.warp.c3=[0,0]"});
  list.add("warp", "c3 = 1e-30", {on, "terrain.warp.c3=[1e-30,1e-30]"});
  list.add("warp", "c3 < 0", {on, "terrain.warp.c3=[-0.11,-0.17]"});
  list.add("warp", "c1 = 0", {on, "terrain.warp.c1=[0,0]"});
  list.add("warp", "c1 < 0", {on, "terrain.warp.c1=[-0.35,-0.16]"});
  list.add("warp", "r0 = 1e-30", {on, "terrain.warp.r0=[1e-30,0]"});
  // R = r^H - h crosses zero wherever the partial height passes r^H = 1.035 (H = 0.05).
  list.add("warp", "H = 0.05: R through 0 often", {on, "terrain.H=0.05"});
  list.add("warp", "every component 100",
           {on, "terrain.warp.c1=[100,100]", "terrain.warp.c2=[100,100]",
            "terrain.warp.c3=[100,100]", "terrain.warp.t0=[100,100]"});
  list.add("warp", "c3 = 101", {on, "terrain.warp.c3=[101,0]"}, "terrain.warp.c3");

  const double h_rule = std::ldexp(1.0, -10);  // H log2 r >= 2^-10 (scene-limits.md)
  list.add("H", "H = 2^-10 (r = 2, amplitude LOD)", {"terrain.r=2", "terrain.H=" + num(h_rule)});
  list.add("H", "H = 0.00025 at r = 2", {"terrain.r=2", "terrain.H=0.00025"}, "terrain.H");
  list.add("H", "H = 0.00025, r = 16",
           {"terrain.r=16", "terrain.last_octave=10", "terrain.H=0.00025"});
  list.add("H", "H = 0.00025, nyquist LOD", {"terrain.lod.criterion=nyquist", "terrain.H=0.00025"});
  list.add("H", "H = 0.5", {"terrain.H=0.5"});
  list.add("H", "H = 1", {"terrain.H=1"});
  list.add("H", "H = 0", {"terrain.H=0"}, "terrain.H");
  list.add("H", "H = nextafter(1, 2)", {"terrain.H=" + num(std::nextafter(1.0, 2.0))}, "terrain.H");

  list.add("r", "r = 1.001", {"terrain.r=1.001"});
  list.add("r", "r = nextafter(1.001, 2)", {"terrain.r=" + num(std::nextafter(1.001, 2.0))});
  list.add("r", "r = 1", {"terrain.r=1"}, "terrain.r");
  list.add("r", "r = 16, 11 octaves", {"terrain.r=16", "terrain.last_octave=10"});
  list.add("r", "r = 16, 15 octaves",
           {"terrain.r=16", "terrain.first_octave=0", "terrain.last_octave=14"},
           "terrain.last_octave");
  list.add("r", "r = nextafter(16, 17)", {"terrain.r=" + num(std::nextafter(16.0, 17.0))},
           "terrain.r");

  list.add("octaves", "1 octave", {"terrain.first_octave=0", "terrain.last_octave=0"});
  list.add("octaves", "0 octaves far away (bias -8)",
           {"terrain.first_octave=0", "terrain.last_octave=0", "terrain.lod.bias=-8"});
  list.add("octaves", "24 octaves (0..23)", {"terrain.first_octave=0", "terrain.last_octave=23"});
  if (base.terrain.basis) {
    // Basis images set the octave-0 cell by tile_size / P: even the largest tile puts the
    // coarsest coordinate of octave 32 at the farthest footprint past 2^24, which the scene's
    // rule refuses by name.
    list.add("octaves", "octaves 32..40 (r^k = 2^40)",
             {"terrain.r=2", "terrain.first_octave=32", "terrain.last_octave=40"},
             "terrain.basis.tile_size");
  } else {
    list.add(
        "octaves", "octaves 32..40 (r^k = 2^40)",
        {"terrain.r=2", "terrain.first_octave=32", "terrain.last_octave=40",
         // the coarsest lattice coordinate at the farthest footprint below 2^24 (for the
         // default camera.far, which a preset's may exceed)
         "terrain.horizontal_scale=1e8", "camera.far=60000"},
        // a planet's far side lies farther than any footprint: its own rule refuses it
        base.terrain.planet && base.terrain.planet->radius != 0.0 ? "terrain.planet.radius" : "");
  }
  list.add("octaves", "25 octaves", {"terrain.first_octave=0", "terrain.last_octave=24"},
           "terrain.last_octave");
}

void add_size_cases(CaseList& list, const Scene& base, std::uintmax_t budget,
                    const std::vector<Backend>& backends) {
  const auto grid = [](int w, int h) {
    return std::vector<std::string>{"grid.width=" + std::to_string(w),
                                    "grid.height=" + std::to_string(h)};
  };
  const auto with_margin = [](std::vector<std::string> v, int margin) {
    v.push_back("grid.margin=" + std::to_string(margin));
    return v;
  };
  const int max_grid = limits::kMaxGridSide;
  // The rasteriser's set-up triangles and bins are counted only once the triangles are set up
  // (job_memory.h): the largest cases leave them a tenth of the budget.
  const std::uintmax_t fitting_budget = budget - budget / 10;
  list.add("grid", "2x2, margin 0", with_margin(grid(2, 2), 0));
  list.add("grid", "3x3, margin 0", with_margin(grid(3, 3), 0));
  list.add("grid", "6x6, margin 2", with_margin(grid(6, 6), 2));
  Scene sized = base;
  // The narrow grids: set-up's scratch holds a chunk's rows for every thread (job_memory.cc),
  // 1.1 MiB a thread on 2 x 8192, so whether they fit depends on the machine's threads (16
  // threads need 17 MiB of it) and on the backend (GL sets up no triangles): refused by name
  // on the backends whose estimate exceeds the budget.
  for (const auto& [w, h] : {std::pair{2, max_grid}, std::pair{max_grid, 2}}) {
    sized.grid.width = w;
    sized.grid.height = h;
    sized.grid.margin = 0;
    const std::string size = std::to_string(w) + "x" + std::to_string(h);
    std::vector<std::string> refusing;
    for (const Backend backend : backends) {
      if (largest_estimate(sized, {backend}) > budget) {
        refusing.emplace_back(backend_name(backend));
      }
    }
    list.add("grid", size + ", margin 0", with_margin(grid(w, h), 0),
             refusing.empty() ? "" : "grid " + size);
    if (refusing.size() < backends.size()) {
      list.refuse_only_on(std::move(refusing));
    }
  }
  sized = base;
  // GL draws from one index buffer of 3 x 4 bytes a triangle, two triangles a cell, bound as a
  // storage block: GL 4.5 guarantees 2^27 bytes of one (GL_MAX_SHADER_STORAGE_BLOCK_SIZE,
  // table 23.64); a larger grid may be refused by a conforming GL (llvmpipe's limit is that).
  const bool gl = std::find(backends.begin(), backends.end(), Backend::kGl) != backends.end();
  const auto gl_draws = [&](int side) {
    const std::uintmax_t cells = std::uintmax_t(side - 1) * std::uintmax_t(side - 1);
    return !gl || 2 * 3 * 4 * cells <= (std::uintmax_t{1} << 27);
  };
  const int fitting_grid = largest_fitting(base.grid.width, max_grid, [&](int side) {
    sized.grid.width = sized.grid.height = side;
    return largest_estimate(sized, backends) <= fitting_budget && gl_draws(side);
  });
  list.add("grid",
           "largest within the budget: " + std::to_string(fitting_grid) + "x" +
               std::to_string(fitting_grid),
           grid(fitting_grid, fitting_grid));
  sized.grid.width = sized.grid.height = max_grid;
  const bool max_grid_fits = largest_estimate(sized, backends) <= budget;
  list.add("grid", "8192x8192", grid(max_grid, max_grid), max_grid_fits ? "" : "grid 8192x8192");
  list.add("grid", "8193x8193", grid(max_grid + 1, max_grid + 1), "grid.width");

  const auto viewport = [](int w, int h) {
    return std::vector<std::string>{"viewport.width=" + std::to_string(w),
                                    "viewport.height=" + std::to_string(h)};
  };
  const int max_side = limits::kMaxViewportSide;
  list.add("viewport", "1x1", viewport(1, 1));
  list.add("viewport", "1x2", viewport(1, 2));
  list.add("viewport", "3x1", viewport(3, 1));
  list.add("viewport", "1x16384", viewport(1, max_side), "camera.fov_y_deg");
  sized = base;
  const int fitting_side = largest_fitting(base.viewport.width, max_side, [&](int side) {
    sized.viewport.width = sized.viewport.height = side;
    return largest_estimate(sized, backends) <= fitting_budget;
  });
  list.add("viewport",
           "largest within the budget: " + std::to_string(fitting_side) + "x" +
               std::to_string(fitting_side),
           viewport(fitting_side, fitting_side));
  sized.viewport.width = sized.viewport.height = max_side;
  const bool max_viewport_fits = largest_estimate(sized, backends) <= budget;
  list.add("viewport", "16384x16384", viewport(max_side, max_side),
           max_viewport_fits ? "" : "image 16384x16384");
  list.add("viewport", "16385x16385", viewport(max_side + 1, max_side + 1), "viewport.width");
}

}  // namespace

std::vector<StressCase> make_stress_cases(const Scene& base, std::uintmax_t budget_bytes,
                                          const std::vector<Backend>& backends) {
  const std::optional<NoiseLattice> basis = load_basis_grid(base);  // stage 3's grid
  const NoiseLattice lattice =
      basis ? *basis : make_noise_lattice(base.terrain.seed, base.terrain.lattice_size);
  std::vector<StressCase> cases;
  CaseList list(cases);
  add_camera_cases(list, base, lattice);
  add_terrain_cases(list, base);
  add_size_cases(list, base, budget_bytes, backends);
  return cases;
}

std::vector<std::string> stress_axes() {
  return {"distance", "altitude", "pitch",   "position", "warp",
          "H",        "r",        "octaves", "grid",     "viewport"};
}

}  // namespace relief
