#include "core/scene/json_input.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cstdint>
#include <set>
#include <vector>

#include "core/limits.h"
#include "core/scene/scene_json.h"

namespace relief {

namespace {

using nlohmann::json;

// Where the parser is: one frame per open object or array, for duplicate keys and for the
// JSON path of a message.
struct OpenValue {
  bool object = false;
  std::set<std::string> keys;
  std::string key;  // objects: the key being read
  long index = -1;  // arrays: the element being read
};

std::string path_of(const std::vector<OpenValue>& open) {
  std::string path;
  for (const OpenValue& v : open) {
    if (v.object && !v.key.empty()) {
      if (!path.empty()) {
        path += '.';
      }
      path += v.key;
    } else if (!v.object && v.index >= 0) {
      path += '[';
      path += std::to_string(v.index);
      path += ']';
    }
  }
  return path;
}

void append_brief(const json& value, std::string& out) {
  if (out.size() > kBriefChars) {
    return;
  }
  const auto dump = [](const json& v) {
    return v.dump(-1, ' ', false, json::error_handler_t::replace);
  };
  if (value.is_array() || value.is_object()) {
    out += value.is_array() ? '[' : '{';
    bool first = true;
    for (auto it = value.begin(); it != value.end(); ++it) {
      if (out.size() > kBriefChars) {
        out += "...";
        break;
      }
      out += first ? "" : ",";
      first = false;
      if (value.is_object()) {
        out += dump(json(it.key())) + ":";
      }
      append_brief(*it, out);
    }
    out += value.is_array() ? ']' : '}';
  } else if (value.is_string()) {
    out += dump(json(brief_text(value.get_ref<const std::string&>())));
  } else if (value.is_number_float()) {
    char buffer[32];  // the shortest text that reads back the same: 1e+09, not 1000000000.0
    const auto result = std::to_chars(buffer, buffer + sizeof buffer, value.get<double>());
    out.append(buffer, result.ptr);
  } else {
    out += dump(value);
  }
}

}  // namespace

std::string brief_text(std::string_view text, std::size_t limit) {
  std::size_t cut = text.size();
  if (text.size() > limit) {
    cut = limit;
    while (cut > 0 && (static_cast<unsigned char>(text[cut]) & 0xc0) == 0x80) {
      --cut;  // do not split a UTF-8 sequence
    }
  }
  // Control characters (a NUL would end the message on a terminal, an ESC would command it)
  // are written as \xNN.
  std::string out;
  for (const char c : text.substr(0, cut)) {
    const auto byte = static_cast<unsigned char>(c);
    if (byte < 0x20 || byte == 0x7f) {
      static constexpr char kHex[] = "0123456789abcdef";
      out += "\\x";
      out += kHex[byte >> 4];
      out += kHex[byte & 15];
    } else {
      out += c;
    }
  }
  if (cut < text.size()) {
    out += "... (" + std::to_string(text.size()) + " bytes)";
  }
  return out;
}

bool is_valid_utf8(std::string_view text) {
  std::size_t k = 0;
  while (k < text.size()) {
    const auto lead = static_cast<unsigned char>(text[k]);
    // Length and smallest code point of the sequence; continuation bytes are 10xxxxxx.
    int length = 0;
    std::uint32_t code = 0, smallest = 0;
    if (lead < 0x80) {
      length = 1, code = lead;
    } else if ((lead & 0xe0) == 0xc0) {
      length = 2, code = lead & 0x1f, smallest = 0x80;
    } else if ((lead & 0xf0) == 0xe0) {
      length = 3, code = lead & 0x0f, smallest = 0x800;
    } else if ((lead & 0xf8) == 0xf0) {
      length = 4, code = lead & 0x07, smallest = 0x10000;
    } else {
      return false;
    }
    if (k + length > text.size()) {
      return false;
    }
    for (int c = 1; c < length; ++c) {
      const auto next = static_cast<unsigned char>(text[k + c]);
      if ((next & 0xc0) != 0x80) {
        return false;
      }
      code = code << 6 | (next & 0x3f);
    }
    if (code < smallest || code > 0x10ffff || (code >= 0xd800 && code <= 0xdfff)) {
      return false;
    }
    k += length;
  }
  return true;
}

std::string brief(const json& value) {
  std::string out;
  append_brief(value, out);
  return out;
}

json parse_json_strictly(std::string_view text, const std::string& source) {
  if (const std::size_t nul = text.find('\0'); nul != std::string_view::npos) {
    throw SceneError("", source + ": contains a NUL byte at offset " + std::to_string(nul) +
                             "; a scene is JSON text");
  }
  std::vector<OpenValue> open;
  const auto on_event = [&](int depth, json::parse_event_t event, json& parsed) {
    switch (event) {
      case json::parse_event_t::object_start:
      case json::parse_event_t::array_start:
        if (depth >= limits::kMaxJsonDepth) {
          throw SceneError(path_of(open), source + ": " +
                                              (open.empty() ? "the value" : path_of(open)) +
                                              " is nested deeper than " +
                                              std::to_string(limits::kMaxJsonDepth) + " levels");
        }
        if (!open.empty() && !open.back().object) {
          ++open.back().index;
        }
        open.push_back(OpenValue{event == json::parse_event_t::object_start, {}, {}, -1});
        break;
      case json::parse_event_t::object_end:
      case json::parse_event_t::array_end:
        open.pop_back();
        break;
      case json::parse_event_t::key: {
        OpenValue& object = open.back();
        object.key = parsed.get<std::string>();
        if (!object.keys.insert(object.key).second) {
          const std::string path = path_of(open);
          throw SceneError(path, source + ": key '" + brief_text(path) +
                                     "' appears twice; each key may be given once");
        }
        break;
      }
      case json::parse_event_t::value:
        if (!open.empty() && !open.back().object) {
          ++open.back().index;
        }
        break;
    }
    return true;
  };
  try {
    return json::parse(text, on_event);
  } catch (const json::exception& e) {
    // nlohmann's text without its "[json.exception.parse_error.101] " tag, a byte that is not
    // UTF-8 as \xNN (it may quote the offending byte), and the hint on NaN only where the text
    // holds something like it.
    std::string reason = e.what();
    if (reason.rfind("[json.exception.", 0) == 0 && reason.find("] ") != std::string::npos) {
      reason.erase(0, reason.find("] ") + 2);
    }
    std::string printable;
    for (const unsigned char c : reason) {
      if (c < 0x80) {
        printable += char(c);
      } else {
        static constexpr char kHex[] = "0123456789abcdef";
        printable += std::string("\\x") + kHex[c >> 4] + kHex[c & 15];
      }
    }
    std::string lower(text);
    std::transform(lower.begin(), lower.end(), lower.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    const bool non_finite =
        lower.find("nan") != std::string::npos || lower.find("inf") != std::string::npos;
    throw SceneError("", source + ": not valid JSON: " + brief_text(printable, 3 * kBriefChars) +
                             (non_finite ? " (numbers must be finite; NaN and Infinity are not "
                                           "JSON)"
                                         : ""));
  }
}

}  // namespace relief
