// Strict reading of JSON fields for the scene loader: every failure is a SceneError whose
// message names where the input came from, the JSON path, the value and the allowed range.
#pragma once

#include <charconv>
#include <cmath>
#include <functional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/scene_json.h"

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
                     value.dump());
    }
    for (const auto& [key, item] : value.items()) {
      const auto handler = std::find_if(handlers.begin(), handlers.end(),
                                        [&](const auto& h) { return h.first == key; });
      if (handler == handlers.end()) {
        std::vector<std::string> known;
        for (const auto& h : handlers) {
          known.push_back(h.first);
        }
        fail(child_path(path, key), "unknown key '" + child_path(path, key) + "'; allowed keys" +
                                        (path.empty() ? "" : " in " + path) + ": " +
                                        join(known, ", "));
      }
      handler->second(item, child_path(path, key));
    }
  }

  double number(const json& value, const std::string& path, const Range& range) const {
    if (!value.is_number()) {
      fail(path,
           path + " = " + value.dump() + " is not a number; allowed " + describe(range, path));
    }
    const double v = value.get<double>();
    if (!std::isfinite(v)) {
      fail(path, path + " = " + value.dump() + " is not a finite number");
    }
    if (!range.contains(v)) {
      fail(path,
           path + " = " + format_number(v) + " is out of range; allowed " + describe(range, path));
    }
    return v;
  }

  long long integer(const json& value, const std::string& path, long long lo, long long hi) const {
    const Range range{static_cast<double>(lo), static_cast<double>(hi)};
    if (!value.is_number_integer()) {
      fail(path,
           path + " = " + value.dump() + " is not an integer; allowed " + describe(range, path));
    }
    if (value.is_number_unsigned() && value.get<std::uint64_t>() > static_cast<std::uint64_t>(hi)) {
      fail(path,
           path + " = " + value.dump() + " is out of range; allowed " + describe(range, path));
    }
    const long long v = value.get<long long>();
    if (v < lo || v > hi) {
      fail(path,
           path + " = " + value.dump() + " is out of range; allowed " + describe(range, path));
    }
    return v;
  }

  std::uint64_t unsigned64(const json& value, const std::string& path) const {
    if (!value.is_number_integer() || (!value.is_number_unsigned() && value.get<long long>() < 0)) {
      fail(path, path + " = " + value.dump() + " is not an unsigned integer; allowed 0 <= " + path +
                     " <= 18446744073709551615");
    }
    return value.get<std::uint64_t>();
  }

  bool boolean(const json& value, const std::string& path) const {
    if (!value.is_boolean()) {
      fail(path, path + " = " + value.dump() + " is not a boolean; allowed true or false");
    }
    return value.get<bool>();
  }

  std::string string(const json& value, const std::string& path) const {
    if (!value.is_string()) {
      fail(path, path + " = " + value.dump() + " is not a string");
    }
    std::string s = value.get<std::string>();
    if (s.empty()) {
      fail(path, path + " is empty; a path is required");
    }
    return s;
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
    fail(path, path + " = " + value.dump() + " is not allowed; allowed: " + join(allowed, ", "));
  }

  template <std::size_t N>
  std::array<double, N> vector(const json& value, const std::string& path,
                               const Range& range) const {
    if (!value.is_array() || value.size() != N) {
      fail(path,
           path + " = " + value.dump() + " must be an array of " + std::to_string(N) + " numbers");
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
