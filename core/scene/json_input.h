// JSON text from outside (scene files, --set values) turned into a DOM strictly, and JSON
// values quoted briefly in messages.
//
// nlohmann::json alone accepts what a scene must not: duplicate keys (the last silently wins),
// text after a NUL byte (parsing stops there), and nesting of any depth (printing such a value
// in an error message recurses once per level and overflows the stack at ~100,000 levels).
#pragma once

#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

namespace relief {

// Parses `text` as one JSON value. Throws SceneError (path "" or the JSON path of the problem)
// whose message starts with `source` for: a NUL byte anywhere, nesting deeper than
// limits::kMaxJsonDepth, a key repeated within one object, and any syntax error. Never
// recurses per nesting level. NaN and Infinity are not JSON and are rejected as syntax.
nlohmann::json parse_json_strictly(std::string_view text, const std::string& source);

// `value` as JSON text for a message, cut to about kBriefChars characters ("[1,2,3]",
// "\"abc…\" (100000 characters)"); invalid UTF-8 in strings is replaced, never thrown on.
std::string brief(const nlohmann::json& value);

inline constexpr std::size_t kBriefChars = 80;

// Whether `text` is well-formed UTF-8 (RFC 3629: no overlong forms, no surrogates, at most
// U+10FFFF). JSON text must be; the parser checks files, this checks --set's bare words.
bool is_valid_utf8(std::string_view text);

// `text` cut to about `limit` characters for a message, with its length when cut.
std::string brief_text(std::string_view text, std::size_t limit = kBriefChars);

}  // namespace relief
