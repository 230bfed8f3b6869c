// The scene-field schema: every field of a scene file declared once, with its JSON key, the
// member it sets, its type and allowed range, its unit and one line of meaning. The reader
// (apply_scene_layer), the writer (scene_to_json), docs/scene-reference.md's table and the
// fuzzers' dictionaries (scene_reference.h) all walk it, so a field declared here reaches all four.
// The builders of single fields are in schema_fields.h; each section's list in its
// *_section.cc.
#pragma once

#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/scene/json_fields.h"

namespace relief {

// What a field's reader needs beyond the value: who reports failures (naming the layer's
// source) and the directory relative file names start from (the scene file's, or the current
// one for --set and presets).
struct LayerContext {
  const LayerReader& in;
  std::filesystem::path base_dir;
};

// A field's documentation: docs/scene-reference.md's table prints it.
struct FieldDoc {
  std::string_view unit;     // "" where the value has none
  std::string_view meaning;  // one line
  // What is allowed beyond the field's own type and range: the rules across fields that
  // validate_scene checks, or a special form. Printed after the range.
  std::string_view rule = {};
};

class SchemaNode;

// A field as the documentation and the dictionaries see it, without its section's type.
struct FieldInfo {
  std::string key;
  std::string allowed;  // the field's own type and range, as text ("1.001…16")
  FieldDoc doc;
  std::vector<std::string> words = {};   // the strings a choice allows (dictionary tokens)
  const SchemaNode* children = nullptr;  // an object's fields, or each array element's
  bool array = false;                    // children belong to each element: key[k].child
};

// One section's field list, its type erased.
class SchemaNode {
 public:
  virtual ~SchemaNode() = default;
  virtual std::vector<const FieldInfo*> field_infos() const = 0;
  // A default-constructed section as the writer prints it: where a field's own default is null
  // (terrain.sketch) or a list (shading.layers), its children's defaults come from here.
  virtual nlohmann::json defaults() const = 0;
};

// One field of section S: how to read it onto S and how to print it from S.
template <class S>
struct Field {
  FieldInfo info;
  std::function<void(const LayerContext&, const json&, const std::string&, S&)> read;
  // nullopt leaves the key out of the printed scene (camera.look_at, which is turned into
  // yaw and pitch; the plane's terrain.planet, which prints as it always has: absent).
  std::function<std::optional<json>(const S&)> write;
};

// Rules across one section's fields that must see the whole object (camera.look_at against
// the angles and the final position): run after every field was read.
template <class S>
using SectionFinish = std::function<void(const LayerContext&, const json&, const std::string&, S&)>;

template <class S>
class Schema final : public SchemaNode {
 public:
  // `prototype`: what a new section starts from (a default-constructed S unless given).
  explicit Schema(std::vector<Field<S>> fields, SectionFinish<S> finish = {}, S prototype = S{})
      : fields_(std::move(fields)), finish_(std::move(finish)), prototype_(std::move(prototype)) {}

  // Reads `value` (a JSON object, every key optional) onto `target`: unknown keys and every
  // field's own errors are SceneErrors that name the path.
  void apply(const LayerContext& context, const json& value, const std::string& path,
             S& target) const {
    Handlers handlers;
    handlers.reserve(fields_.size());
    for (const Field<S>& field : fields_) {
      handlers.emplace_back(field.info.key, [&](const json& v, const std::string& p) {
        field.read(context, v, p, target);
      });
    }
    context.in.object(value, path, handlers);
    if (finish_) {
      finish_(context, value, path, target);
    }
  }

  // Every field of `section` that prints, as one JSON object.
  json write(const S& section) const {
    json out = json::object();
    for (const Field<S>& field : fields_) {
      if (std::optional<json> value = field.write(section)) {
        out[field.info.key] = std::move(*value);
      }
    }
    return out;
  }

  std::vector<const FieldInfo*> field_infos() const override {
    std::vector<const FieldInfo*> infos;
    for (const Field<S>& field : fields_) {
      infos.push_back(&field.info);
    }
    return infos;
  }

  json defaults() const override { return write(prototype_); }
  const S& prototype() const { return prototype_; }

 private:
  std::vector<Field<S>> fields_;
  SectionFinish<S> finish_;
  S prototype_;
};

}  // namespace relief
