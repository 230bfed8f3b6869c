// `--set KEY=VALUE` (scene_json.h, parse_override): the assignment as the one-key JSON layer
// it stands for, validated like the scene file by apply_scene_layer.
#include <algorithm>
#include <cctype>
#include <charconv>
#include <string>
#include <string_view>
#include <vector>

#include "core/limits.h"
#include "core/scene/json_fields.h"
#include "core/scene/json_input.h"
#include "core/scene/scene_json.h"

namespace relief {

namespace {

bool looks_non_finite(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (!text.empty() && (text[0] == '+' || text[0] == '-')) {
    text.erase(0, 1);
  }
  return text == "nan" || text == "inf" || text == "infinity";
}

}  // namespace

json parse_override(std::string_view assignment) {
  const std::string source = "--set " + brief_text(assignment);
  const std::size_t equals = assignment.find('=');
  if (equals == std::string_view::npos || equals == 0) {
    throw SceneError("", source + ": expected KEY=VALUE, for example --set terrain.H=0.85");
  }
  const std::string key(assignment.substr(0, equals));
  const std::string text(assignment.substr(equals + 1));
  json value;
  // An object, array or string that does not parse is a JSON error, not a bare word.
  const std::size_t first = text.find_first_not_of(" \t\r\n");
  if (json::accept(text) || (first != std::string::npos &&
                             std::string_view("{[\"").find(text[first]) != std::string::npos)) {
    value = parse_json_strictly(text, source);
  } else {
    // Not JSON: a number beyond double's range, NaN or Infinity are errors; anything else is a
    // bare word such as quintic.
    double number = 0;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), number);
    if (looks_non_finite(text) ||
        (ec == std::errc::result_out_of_range && end == text.data() + text.size())) {
      throw SceneError(key, source + ": " + brief_text(key) + " = " + brief_text(text) +
                                " is not a finite number");
    }
    if (!is_valid_utf8(text)) {
      throw SceneError(key, source + ": " + brief_text(key) + " = " + brief_text(text) +
                                " is not valid UTF-8; scene values are text");
    }
    value = text;
  }
  // Build {"a": {"b": value}} from "a.b"; each segment is checked by apply_scene_layer.
  std::vector<std::string> segments;
  for (std::size_t begin = 0;;) {
    const std::size_t dot = std::min(key.find('.', begin), key.size());
    segments.push_back(key.substr(begin, dot - begin));
    if (segments.back().empty()) {
      throw SceneError(key, source + ": key '" + brief_text(key) + "' has an empty segment");
    }
    if (segments.size() > std::size_t(limits::kMaxJsonDepth)) {
      throw SceneError(key, source + ": key '" + brief_text(key) + "' has more than " +
                                std::to_string(limits::kMaxJsonDepth) + " segments");
    }
    if (dot == key.size()) {
      break;
    }
    begin = dot + 1;
  }
  json layer = value;
  for (auto segment = segments.rbegin(); segment != segments.rend(); ++segment) {
    layer = json{{*segment, layer}};
  }
  return layer;
}

}  // namespace relief
