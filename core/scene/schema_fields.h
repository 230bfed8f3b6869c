// Builders of single scene fields (scene_schema.h): each takes the JSON key, the member it
// sets, its range and its documentation, and returns the field's reader, writer and allowed
// text. Every failure goes through LayerReader, so each message names the path, the value
// and the allowed range.
#pragma once

#include <array>
#include <bit>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "core/scene/scene_schema.h"

namespace relief {

// "[1.001, 16]", "(0, 1e9]", "|·| ≤ 1e12": a range as docs/scene-reference.md prints it.
std::string range_text(const Range& range);
// "4, 8, 16, ..., 4096" or "1, 2, 4 or 8": the powers of two from lo to hi.
std::string powers_of_two_text(long long lo, long long hi);
// "`.pfm` or `.exr`".
std::string extensions_text(const std::vector<std::string_view>& extensions);
// A file name relative to `base_dir` (the scene file's directory, the current one for --set)
// made absolute, so that the printed scene loads back from anywhere; "builtin:..." and absolute
// names unchanged.
std::string resolve_scene_path(std::string name, const std::filesystem::path& base_dir);

template <class S>
Field<S> number_field(std::string key, double S::*member, Range range, FieldDoc doc) {
  return {{std::move(key), range_text(range), doc},
          [member, range](const LayerContext& cx, const json& v, const std::string& p, S& s) {
            s.*member = cx.in.number(v, p, range);
          },
          [member](const S& s) -> std::optional<json> { return json(s.*member); }};
}

// A number or null: null is the field's "none" (terrain.water_level: no water).
template <class S>
Field<S> nullable_number_field(std::string key, std::optional<double> S::*member, Range range,
                               FieldDoc doc) {
  return {{std::move(key), range_text(range) + " or `null`", doc},
          [member, range](const LayerContext& cx, const json& v, const std::string& p, S& s) {
            if (v.is_null()) {
              (s.*member).reset();
            } else {
              s.*member = cx.in.number(v, p, range);
            }
          },
          [member](const S& s) -> std::optional<json> {
            return s.*member ? json(*(s.*member)) : json(nullptr);
          }};
}

template <class S>
Field<S> integer_field(std::string key, int S::*member, long long lo, long long hi, FieldDoc doc) {
  return {
      {std::move(key),
       "integer in " + range_text(Range{static_cast<double>(lo), static_cast<double>(hi)}), doc},
      [member, lo, hi](const LayerContext& cx, const json& v, const std::string& p, S& s) {
        s.*member = static_cast<int>(cx.in.integer(v, p, lo, hi));
      },
      [member](const S& s) -> std::optional<json> { return json(s.*member); }};
}

// Sizes that halve down a mip chain or a lattice: a power of two from lo to hi.
template <class S>
Field<S> power_of_two_field(std::string key, int S::*member, long long lo, long long hi,
                            FieldDoc doc) {
  return {{std::move(key), powers_of_two_text(lo, hi), doc},
          [member, lo, hi](const LayerContext& cx, const json& v, const std::string& p, S& s) {
            const long long size = cx.in.integer(v, p, lo, hi);
            if (!std::has_single_bit(static_cast<unsigned long long>(size))) {
              cx.in.fail(p, p + " = " + brief(v) + " is not a power of two; allowed " +
                                powers_of_two_text(lo, hi));
            }
            s.*member = static_cast<int>(size);
          },
          [member](const S& s) -> std::optional<json> { return json(s.*member); }};
}

template <class S>
Field<S> unsigned64_field(std::string key, std::uint64_t S::*member, FieldDoc doc) {
  return {{std::move(key), "integer in [0, 2^64 − 1] (a float only up to 2^53)", doc},
          [member](const LayerContext& cx, const json& v, const std::string& p, S& s) {
            s.*member = cx.in.unsigned64(v, p);
          },
          [member](const S& s) -> std::optional<json> { return json(s.*member); }};
}

template <class S>
Field<S> boolean_field(std::string key, bool S::*member, FieldDoc doc) {
  return {{std::move(key), "`true`, `false`", doc, {"true", "false"}},
          [member](const LayerContext& cx, const json& v, const std::string& p, S& s) {
            s.*member = cx.in.boolean(v, p);
          },
          [member](const S& s) -> std::optional<json> { return json(s.*member); }};
}

template <std::size_t N>
json numbers_json(const std::array<double, N>& values) {
  json out = json::array();
  for (const double v : values) {
    out.push_back(v);
  }
  return out;
}

template <class S, std::size_t N>
Field<S> vector_field(std::string key, std::array<double, N> S::*member, Range range,
                      FieldDoc doc) {
  return {{std::move(key), std::to_string(N) + " numbers, each " + range_text(range), doc},
          [member, range](const LayerContext& cx, const json& v, const std::string& p, S& s) {
            s.*member = cx.in.vector<N>(v, p, range);
          },
          [member](const S& s) -> std::optional<json> { return numbers_json(s.*member); }};
}

// [low, high] with low < high: a band of heights or slopes.
template <class S>
Field<S> increasing_pair_field(std::string key, std::array<double, 2> S::*member, Range range,
                               FieldDoc doc) {
  return {{std::move(key), "[low, high], each " + range_text(range) + ", low < high", doc},
          [member, range](const LayerContext& cx, const json& v, const std::string& p, S& s) {
            const std::array<double, 2> pair = cx.in.vector<2>(v, p, range);
            if (!(pair[0] < pair[1])) {
              cx.in.fail(p,
                         p + " = " + brief(v) + " is empty; allowed [low, high] with low < high");
            }
            s.*member = pair;
          },
          [member](const S& s) -> std::optional<json> { return numbers_json(s.*member); }};
}

template <class S, class Enum>
Field<S> choice_field(std::string key, Enum S::*member,
                      std::vector<std::pair<std::string, Enum>> names, FieldDoc doc) {
  FieldInfo info{std::move(key), "", doc};
  for (const auto& [name, value] : names) {
    info.allowed += (info.allowed.empty() ? "`" : ", `") + name + "`";
    info.words.push_back(name);
  }
  return {std::move(info),
          [member, names](const LayerContext& cx, const json& v, const std::string& p, S& s) {
            s.*member = cx.in.choice<Enum>(v, p, names);
          },
          [member, names](const S& s) -> std::optional<json> {
            for (const auto& [name, value] : names) {
              if (value == s.*member) {
                return json(name);
              }
            }
            return json(nullptr);  // unreachable: every enumerator has a name
          }};
}

// A name: non-empty, at most kMaxStringBytes, no NUL (LayerReader::string).
template <class S>
Field<S> text_field(std::string key, std::string S::*member, FieldDoc doc) {
  return {{std::move(key), "non-empty string", doc},
          [member](const LayerContext& cx, const json& v, const std::string& p, S& s) {
            s.*member = cx.in.string(v, p);
          },
          [member](const S& s) -> std::optional<json> { return json(s.*member); }};
}

// An input file: "builtin:NAME" or a path, relative ones made absolute against the layer's
// directory (resolve_scene_path). Whether it can be read is checked where it is loaded.
template <class S>
Field<S> input_file_field(std::string key, std::string S::*member, FieldDoc doc) {
  return {{std::move(key), "`builtin:NAME` or a file path (relative to the scene file)", doc},
          [member](const LayerContext& cx, const json& v, const std::string& p, S& s) {
            s.*member = resolve_scene_path(cx.in.string(v, p), cx.base_dir);
          },
          [member](const S& s) -> std::optional<json> { return json(s.*member); }};
}

// An output file whose extension names the format it is written in.
template <class S>
Field<S> output_file_field(std::string key, std::string S::*member,
                           std::vector<std::string_view> extensions, std::string_view why,
                           FieldDoc doc) {
  return {{std::move(key), "path ending in " + extensions_text(extensions), doc},
          [member, extensions, why](const LayerContext& cx, const json& v, const std::string& p,
                                    S& s) { s.*member = cx.in.file_name(v, p, extensions, why); },
          [member](const S& s) -> std::optional<json> { return json(s.*member); }};
}

template <class S>
Field<S> nullable_output_file_field(std::string key, std::optional<std::string> S::*member,
                                    std::vector<std::string_view> extensions, std::string_view why,
                                    FieldDoc doc) {
  return {
      {std::move(key), "`null` or a path ending in " + extensions_text(extensions), doc},
      [member, extensions, why](const LayerContext& cx, const json& v, const std::string& p, S& s) {
        if (v.is_null()) {
          (s.*member).reset();
        } else {
          s.*member = cx.in.file_name(v, p, extensions, why);
        }
      },
      [member](const S& s) -> std::optional<json> {
        return s.*member ? json(*(s.*member)) : json(nullptr);
      }};
}

// A nested object read with its own schema, patched key by key.
template <class S, class T>
Field<S> section_field(std::string key, T S::*member, const Schema<T>& schema, FieldDoc doc) {
  return {{std::move(key), "object", doc, {}, &schema},
          [member, &schema](const LayerContext& cx, const json& v, const std::string& p, S& s) {
            schema.apply(cx, v, p, s.*member);
          },
          [member, &schema](const S& s) -> std::optional<json> { return schema.write(s.*member); }};
}

// A nested object that may be absent: null removes it, an object patches it, and a new one
// must give `required_key` (described in messages as `required_phrase`: an "image"). Printed
// as null when absent, or left out where `printed` says so.
template <class S, class T>
Field<S> optional_section_field(std::string key, std::optional<T> S::*member,
                                const Schema<T>& schema, std::string required_key,
                                std::string required_phrase, FieldDoc doc,
                                bool (*printed)(const T&) = nullptr) {
  std::string allowed =
      "`null` or an object" + (required_key.empty() ? std::string() : " with " + required_phrase);
  return {{std::move(key), std::move(allowed), doc, {}, &schema},
          [member, &schema, required_key, required_phrase](const LayerContext& cx, const json& v,
                                                           const std::string& p, S& s) {
            std::optional<T>& target = s.*member;
            if (v.is_null()) {
              target.reset();
              return;
            }
            if (!target && !required_key.empty() && v.is_object() && !v.contains(required_key)) {
              cx.in.fail(p, p + " must be null or an object with at least " + required_phrase);
            }
            T section = target.value_or(schema.prototype());
            schema.apply(cx, v, p, section);
            target = std::move(section);
          },
          [member, &schema, printed](const S& s) -> std::optional<json> {
            const std::optional<T>& section = s.*member;
            if (printed && !(section && printed(*section))) {
              return std::nullopt;
            }
            return section ? schema.write(*section) : json(nullptr);
          }};
}

}  // namespace relief
