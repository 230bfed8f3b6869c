#include "core/scene/scene_reference.h"

#include <set>
#include <string>

#include "core/limits.h"
#include "core/scene/scene_sections.h"

namespace relief {

namespace {

// A default as the table prints it: numbers as they read back, strings and words in code
// quotes, a list of named entries by their names.
std::string default_text(const json* value) {
  if (value == nullptr) {
    return "—";  // not printed: camera.look_at, the plane's terrain.planet
  }
  if (value->is_null()) {
    return "`null`";
  }
  if (value->is_boolean()) {
    return value->get<bool>() ? "`true`" : "`false`";
  }
  if (value->is_number_float()) {
    return format_number(value->get<double>());
  }
  if (value->is_number()) {
    return value->dump();
  }
  if (value->is_string()) {
    const std::string& text = value->get_ref<const std::string&>();
    return text.empty() ? "" : "`" + text + "`";
  }
  if (value->is_array()) {
    std::string names;
    std::string numbers;
    for (const json& item : *value) {
      if (item.is_object() && item.contains("name")) {
        names += (names.empty() ? "" : ", ") + item["name"].get<std::string>();
      } else if (item.is_number()) {
        numbers += (numbers.empty() ? "" : ", ") + format_number(item.get<double>());
      }
    }
    if (!numbers.empty()) {
      return "`[" + numbers + "]`";
    }
    return value->empty()  ? "`[]`"
           : names.empty() ? std::to_string(value->size()) + " entries"
                           : names;
  }
  return "object";
}

// Every field under `node`, depth first in declaration order. `defaults` is the section's
// printed default (null or absent: the schema's own prototype is used for the children).
void collect(const SchemaNode& node, const std::string& prefix, const json& defaults,
             bool array_element, std::vector<SceneFieldRow>& rows) {
  for (const FieldInfo* info : node.field_infos()) {
    const std::string path = prefix + info->key;
    const json* value =
        defaults.is_object() && defaults.contains(info->key) ? &defaults[info->key] : nullptr;
    const bool plain_section = info->children && !info->array && info->allowed == "object";
    if (!plain_section) {
      std::string allowed = info->allowed;
      if (!info->doc.rule.empty()) {
        allowed += "; " + std::string(info->doc.rule);
      }
      rows.push_back({path, default_text(value), allowed, std::string(info->doc.unit),
                      std::string(info->doc.meaning), info->words, array_element});
    }
    if (info->children) {
      const json child_defaults =
          info->array || !value || !value->is_object() ? info->children->defaults() : *value;
      collect(*info->children, path + (info->array ? "[k]." : "."), child_defaults,
              array_element || info->array, rows);
    }
  }
}

std::string quoted(const std::string& text) {
  std::string out(1, '"');
  return out.append(text).append(1, '"');
}

std::string cell(const std::string& text) {
  std::string out;
  for (const char c : text) {
    out += c == '|' ? std::string("\\|") : std::string(1, c);
  }
  return out;
}

std::string dictionary(const std::string& target, const std::set<std::string>& tokens) {
  std::string text = "# Tokens for the " + target +
                     " fuzzer, written by relief_scene_docs from the scene schema.\n";
  for (const std::string& token : tokens) {
    text += '"';
    for (const unsigned char c : token) {
      if (c >= 32 && c < 127 && c != '"' && c != '\\') {
        text += static_cast<char>(c);
      } else {
        static const char* const kHex = "0123456789abcdef";
        text += std::string("\\x") + kHex[c >> 4] + kHex[c & 15];
      }
    }
    text += "\"\n";
  }
  return text;
}

}  // namespace

std::vector<SceneFieldRow> scene_field_rows() {
  std::vector<SceneFieldRow> rows;
  collect(scene_schema(), "", scene_schema().defaults(), false, rows);
  return rows;
}

std::string scene_reference_table() {
  std::string text = "| field | default | allowed | unit | meaning |\n|---|---|---|---|---|\n";
  for (const SceneFieldRow& row : scene_field_rows()) {
    text += "| `" + row.path + "` | " + cell(row.default_text) + " | " + cell(row.allowed) + " | " +
            cell(row.unit) + " | " + cell(row.meaning) + " |\n";
  }
  return text;
}

std::string scene_dictionary() {
  std::set<std::string> tokens = {"{",  "}",     "[",    "]",    ",",     "\"0\":", "1e308",
                                  "-0", "1e-17", "4096", "true", "false", "null"};
  for (const SceneFieldRow& row : scene_field_rows()) {
    tokens.insert(quoted(row.path.substr(row.path.rfind('.') + 1)).append(":"));
    for (const std::string& word : row.words) {
      tokens.insert(quoted(word));
    }
  }
  return dictionary("scene", tokens);
}

std::string override_dictionary() {
  std::set<std::string> tokens = {"\n", "[1,2]", "[0,0,0]", "nan", "inf", "1e999", "{}", "null"};
  const std::string last_layer = std::to_string(limits::kMaxMaterialLayers - 1);
  for (const SceneFieldRow& row : scene_field_rows()) {
    // --set reaches array elements only where an object patches them by index (the layers).
    const std::size_t element = row.path.find("[k]");
    if (element == std::string::npos) {
      tokens.insert(row.path + "=");
    } else if (row.path.starts_with("shading.layers[k].")) {
      for (const std::string& index : {std::string("0"), last_layer}) {
        tokens.insert("shading.layers." + index + row.path.substr(element + 3) + "=");
      }
    }
    tokens.insert(row.words.begin(), row.words.end());
  }
  return dictionary("override", tokens);
}

}  // namespace relief
