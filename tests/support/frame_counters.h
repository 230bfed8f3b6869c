// A frame's work counters (relief render --stats) by name, for the tests that prove a skip or
// count the work a stage did.
#pragma once

#include <cstdint>
#include <string>

#include <catch2/catch.hpp>

#include "pipeline/frame.h"

namespace relief::test {

// The sum of the counters named `name` over the frame's stages; fails if there is none.
inline std::uint64_t frame_counter(const Frame& frame, const std::string& name) {
  std::uint64_t sum = 0;
  bool found = false;
  for (const StageTime& stage : frame.stats.stages) {
    for (const WorkCounter& c : stage.counters) {
      if (c.name == name) {
        sum += c.value;
        found = true;
      }
    }
  }
  INFO("counter " << name);
  REQUIRE(found);
  return sum;
}

}  // namespace relief::test
