// How much memory a job may use, and how much it will need, decided before any large
// allocation: a job that cannot fit is refused with its estimate (exit code 2) instead of being
// killed by the kernel or aborting on std::bad_alloc half way through.
#pragma once

#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace relief {

// The limit a job is checked against: the machine's available memory (Linux MemAvailable,
// the cgroup's remaining limit where one is set, and the address space left under the
// process's RLIMIT_AS where one is set), or --max-memory when that is lower.
struct MemoryBudget {
  std::uintmax_t bytes = UINTMAX_MAX;
  std::string source;  // what the limit is: "available memory", "--max-memory 2G"
};

// The address space the process may still map under its limit (ulimit -v, RLIMIT_AS): the
// limit minus what is mapped now (VmSize); nullopt without a limit.
std::optional<std::uintmax_t> address_space_remaining();

// The machine's available memory in bytes, or nullopt where it cannot be read.
std::optional<std::uintmax_t> available_memory();

// "4096", "512K", "2G", "1.5GiB", "800MB", "1E" (K, M, G, T, P, E are powers of 1024, with or
// without "iB"/"B"). nullopt for anything else, for values below 1 MiB and beyond 2^60 (1E).
std::optional<std::uintmax_t> parse_memory_size(std::string_view text);

MemoryBudget memory_budget(std::optional<std::uintmax_t> max_memory, std::string_view max_text);

// A job's estimated peak memory, as named parts ("image 1280x1024", "grid 512x512").
struct MemoryEstimate {
  std::vector<std::pair<std::string, std::uintmax_t>> parts;

  void add(std::string part, std::uintmax_t bytes) { parts.emplace_back(std::move(part), bytes); }
  std::uintmax_t total() const;
  std::string describe() const;  // "27.9 GiB (image 16384x16384: 26.1 GiB, ...)"
};

// A job that does not fit its budget: bad input (exit code 2), like any value out of range.
class MemoryLimitError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// What the budget leaves once the estimate is taken (0 when it does not fit).
std::uintmax_t memory_left(const MemoryEstimate& estimate, const MemoryBudget& budget);

// Throws MemoryLimitError naming the job, its estimate and the budget when it does not fit.
void check_memory(const MemoryEstimate& estimate, const MemoryBudget& budget, std::string_view job,
                  std::string_view advice);

}  // namespace relief
