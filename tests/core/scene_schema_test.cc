// The scene-field schema's table (docs/scene-reference.md, core/scene/scene_reference.h)
// checked against the scene's reader and writer from outside: every field the writer prints
// has a row, every row names a field the reader knows, and every range the table prints is the
// one the reader enforces at both ends.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/scene/scene_json.h"
#include "core/scene/scene_reference.h"

namespace relief {
namespace {

using nlohmann::json;

// Every leaf path of a printed scene, array elements written "[k]".
void leaf_paths(const json& value, const std::string& path, std::set<std::string>& out) {
  if (value.is_object() && !value.empty()) {
    for (const auto& item : value.items()) {
      leaf_paths(item.value(), path.empty() ? item.key() : path + "." + item.key(), out);
    }
  } else if (value.is_array() && !value.empty() && value[0].is_object()) {
    out.insert(path);
    for (const json& element : value) {
      leaf_paths(element, path + "[k]", out);
    }
  } else {
    out.insert(path);
  }
}

// The preset in which a field's enclosing optional section exists.
std::string base_scene_for(const std::string& path) {
  if (path.starts_with("terrain.sketch"))
    return "island";
  if (path.starts_with("terrain.basis"))
    return "craters";
  if (path.starts_with("terrain.planet"))
    return "planet";
  return "default";
}

// `value` at `path` as a one-field layer; "[k]" is element 0 (shading.layers patches it by
// index, terrain.basis.images is replaced whole by one image with `value` in it,
// shading.gradient.stops by two stops, the first with `value` in it).
json layer_at(const std::string& path, const json& value) {
  const std::size_t element = path.find("[k].");
  if (element != std::string::npos) {
    const std::string array = path.substr(0, element);
    const std::string key = path.substr(element + 4);
    if (array == "shading.layers") {
      return layer_at(array, json{{"0", json{{key, value}}}});
    }
    if (array == "shading.gradient.stops") {  // replaced whole: two complete stops
      json first{{"at", 0}, {"color", {0, 0, 0}}};
      first[key] = value;
      return layer_at(array, json::array({first, json{{"at", 1}, {"color", {1, 1, 1}}}}));
    }
    json image{{"image", "builtin:basis/craters"}};
    image[key] = value;
    return layer_at(array, json::array({image}));
  }
  const std::size_t dot = path.find('.');
  if (dot == std::string::npos) {
    return json{{path, value}};
  }
  return json{{path.substr(0, dot), layer_at(path.substr(dot + 1), value)}};
}

// The path the reader reports for a field: element 0 for "[k]".
std::string reported_path(std::string path) {
  const std::size_t element = path.find("[k]");
  if (element != std::string::npos) {
    path.replace(element, 3, "[0]");
  }
  return path;
}

// The SceneError path when `value` is applied at `path` onto the field's base scene; nullopt
// when it is accepted.
std::optional<std::string> error_path(const std::string& path, const json& value) {
  // sky.skybox's fields need a skybox to patch: its faces are only read when a frame loads.
  // So do terrain.heightfield's: its file is only read when a frame loads.
  const std::vector<std::string> skybox = {
      R"(sky.skybox={"faces": ["a.png", "b.png", "c.png", "d.png", "e.png", "f.png"]})"};
  const std::vector<std::string> heightfield = {R"(terrain.heightfield={"file": "a.pfm"})"};
  Scene scene = resolve_scene(base_scene_for(path), path.starts_with("sky.skybox.") ? skybox
                                                    : path.starts_with("terrain.heightfield.")
                                                        ? heightfield
                                                        : std::vector<std::string>{});
  try {
    apply_scene_layer(scene, layer_at(path, value), "test");
  } catch (const SceneError& e) {
    return e.path();
  }
  return std::nullopt;
}

// Whether an error at `got` is about `field`: the field itself or one of its components.
bool about(const std::optional<std::string>& got, const std::string& field) {
  return got && (*got == field || got->starts_with(field + "["));
}

std::set<std::string> table_paths() {
  std::set<std::string> paths;
  for (const SceneFieldRow& row : scene_field_rows()) {
    paths.insert(row.path);
  }
  return paths;
}

TEST_CASE("every field the scene printout holds has a row in the scene table") {
  const std::set<std::string> rows = table_paths();
  for (const char* preset : {"default", "island", "craters", "planet"}) {
    std::set<std::string> printed;
    leaf_paths(scene_to_json(resolve_scene(preset, {})), "", printed);
    for (const std::string& path : printed) {
      INFO(preset << ": " << path);
      CHECK(rows.count(path) == 1);
    }
  }
}

TEST_CASE("every row of the scene table names a field the reader knows") {
  for (const SceneFieldRow& row : scene_field_rows()) {
    INFO(row.path);
    // A nested array of arrays is the wrong type for every field: the error must name the
    // field (or a part of it), not an unknown key of its parent.
    const std::optional<std::string> path = error_path(row.path, json::parse("[[[]]]"));
    REQUIRE(path);
    const std::string field = reported_path(row.path);
    // The field itself, or one element of it (shading.layers[0], camera.look_at[0]).
    CHECK(about(path, field));
  }
}

TEST_CASE("every choice word in the scene table is accepted by the reader") {
  for (const SceneFieldRow& row : scene_field_rows()) {
    for (const std::string& word : row.words) {
      INFO(row.path << " = " << word);
      const json value = word == "true" ? json(true) : word == "false" ? json(false) : json(word);
      CHECK_FALSE(about(error_path(row.path, value), reported_path(row.path)));
    }
  }
}

struct PrintedRange {
  double lo, hi;
  bool lo_open, hi_open;
};

// "[1, 170]", "(1e-17, 1e+09]", "|·| ≤ 360" at the start of `text`; nullopt for anything else.
std::optional<PrintedRange> parse_range(const std::string& text) {
  const std::string symmetric = "|·| ≤ ";
  if (text.starts_with(symmetric)) {
    const double hi = std::strtod(text.c_str() + symmetric.size(), nullptr);
    return PrintedRange{-hi, hi, false, false};
  }
  if (text.empty() || (text[0] != '[' && text[0] != '(')) {
    return std::nullopt;
  }
  char* end = nullptr;
  const double lo = std::strtod(text.c_str() + 1, &end);
  if (end[0] != ',' || end[1] != ' ') {
    return std::nullopt;
  }
  const double hi = std::strtod(end + 2, &end);
  if (*end != ']' && *end != ')') {
    return std::nullopt;
  }
  return PrintedRange{lo, hi, text[0] == '(', *end == ')'};
}

TEST_CASE("every range the scene table prints is the one the reader enforces at both ends") {
  int ranges_checked = 0;
  for (const SceneFieldRow& row : scene_field_rows()) {
    std::string text = row.allowed;
    bool integer = false;
    int components = 1;
    bool pair = false;
    if (text.starts_with("integer in ")) {
      text = text.substr(11);
      integer = true;
    } else if (text.size() > 2 && text[1] == ' ' && text.substr(2).starts_with("numbers, each ")) {
      components = text[0] - '0';
      text = text.substr(16);
    } else if (text.starts_with("[low, high], each ")) {
      pair = true;
      text = text.substr(18);
    }
    const std::optional<PrintedRange> range = parse_range(text);
    if (!range || row.path == "camera.look_at") {
      continue;  // not a plain range (a choice, a file, a rule first), or never printed
    }
    INFO(row.path << ": " << row.allowed);
    const auto below = [&](double v) {
      return integer ? v - 1 : std::nextafter(v, -std::numeric_limits<double>::infinity());
    };
    const auto above = [&](double v) {
      return integer ? v + 1 : std::nextafter(v, std::numeric_limits<double>::infinity());
    };
    const double lo_in = range->lo_open ? above(range->lo) : range->lo;
    const double hi_in = range->hi_open ? below(range->hi) : range->hi;
    const double lo_out = range->lo_open ? range->lo : below(range->lo);
    const double hi_out = range->hi_open ? range->hi : above(range->hi);
    const std::string own = reported_path(row.path);
    if (pair || components > 1) {
      // Low ends first, high ends last: ordered as [low, high] pairs and sketch extents want.
      const int n = pair ? 2 : components;
      std::vector<double> inside(n, hi_in);
      std::fill(inside.begin(), inside.begin() + n / 2, lo_in);
      std::vector<double> low = inside;
      low.front() = lo_out;
      std::vector<double> high = inside;
      high.back() = hi_out;
      CHECK_FALSE(about(error_path(row.path, json(inside)), own));
      CHECK(about(error_path(row.path, json(low)), own));
      CHECK(about(error_path(row.path, json(high)), own));
    } else {
      const auto value = [&](double v) {
        return integer ? json(static_cast<long long>(v)) : json(v);
      };
      CHECK_FALSE(about(error_path(row.path, value(lo_in)), own));
      CHECK_FALSE(about(error_path(row.path, value(hi_in)), own));
      CHECK(about(error_path(row.path, value(lo_out)), own));
      CHECK(about(error_path(row.path, value(hi_out)), own));
    }
    ++ranges_checked;
  }
  CHECK(ranges_checked >= 60);
}

}  // namespace
}  // namespace relief
