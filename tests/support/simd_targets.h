// The Highway targets a test checks here: every target compiled in that this CPU runs, each
// forced in turn (simd::force_target); the others are named, so that a run on a machine
// without AVX-512 says AVX3 was not checked there.
#pragma once

#include <initializer_list>
#include <string>
#include <vector>

#include <tbb/global_control.h>

#include "simd/targets.h"

namespace relief {

// The targets to check here; restores the best target when it goes out of scope.
class EachTarget {
 public:
  EachTarget() {
    for (const simd::Target& t : simd::compiled_targets()) {
      if (t.supported) {
        runnable_.push_back(t.name);
      } else {
        skipped_ += (skipped_.empty() ? "" : ", ") + t.name;
      }
    }
  }
  ~EachTarget() { simd::force_target("best"); }
  EachTarget(const EachTarget&) = delete;
  EachTarget& operator=(const EachTarget&) = delete;

  const std::vector<std::string>& runnable() const { return runnable_; }

  // body(target, threads) for every runnable target, forced, and each thread count, the pool
  // limited to it (whole-frame bit-identity checks).
  template <class Body>
  void each_with_threads(std::initializer_list<int> thread_counts, const Body& body) const {
    for (const std::string& target : runnable_) {
      simd::force_target(target);
      for (const int threads : thread_counts) {
        const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
        body(target, threads);
      }
    }
  }
  const std::string& skipped() const { return skipped_; }

 private:
  std::vector<std::string> runnable_;
  std::string skipped_;
};

}  // namespace relief
