// `import relief` (docs/python.md): Relief's scenes, frames, stage buffers and image comparison
// from Python, for test suites written in pytest. Images and buffers come back as numpy arrays
// that view the frame's own memory (no copy: a frame's rows are stored bottom to top, so the
// arrays have a negative row stride and read top row first, as the PNG does). Bad input raises
// relief.SceneError (a ValueError) carrying the field and the command line's exit code.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <tbb/global_control.h>

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/scene/json_input.h"
#include "core/scene/scene_json.h"
#include "image/image_io.h"
#include "image/image_metadata.h"
#include "pipeline/build_info.h"
#include "pipeline/frame.h"
#include "pipeline/job_memory.h"
#include "pipeline/memory_budget.h"
#include "pipeline/scene_resources.h"
#include "tools/image_compare.h"

namespace py = pybind11;

namespace relief {
namespace {

// A scene and, once a frame needed them, its resources (textures, lattice: scene_resources.h),
// dropped when a field changes.
struct PyScene {
  Scene scene;
  std::shared_ptr<const SceneResources> resources;

  const SceneResources& loaded() {
    if (!resources) {
      check_memory(estimate_scene_resources_memory(scene), memory_budget(std::nullopt, ""),
                   "loading the scene's files", "Use smaller textures, sketch or basis images");
      resources = std::make_shared<const SceneResources>(load_scene_resources(scene));
    }
    return *resources;
  }
};

py::object json_to_python(const nlohmann::json& value) {
  return py::module_::import("json").attr("loads")(value.dump());
}

std::string python_to_json(const py::handle& value) {
  return py::module_::import("json").attr("dumps")(value).cast<std::string>();
}

PyScene make_scene(const std::string& name, const std::vector<std::string>& overrides) {
  return PyScene{resolve_scene(name, overrides), nullptr};
}

// relief.Scene.set: one field, validated like --set and then the whole scene.
void set_field(PyScene& s, const std::string& key, const py::handle& value) {
  Scene scene = s.scene;
  const std::string assignment = key + "=" + python_to_json(value);
  apply_scene_layer(scene, parse_override(assignment), "relief.Scene.set(" + key + ")");
  validate_scene(scene);
  // Kept where the new scene loads the same resources (a camera, viewport, lighting, grid or
  // output field), and with them what the GL backend keeps uploaded between frames
  // (pipeline/gl_scene_cache.h): an animation moving the camera loads and uploads nothing again.
  if (!same_resource_inputs(s.scene, scene)) {
    s.resources.reset();
  }
  s.scene = std::move(scene);
}

py::object get_field(const PyScene& s, const std::string& key) {
  nlohmann::json value = scene_to_json(s.scene);
  std::size_t start = 0;
  while (start <= key.size()) {
    const std::size_t dot = std::min(key.find('.', start), key.size());
    const std::string part = key.substr(start, dot - start);
    if (!value.is_object() || !value.contains(part)) {
      throw py::key_error("no scene field '" + key + "'");
    }
    value = nlohmann::json(value[part]);
    start = dot + 1;
  }
  return json_to_python(value);
}

// A frame kept alive by the arrays that view it.
struct PyFrame {
  Frame frame;
};

// A read-only numpy array over `data`, which `owner` keeps alive (the array holds a copy of
// the shared pointer): a view, never a copy.
template <class T, class Owner>
py::object readonly_view(const std::shared_ptr<Owner>& owner, const T* data,
                         std::vector<py::ssize_t> shape, std::vector<py::ssize_t> strides) {
  py::capsule base(new std::shared_ptr<Owner>(owner),
                   [](void* p) { delete static_cast<std::shared_ptr<Owner>*>(p); });
  py::array out(py::dtype::of<T>(), std::move(shape), std::move(strides), data, base);
  py::detail::array_proxy(out.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
  return out;
}

// rows x cols [x channels] of `data`, stored bottom row first, viewed top row first.
template <class T>
py::object view(const std::shared_ptr<PyFrame>& owner, const std::vector<T>& data, int channels) {
  const FrameImage& image = owner->frame.image;
  if (data.empty()) {
    return py::none();
  }
  const auto row = static_cast<py::ssize_t>(sizeof(T)) * image.width * channels;
  const T* top = data.data() + std::size_t(image.height - 1) * image.width * channels;
  std::vector<py::ssize_t> shape = {image.height, image.width};
  std::vector<py::ssize_t> strides = {-row, static_cast<py::ssize_t>(sizeof(T)) * channels};
  if (channels > 1) {
    shape.push_back(channels);
    strides.push_back(sizeof(T));
  }
  return readonly_view(owner, top, std::move(shape), std::move(strides));
}

Backend backend_named(const std::string& name) {
  const std::optional<Backend> backend = backend_from_name(name);
  if (!backend) {
    throw SceneError("backend", "backend '" + name + "' is not one of reference, " +
                                    "reference-double, simd, gl");
  }
  return *backend;
}

py::dict render(PyScene& s, const std::string& backend_name, const std::vector<std::string>& extra,
                int threads, const std::string& max_memory) {
  if (threads < 0 || threads > 1024) {
    throw SceneError("threads", "threads = " + std::to_string(threads) +
                                    " is out of range; allowed 0 (every core) to 1024");
  }
  FrameRequest request;
  request.backend = backend_named(backend_name);
  for (const std::string& output : extra) {
    bool* flag = output == "linear"      ? &request.outputs.linear
                 : output == "depth"     ? &request.outputs.depth
                 : output == "primitive" ? &request.outputs.primitive
                 : output == "normal"    ? &request.outputs.normal
                 : output == "height"    ? &request.outputs.world_height
                 : output == "octaves"   ? &request.outputs.octaves
                                         : nullptr;
    if (!flag) {
      throw SceneError("outputs", "output '" + output + "' is not one of linear, depth, " +
                                      "primitive, normal, height, octaves");
    }
    *flag = true;
  }
  const std::optional<std::uintmax_t> memory_limit = parse_memory_size(max_memory);
  if (!max_memory.empty() && !memory_limit) {
    throw SceneError("max_memory", "max_memory = '" + max_memory +
                                       "' is not a size such as 2G, 512M or 1000000 (bytes)");
  }
  const MemoryBudget budget = memory_budget(memory_limit, max_memory);
  const MemoryEstimate estimate = estimate_render_memory(s.scene, request.backend, request.outputs);
  check_memory(estimate, budget, "this render", "Lower viewport.width/height or grid.width/height");
  request.max_bin_bytes = memory_left(estimate, budget);
  const SceneResources& resources = s.loaded();
  auto owner = std::make_shared<PyFrame>();
  {
    const py::gil_scoped_release unlocked;
    std::unique_ptr<tbb::global_control> limit;
    if (threads > 0) {
      limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                    std::size_t(threads));
    }
    owner->frame = render_frame(s.scene, resources, request);
  }
  const FrameImage& image = owner->frame.image;
  py::dict out;
  out["image"] = view(owner, image.srgb, 3);
  out["linear"] = view(owner, image.linear, 3);
  out["depth"] = view(owner, image.depth, 1);
  out["primitive"] = view(owner, image.primitive, 1);
  out["normal"] = view(owner, image.normal, 3);
  out["height"] = view(owner, image.world_height, 1);
  out["octaves"] = view(owner, image.octaves, 1);
  py::dict stages;
  for (const StageTime& stage : owner->frame.stats.stages) {
    py::dict counters;
    for (const WorkCounter& c : stage.counters) {
      counters[py::str(c.name)] = c.value;
    }
    stages[py::str(stage.name)] = py::dict(py::arg("ms") = stage.ms, py::arg("ran") = stage.ran,
                                           py::arg("counters") = counters);
  }
  out["stats"] =
      py::dict(py::arg("total_ms") = owner->frame.stats.total_ms, py::arg("stages") = stages);
  const std::vector<unsigned char> png =
      encode_png_rgb(image.width, image.height, image.srgb, scene_metadata(s.scene));
  out["png"] = py::bytes(reinterpret_cast<const char*>(png.data()), png.size());
  return out;
}

// relief stages' buffers (stages 1-4) as (grid rows, grid columns) arrays, row 0 first.
py::dict stages(PyScene& s, const std::string& backend_name) {
  const Backend backend = backend_named(backend_name);
  if (backend == Backend::kReferenceDouble) {
    throw SceneError("backend", "relief.stages runs in float: reference, simd or gl");
  }
  const SceneResources& resources = s.loaded();
  auto run = std::make_shared<TerrainRun<float>>(run_terrain_stages<float>(
      s.scene, resources.terrain_values(), backend, resources.sketch_or_null()));
  const GridLayout& layout = run->grid.layout;
  const auto buffer = [&](const auto& values) -> py::object {
    using T = typename std::decay_t<decltype(values)>::value_type;
    if (values.empty()) {
      return py::none();
    }
    return readonly_view(
        run, values.data(), {layout.height, layout.width},
        {static_cast<py::ssize_t>(sizeof(T)) * layout.pitch, static_cast<py::ssize_t>(sizeof(T))});
  };
  const GridBuffers<float>& g = run->grid;
  py::dict out;
  for (const auto& [name, values] : {std::pair{"dx", &g.dx},
                                     {"dz", &g.dz},
                                     {"sigma", &g.sigma},
                                     {"nu", &g.nu},
                                     {"height", &g.height},
                                     {"nx", &g.nx},
                                     {"ny", &g.ny},
                                     {"nz", &g.nz},
                                     {"slope", &g.slope},
                                     {"water_depth", &g.water_depth}}) {
    out[name] = buffer(*values);
  }
  out["valid"] = buffer(g.valid);
  return out;
}

// relief compare's figures for two arrays of one shape: (rows, columns[, channels]).
py::dict compare(const py::array_t<float, py::array::c_style | py::array::forcecast>& a,
                 const py::array_t<float, py::array::c_style | py::array::forcecast>& b, float fail,
                 float warn) {
  const auto image = [](const py::array_t<float, py::array::c_style | py::array::forcecast>& x) {
    if (x.ndim() != 2 && x.ndim() != 3) {
      throw SceneError("compare",
                       "an image is a (rows, columns) or (rows, columns, channels) "
                       "array");
    }
    FloatImage out;
    out.height = static_cast<int>(x.shape(0));
    out.width = static_cast<int>(x.shape(1));
    out.channels = x.ndim() == 3 ? static_cast<int>(x.shape(2)) : 1;
    out.pixels.assign(x.data(), x.data() + x.size());
    return out;
  };
  CompareThresholds thresholds;
  thresholds.fail = fail;
  thresholds.warn = warn;
  const CompareResult r = compare_images(image(a), image(b), thresholds);
  return py::dict(py::arg("verdict") = std::string(verdict_name(r.verdict)),
                  py::arg("exit_code") = exit_code(r.verdict), py::arg("problem") = r.problem,
                  py::arg("mean_error") = r.mean_error, py::arg("rms_error") = r.rms_error,
                  py::arg("psnr") = r.psnr, py::arg("max_error") = r.max_error,
                  py::arg("max_x") = r.max_x, py::arg("max_y") = r.max_y,
                  py::arg("fail_pixels") = r.fail_pixels, py::arg("warn_pixels") = r.warn_pixels);
}

}  // namespace
}  // namespace relief

PYBIND11_MODULE(relief, m) {
  using namespace relief;
  m.doc() = "Relief: deterministic reference renders of procedural terrain (docs/python.md)";
  m.attr("__version__") = std::string(relief_version());
  // Bad input: the command line's exit code 2, with the scene field it concerns.
  static py::exception<SceneError> scene_error(m, "SceneError", PyExc_ValueError);
  static py::exception<MemoryLimitError> memory_error(m, "MemoryLimitError", PyExc_MemoryError);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) {
        std::rethrow_exception(p);
      }
    } catch (const SceneError& e) {
      py::object error = py::reinterpret_borrow<py::object>(scene_error)(e.what());
      error.attr("field") = e.path();
      error.attr("exit_code") = 2;
      PyErr_SetObject(scene_error.ptr(), error.ptr());
    } catch (const MemoryLimitError& e) {
      PyErr_SetString(memory_error.ptr(), e.what());
    }
  });
  m.def("presets", &preset_names, "The built-in presets' names");
  py::class_<PyScene>(m, "Scene", "A validated scene: a preset or JSON file, then overrides")
      .def(py::init(&make_scene), py::arg("name") = "default",
           py::arg("overrides") = std::vector<std::string>{})
      .def("set", &set_field, py::arg("key"), py::arg("value"),
           "Set one field (a dotted path, as --set), validated with the whole scene")
      .def("get", &get_field, py::arg("key"), "A field's value (a dotted path)")
      .def_property_readonly("json", [](const PyScene& s) { return scene_json_text(s.scene); });
  m.def("render", &render, py::arg("scene"), py::arg("backend") = "simd",
        py::arg("outputs") = std::vector<std::string>{}, py::arg("threads") = 0,
        py::arg("max_memory") = "",
        "Render a frame (max_memory as relief's --max-memory: 2G, 512M; empty: the machine's "
        "available memory): a dict of numpy arrays (image, and the requested linear, depth, "
        "primitive, normal, height, octaves; None when not requested), stats, and png (the "
        "bytes relief render writes)");
  m.def("stages", &stages, py::arg("scene"), py::arg("backend") = "simd",
        "Stages 1-4 (relief stages): the grid buffers as (rows, columns) numpy arrays");
  m.def("compare", &compare, py::arg("a"), py::arg("b"), py::arg("fail") = 1e-6f,
        py::arg("warn") = 1e-6f,
        "relief compare's figures (idiff's) for two float arrays of one shape");
}
