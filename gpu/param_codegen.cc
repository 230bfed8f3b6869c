// Build-time generator (gpu/CMakeLists.txt runs it): prints, from the field lists of
// core/stage_param_fields.h, the GLSL declarations of the stage parameter structs into the
// shader templates and the table that checks GL's offsets against offsetof
// (gl_param_layout.h), and expands det_math's one GLSL text in float and in double.
//
//   relief_param_codegen TABLE.cc [TEMPLATE OUTPUT]...
//
// A template is GLSL in which a line of the form `@directive@ trailing text` is replaced:
//   @struct NAME@      the GLSL struct of C++ struct NAME (the trailing text, a comment, goes
//                      on its first line),
//   @members NAME@     NAME's members only (the body of a block that holds them directly),
//   @scalars NAME@     NAME's members with each array of scalars as numbered scalars (std140,
//                      where a float[3] would be strided by 16: row_x[3] is row_x0 .. row_x2),
//   @real TYPE FILE@   FILE (beside the template) in precision TYPE, float or double: its
//                      REAL(literal) becomes the literal (double: with the LF suffix), and
//                      the word REAL the type.
#include <algorithm>
#include <cctype>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <functional>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include "core/stage_param_fields.h"
#include "core/stage_params.h"
#include "gpu/param_codegen_text.h"

// A named namespace, not an anonymous one: the traits' unused members (uint, TransformParams'
// C++ name) are then no unused internal variables to warn about.
namespace relief::param_codegen {

// The scalar member types, in GLSL and in C++.
template <class T>
struct Scalar;
template <>
struct Scalar<float> {
  static constexpr const char* kGlsl = "float";
  static constexpr const char* kCpp = "float";
};
template <>
struct Scalar<double> {
  static constexpr const char* kGlsl = "double";
  static constexpr const char* kCpp = "double";
};
template <>
struct Scalar<std::int32_t> {
  static constexpr const char* kGlsl = "int";
  static constexpr const char* kCpp = "std::int32_t";
};
template <>
struct Scalar<std::uint32_t> {
  static constexpr const char* kGlsl = "uint";
  static constexpr const char* kCpp = "std::uint32_t";
};

// The structs with a field list, at Real = float (the precision GL reads).
template <class S>
struct Fields;

#define RELIEF_GEN_F(type, name, ...) v.template field<type>(#name, "");
#define RELIEF_GEN_A(type, name, dims, ...) v.template field<type dims>(#name, #dims);
#define RELIEF_GEN_E v.end_line();
#define RELIEF_DESCRIBE(Template, glsl_name, LIST)           \
  template <>                                                \
  struct Fields<Template<float>> {                           \
    static constexpr const char* kName = #Template;          \
    static constexpr const char* kGlsl = glsl_name;          \
    static constexpr const char* kCpp = #Template "<float>"; \
    template <class V>                                       \
    static void visit(V& v) {                                \
      using Real = float;                                    \
      LIST(RELIEF_GEN_F, RELIEF_GEN_A, RELIEF_GEN_E)         \
    }                                                        \
  };

RELIEF_DESCRIBE(Vec3, "Float3", RELIEF_VEC3_FIELDS)
RELIEF_DESCRIBE(ProjectorRays, "ProjectorRays", RELIEF_PROJECTOR_RAYS_FIELDS)
RELIEF_DESCRIBE(DomainParams, "DomainParams", RELIEF_DOMAIN_PARAMS_FIELDS)
RELIEF_DESCRIBE(PlanetParams, "PlanetParams", RELIEF_PLANET_PARAMS_FIELDS)
RELIEF_DESCRIBE(FbmParams, "FbmParams", RELIEF_FBM_PARAMS_FIELDS)
RELIEF_DESCRIBE(SketchParams, "SketchParams", RELIEF_SKETCH_PARAMS_FIELDS)
RELIEF_DESCRIBE(SurfaceParams, "SurfaceParams", RELIEF_SURFACE_PARAMS_FIELDS)
RELIEF_DESCRIBE(TransformParams, "TransformParams", RELIEF_TRANSFORM_PARAMS_FIELDS)
RELIEF_DESCRIBE(RampParams, "Ramp", RELIEF_RAMP_PARAMS_FIELDS)
RELIEF_DESCRIBE(LayerParams, "Layer", RELIEF_LAYER_PARAMS_FIELDS)
RELIEF_DESCRIBE(ShadeParams, "ShadeParams", RELIEF_SHADE_PARAMS_FIELDS)

template <class T>
constexpr bool kIsStruct = requires {
  Fields<T>::kGlsl;
};

template <class T>
std::string glsl_type() {
  if constexpr (kIsStruct<T>) {
    return Fields<T>::kGlsl;
  } else {
    return Scalar<T>::kGlsl;
  }
}

// An array's dimensions in GLSL: the C++ extents' names as the preludes define them.
std::string glsl_dims(const std::string& dims) {
  static const std::map<std::string, std::string> kNames = {
      {"limits::kMaxOctaves", "RELIEF_MAX_OCTAVES"},           // gl_shader_prelude.cc
      {"limits::kMaxFieldLevels", "RELIEF_MAX_FIELD_LEVELS"},  // gl_shader_prelude.cc
      {"limits::kMaxMaterialLayers", "kMaxLayers"},            // glsl_prelude.cc
      {"kWaveOctaves", "kWaveOctaves"},                        // glsl_prelude.cc
      {"limits::kMaxGradientStops", "kMaxGradientStops"},      // glsl_prelude.cc
      {"limits::kMaxCloudOctaves", "kMaxCloudOctaves"},        // glsl_prelude.cc
  };
  std::string out;
  // Each "[ extent ]" of the C++ declaration, its extent trimmed of white space.
  for (std::size_t open = dims.find('['); open != std::string::npos;
       open = dims.find('[', open + 1)) {
    const std::size_t close = dims.find(']', open);
    if (close == std::string::npos) {
      throw std::runtime_error("unbalanced array dimensions " + dims + " (param_codegen.cc)");
    }
    const std::string e = trimmed(dims.substr(open + 1, close - open - 1));
    const auto named = kNames.find(e);
    if (named == kNames.end() && !all_digits(e)) {
      throw std::runtime_error("no GLSL name for the extent " + e + " (param_codegen.cc)");
    }
    out += "[" + (named == kNames.end() ? e : named->second) + "]";
  }
  return out;
}

// The GLSL member lines of a struct: one per E of its list.
struct GlslMembers {
  bool numbered_scalars = false;  // @scalars
  std::string out, type;
  std::vector<std::string> names;

  template <class T>
  void field(const std::string& name, const std::string& dims) {
    using Element = std::remove_all_extents_t<T>;
    const std::string t = glsl_type<Element>();
    if (!names.empty() && t != type) {
      throw std::runtime_error(name + " shares a GLSL line with members of type " + type +
                               ": end the line (E) before it");
    }
    type = t;
    if (!numbered_scalars) {
      names.push_back(name + glsl_dims(dims));
    } else if constexpr (std::rank_v<T> == 0 && !kIsStruct<T>) {
      names.push_back(name);
    } else if constexpr (std::rank_v<T> == 1 && !kIsStruct<Element>) {
      for (std::size_t k = 0; k < std::extent_v<T>; ++k) {
        names.push_back(name + std::to_string(k));
      }
    } else {
      throw std::runtime_error(name + ": only scalars and arrays of them can be numbered");
    }
  }
  void end_line() {
    std::string line = "  " + type + " ";
    for (std::size_t k = 0; k < names.size(); ++k) {
      line += (k > 0 ? ", " : "") + names[k];
    }
    out += line + ";\n";
    names.clear();
  }
};

template <class S>
std::string glsl_members(bool numbered_scalars) {
  GlslMembers v{numbered_scalars, {}, {}, {}};
  Fields<S>::visit(v);
  return v.out;
}

// The rows of the layout table: every buffer variable GL lists for a block, named as GL names
// it, with its C++ offset, array stride and top-level array stride as C++ expressions.
struct Row {
  std::string name, offset, array_stride, top_level_stride;
  bool top_level_is_scalar_array = false;
};

template <class S>
struct LayoutRows {
  std::vector<Row>& rows;
  std::string prefix;  // GL's name of the struct instance, "domain." or "layers[0]."
  std::string base;    // C++ offset of the struct instance, "" or "... + "
  bool top_level;      // the members are the block's own (GL lists arrays by element 0)
  std::string top_level_stride;

  template <class T>
  void field(const std::string& name, const std::string&) {
    using Element = std::remove_all_extents_t<T>;
    const std::string offset = base + "offsetof(" + Fields<S>::kCpp + ", " + name + ")";
    const std::string element = std::string("sizeof(") + cpp_type<Element>() + ")";
    if constexpr (kIsStruct<Element>) {
      static_assert(std::rank_v<T> <= 1, "arrays of arrays of structs");
      if constexpr (std::rank_v<T> == 0) {
        LayoutRows<T>{rows, prefix + name + ".", offset + " + ", false, top_level_stride}.visit();
      } else if (top_level) {
        LayoutRows<Element>{rows, prefix + name + "[0].", offset + " + ", false, element}.visit();
      } else {
        for (std::size_t k = 0; k < std::extent_v<T>; ++k) {
          LayoutRows<Element>{rows, prefix + name + "[" + std::to_string(k) + "].",
                              offset + " + " + std::to_string(k) + " * " + element + " + ", false,
                              top_level_stride}
              .visit();
        }
      }
    } else if constexpr (std::rank_v<T> == 0) {
      rows.push_back({prefix + name, offset, "0", top_level_stride});
    } else if constexpr (std::rank_v<T> == 1) {
      rows.push_back({prefix + name + "[0]", offset, element,
                      top_level ? element : top_level_stride, top_level});
    } else {
      static_assert(std::rank_v<T> == 2, "arrays of more than two dimensions");
      if (top_level) {
        throw std::runtime_error(name + ": a block's own array of arrays is not supported");
      }
      // GL lists an array of arrays by its outer elements, each an array of scalars.
      for (std::size_t q = 0; q < std::extent_v<T>; ++q) {
        rows.push_back({prefix + name + "[" + std::to_string(q) + "][0]",
                        offset + " + " + std::to_string(q) + " * sizeof(" + cpp_type<Element>() +
                            "[" + std::to_string(std::extent_v<T, 1>) + "])",
                        element, top_level_stride});
      }
    }
  }
  void end_line() {}
  void visit() { Fields<S>::visit(*this); }

  template <class T>
  static std::string cpp_type() {
    if constexpr (kIsStruct<T>) {
      return Fields<T>::kCpp;
    } else {
      return Scalar<T>::kCpp;
    }
  }
};

// One function of gl_param_layout.h: `block` holds one S named by `prefix` ("domain."), or,
// with an empty prefix, S's members themselves (named "Block.member", as GL names those of a
// block with an instance name).
template <class S>
std::string layout_function(const std::string& function, const std::string& block,
                            const std::string& prefix) {
  std::vector<Row> rows;
  const bool own = prefix.empty();
  LayoutRows<S>{rows, own ? block + "." : prefix, "", own, "0"}.visit();
  std::string out = "GlBlockLayout " + function + "() {\n  return {\"" + block + "\",\n" +
                    "          sizeof(" + Fields<S>::kCpp + "),\n          {\n";
  for (const Row& r : rows) {
    out += "              {\"" + r.name + "\", " + r.offset + ", " + r.array_stride + ", " +
           r.top_level_stride + ", " + (r.top_level_is_scalar_array ? "true" : "false") + "},\n";
  }
  return out + "          }};\n}\n\n";
}

std::string layout_table() {
  return "// Generated by gpu/param_codegen.cc from core/stage_param_fields.h. Do not edit.\n"
         "#include <cstddef>\n#include <cstdint>\n\n"
         "#include \"core/stage_params.h\"\n#include \"gpu/gl_param_layout.h\"\n\n"
         "namespace relief::gpu {\n\n" +
         layout_function<DomainParams<float>>("domain_params_layout", "DomainParamsBlock",
                                              "domain.") +
         layout_function<FbmParams<float>>("fbm_params_layout", "FbmParamsBlock", "fbm.") +
         layout_function<SketchParams<float>>("sketch_params_layout", "SketchParamsBlock",
                                              "sketch.") +
         layout_function<SurfaceParams<float>>("surface_params_layout", "SurfaceParamsBlock",
                                               "surface.") +
         layout_function<PlanetParams<float>>("planet_params_layout", "PlanetParamsBlock",
                                              "planet.") +
         layout_function<ShadeParams<float>>("shade_params_block_layout", "ShadeParamsBlock", "") +
         "}  // namespace relief::gpu\n";
}

// The directives' struct names: NAME -> (directive, trailing text) -> GLSL.
using Emit = std::function<std::string(const std::string&, const std::string&)>;

template <class S>
std::pair<const std::string, Emit> directive_entry() {
  return {Fields<S>::kName, [](const std::string& kind, const std::string& tail) {
            if (kind == "struct") {
              return "struct " + std::string(Fields<S>::kGlsl) + " {" + tail + "\n" +
                     glsl_members<S>(false) + "};\n";
            }
            if (kind == "members" || kind == "scalars") {
              return glsl_members<S>(kind == "scalars");
            }
            throw std::runtime_error("unknown directive @" + kind + "@");
          }};
}

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    throw std::runtime_error("cannot read " + path);
  }
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

void write_file(const std::string& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
  if (!out.flush()) {
    throw std::runtime_error("cannot write " + path);
  }
}

std::string expand(const std::string& template_path) {
  static const std::map<std::string, Emit> kStructs = {
      directive_entry<Vec3<float>>(),          directive_entry<ProjectorRays<float>>(),
      directive_entry<DomainParams<float>>(),  directive_entry<PlanetParams<float>>(),
      directive_entry<FbmParams<float>>(),     directive_entry<SketchParams<float>>(),
      directive_entry<SurfaceParams<float>>(), directive_entry<TransformParams<float>>(),
      directive_entry<RampParams<float>>(),    directive_entry<LayerParams<float>>(),
      directive_entry<ShadeParams<float>>()};
  const std::string directory = template_path.substr(0, template_path.find_last_of('/') + 1);
  std::istringstream in(read_file(template_path));
  std::string out, line;
  for (int number = 1; std::getline(in, line); ++number) {
    std::string kind, argument, tail;
    if (!parse_directive(line, kind, argument, tail)) {
      out += line + "\n";
      continue;
    }
    try {
      if (kind == "real") {
        const std::size_t space = argument.find(' ');
        out += in_precision(read_file(directory + argument.substr(space + 1)),
                            argument.substr(0, space));
        continue;
      }
      const auto entry = kStructs.find(argument);
      if (entry == kStructs.end()) {
        throw std::runtime_error("no field list for " + argument);
      }
      out += entry->second(kind, tail);
    } catch (const std::exception& e) {
      throw std::runtime_error(template_path + ":" + std::to_string(number) + ": " + e.what());
    }
  }
  return out;
}

}  // namespace relief::param_codegen

int main(int argc, char** argv) {
  if (argc < 2 || argc % 2 != 0) {
    std::fprintf(stderr, "usage: %s TABLE.cc [TEMPLATE OUTPUT]...\n", argv[0]);
    return 2;
  }
  try {
    relief::param_codegen::write_file(argv[1], relief::param_codegen::layout_table());
    for (int k = 2; k + 1 < argc; k += 2) {
      const std::string name = std::string(argv[k]).substr(std::string(argv[k]).rfind('/') + 1);
      relief::param_codegen::write_file(argv[k + 1],
                                        "// Generated from gpu/shaders/" + name +
                                            " by gpu/param_codegen.cc. Do not edit.\n" +
                                            relief::param_codegen::expand(argv[k]));
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "param_codegen: %s\n", e.what());
    return 1;
  }
  return 0;
}
