// The scene file's "shading.gradient" section: castledragmire's height-to-colour gradient
// (shading.mode = "gradient"), its stops and the heights they span.
#include <string>

#include "core/limits.h"
#include "core/scene/scene_sections.h"
#include "core/scene/schema_fields.h"

namespace relief {

namespace {

const Schema<GradientStop>& stop_schema() {
  using S = GradientStop;
  static const Schema<S> schema({
      number_field("at", &S::at, Range{0.0, 1.0},
                   {"", "where the stop lies: 0 at the gradient's low height, 1 at its high one"}),
      vector_field("color", &S::color, Range{0.0, 1.0}, {"linear RGB", "the colour there"}),
  });
  return schema;
}

// shading.gradient.stops: the whole list at once (a list whose order is its meaning is not
// patched element by element); every stop names both fields, `at` never decreases.
Field<GradientSettings> stops_field() {
  const std::string count = std::to_string(limits::kMinGradientStops) + " to " +
                            std::to_string(limits::kMaxGradientStops);
  return {
      {"stops",
       "array of " + count + " objects with `at` and `color`, `at` non-decreasing",
       {"",
        "the gradient's colours, linear between neighbouring stops; two stops at one "
        "`at` make a step"},
       {},
       &stop_schema(),
       true},
      [count](const LayerContext& cx, const json& v, const std::string& p, GradientSettings& s) {
        if (!v.is_array() || v.size() < limits::kMinGradientStops ||
            v.size() > limits::kMaxGradientStops) {
          cx.in.fail(p, p + " = " + brief(v) + " is not an array of " + count + " stops");
        }
        std::vector<GradientStop> stops;
        for (std::size_t k = 0; k < v.size(); ++k) {
          const std::string at = p + "[" + std::to_string(k) + "]";
          if (!v[k].is_object() || !v[k].contains("at") || !v[k].contains("color")) {
            cx.in.fail(at, at + " = " + brief(v[k]) +
                               " is not a stop; allowed an object with `at` and `color`");
          }
          GradientStop stop;
          stop_schema().apply(cx, v[k], at, stop);
          if (!stops.empty() && stop.at < stops.back().at) {
            cx.in.fail(at + ".at",
                       at + ".at = " + format_number(stop.at) + " is below the stop before it (" +
                           format_number(stops.back().at) + "); allowed a non-decreasing `at`");
          }
          stops.push_back(stop);
        }
        s.stops = std::move(stops);
      },
      [](const GradientSettings& s) -> std::optional<json> {
        json stops = json::array();
        for (const GradientStop& stop : s.stops) {
          stops.push_back(stop_schema().write(stop));
        }
        return stops;
      }};
}

// shading.gradient.range: [low, high] world heights, or null for the terrain's height bounds.
Field<GradientSettings> range_field() {
  const Range heights{-limits::kMaxBaseHeight, limits::kMaxBaseHeight};
  return {
      {"range",
       "`null` or [low, high], each " + range_text(heights) + ", low < high",
       {"world units",
        "heights of `at` = 0 and 1; null: the terrain's height bounds (derived from the "
        "fBm, the sketch or the height field)"}},
      [heights](const LayerContext& cx, const json& v, const std::string& p, GradientSettings& s) {
        if (v.is_null()) {
          s.range.reset();
          return;
        }
        const std::array<double, 2> pair = cx.in.vector<2>(v, p, heights);
        if (!(pair[0] < pair[1])) {
          cx.in.fail(p, p + " = " + brief(v) + " is empty; allowed [low, high] with low < high");
        }
        s.range = pair;
      },
      [](const GradientSettings& s) -> std::optional<json> {
        return s.range ? numbers_json(*s.range) : json(nullptr);
      }};
}

}  // namespace

const Schema<GradientSettings>& gradient_schema() {
  static const Schema<GradientSettings> schema({range_field(), stops_field()});
  return schema;
}

}  // namespace relief
