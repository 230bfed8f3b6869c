// Strict reading of JSON fields for the scene loader: every failure is a SceneError whose
// message names where the input came from, the JSON path, the value and the allowed range.
#pragma once

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <functional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/limits.h"
#include "core/scene/json_input.h"
#include "core/scene/scene_json.h"

namespace relief {

using nlohmann::json;

// A closed or open interval, printed the way messages quote it: "1 < terrain.r <= 16".
struct Range {
  double lo;
  double hi;
  bool lo_open = false;
  bool hi_open = false;

  bool contains(double v) const {
    return (lo_open ? v > lo : v >= lo) && (hi_open ? v < hi : v <= hi);
  }
};

// Shortest text that reads back to the same double ("90", "0.85", "1e+30").
inline std::string format_number(double v) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, v);
  return std::string(buffer, result.ptr);
}

inline std::string describe(const Range& range, const std::string& path) {
  return format_number(range.lo) + (range.lo_open ? " < " : " <= ") + path +
         (range.hi_open ? " < " : " <= ") + format_number(range.hi);
}

inline std::string join(const std::vector<std::string>& items, std::string_view separator) {
  std::string out;
  for (std::size_t k = 0; k < items.size(); ++k) {
    out += (k ? std::string(separator) : std::string()) + items[k];
  }
  return out;
}

inline std::string child_path(const std::string& parent, std::string_view key) {
  return parent.empty() ? std::string(key) : parent + "." + std::string(key);
}

// Reads one layer field by field. Every failure names the layer's source and the JSON path.
class LayerReader {
 public:
  explicit LayerReader(std::string_view source) : source_(source) {}

  [[noreturn]] void fail(const std::string& path, const std::string& problem) const {
    throw SceneError(path, std::string(source_) + ": " + problem);
  }

  // Visits each key of an object, rejecting keys not in `handlers`.
  void object(const json& value, const std::string& path,
              const std::vector<
                  std::pair<std::string, std::function<void(const json&, const std::string&)>>>&
                  handlers) const {
    if (!value.is_object()) {
      fail(path, (path.empty() ? std::string("the scene") : path) + " must be a JSON object, got " +
                     brief(value));
    }
    // Named references, not a structured binding: clang before 16 cannot capture one.
    for (const auto& entry : value.items()) {
      const std::string& key = entry.key();
      const json& item = entry.value();
      const auto handler = std::find_if(handlers.begin(), handlers.end(),
                                        [&](const auto& h) { return h.first == key; });
      if (handler == handlers.end()) {
        std::vector<std::string> known;
        for (const auto& h : handlers) {
          known.push_back(h.first);
        }
        const std::string unknown = brief_text(child_path(path, key));
        fail(unknown, "unknown key '" + unknown + "'; allowed keys" +
                          (path.empty() ? "" : " in " + path) + ": " + join(known, ", "));
      }
      handler->second(item, child_path(path, key));
    }
  }

  double number(const json& value, const std::string& path, const Range& range) const {
    if (!value.is_number()) {
      fail(path,
           path + " = " + brief(value) + " is not a number; allowed " + describe(range, path));
    }
    const double v = value.get<double>();
    if (!std::isfinite(v)) {
      fail(path, path + " = " + brief(value) + " is not a finite number");
    }
    if (!range.contains(v)) {
      fail(path,
           path + " = " + format_number(v) + " is out of range; allowed " + describe(range, path));
    }
    return v;
  }

  // Integers may be written as 512 or 512.0 (or 5.12e2): JSON does not tell them apart, and a
  // value such as 1e9 deserves "out of range", not "not an integer".
  long long integer(const json& value, const std::string& path, long long lo, long long hi) const {
    const Range range{static_cast<double>(lo), static_cast<double>(hi)};
    const bool integral = value.is_number_integer() ||
                          (value.is_number_float() && std::isfinite(value.get<double>()) &&
                           value.get<double>() == std::floor(value.get<double>()));
    if (!integral) {
      fail(path,
           path + " = " + brief(value) + " is not an integer; allowed " + describe(range, path));
    }
    const bool in_range =
        value.is_number_unsigned() ? value.get<std::uint64_t>() <= static_cast<std::uint64_t>(hi) &&
                                         static_cast<long long>(value.get<std::uint64_t>()) >= lo
        : value.is_number_integer() ? value.get<long long>() >= lo && value.get<long long>() <= hi
                                    : range.contains(value.get<double>());
    if (!in_range) {
      fail(path,
           path + " = " + brief(value) + " is out of range; allowed " + describe(range, path));
    }
    return value.is_number_float() ? static_cast<long long>(value.get<double>())
                                   : value.get<long long>();
  }

  // Seeds are whole numbers; 1e3 is accepted, but a float beyond 2^53 no longer says which
  // integer it means and must be written out.
  std::uint64_t unsigned64(const json& value, const std::string& path) const {
    if (value.is_number_float()) {
      const double v = value.get<double>();
      if (v >= 0.0 && v <= 0x1p53 && v == std::floor(v)) {
        return static_cast<std::uint64_t>(v);
      }
    }
    if (!value.is_number_integer() || (!value.is_number_unsigned() && value.get<long long>() < 0)) {
      fail(path, path + " = " + brief(value) +
                     " is not an unsigned integer (floats only up to 2^53); allowed 0 <= " + path +
                     " <= 18446744073709551615");
    }
    return value.get<std::uint64_t>();
  }

  bool boolean(const json& value, const std::string& path) const {
    if (!value.is_boolean()) {
      fail(path, path + " = " + brief(value) + " is not a boolean; allowed true or false");
    }
    return value.get<bool>();
  }

  // Paths and names: non-empty, at most kMaxStringBytes, and no NUL (a path would end there
  // for the operating system: "a.png\u0000.txt" would open a.png).
  std::string string(const json& value, const std::string& path) const {
    if (!value.is_string()) {
      fail(path, path + " = " + brief(value) + " is not a string");
    }
    const std::string& s = value.get_ref<const std::string&>();
    if (s.empty()) {
      fail(path, path + " is empty; a non-empty string is required");
    }
    if (s.size() > limits::kMaxStringBytes) {
      fail(path, path + " = " + brief(value) + " is longer than " +
                     std::to_string(limits::kMaxStringBytes) + " bytes");
    }
    if (s.find('\0') != std::string::npos) {
      fail(path, path + " = " + brief(value) + " contains a NUL character");
    }
    return s;
  }

  // An output file name that must end in one of `extensions` (any letter case): the format it
  // is written in.
  std::string file_name(const json& value, const std::string& path,
                        const std::vector<std::string_view>& extensions,
                        std::string_view why) const {
    std::string name = string(value, path);
    std::string lower = name;
    std::transform(lower.begin(), lower.end(), lower.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    std::string allowed;
    for (const std::string_view extension : extensions) {
      if (lower.ends_with(extension)) {
        return name;
      }
      allowed += (allowed.empty() ? "" : " or ") + std::string(extension);
    }
    fail(path, path + " = " + brief(value) + ": " + std::string(why) + "; give a name ending in " +
                   allowed);
  }

  template <class Enum>
  Enum choice(const json& value, const std::string& path,
              const std::vector<std::pair<std::string, Enum>>& names) const {
    std::vector<std::string> allowed;
    for (const auto& [name, e] : names) {
      allowed.push_back(name);
    }
    if (value.is_string()) {
      for (const auto& [name, e] : names) {
        if (name == value.get<std::string>()) {
          return e;
        }
      }
    }
    fail(path, path + " = " + brief(value) + " is not allowed; allowed: " + join(allowed, ", "));
  }

  template <std::size_t N>
  std::array<double, N> vector(const json& value, const std::string& path,
                               const Range& range) const {
    if (!value.is_array() || value.size() != N) {
      fail(path,
           path + " = " + brief(value) + " must be an array of " + std::to_string(N) + " numbers");
    }
    std::array<double, N> out{};
    for (std::size_t k = 0; k < N; ++k) {
      out[k] = number(value[k], path + "[" + std::to_string(k) + "]", range);
    }
    return out;
  }

 private:
  std::string_view source_;
};

using Handlers =
    std::vector<std::pair<std::string, std::function<void(const json&, const std::string&)>>>;

}  // namespace relief
