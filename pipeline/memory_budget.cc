#include "pipeline/memory_budget.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>

#include <sys/resource.h>

#include "core/input_file.h"

namespace relief {

namespace {

// A single unsigned number from a small kernel file ("max" and anything else: nullopt).
std::optional<std::uintmax_t> read_number(const char* path) {
  std::ifstream in(path);
  std::uintmax_t value = 0;
  if (in >> value) {
    return value;
  }
  return std::nullopt;
}

// The memory cgroup's limit minus its usage (cgroup v2, else v1); nullopt without a limit.
std::optional<std::uintmax_t> cgroup_remaining() {
  std::optional<std::uintmax_t> limit = read_number("/sys/fs/cgroup/memory.max");
  std::optional<std::uintmax_t> usage = read_number("/sys/fs/cgroup/memory.current");
  if (!limit) {
    limit = read_number("/sys/fs/cgroup/memory/memory.limit_in_bytes");
    usage = read_number("/sys/fs/cgroup/memory/memory.usage_in_bytes");
  }
  // cgroup v1 reports "no limit" as a page-rounded 2^63.
  if (!limit || *limit >= (std::uintmax_t{1} << 62)) {
    return std::nullopt;
  }
  const std::uintmax_t used = usage.value_or(0);
  return *limit > used ? *limit - used : 0;
}

// A "Key: N kB" line of a kernel file (/proc/meminfo, /proc/self/status) in bytes; nullopt if
// the file or the key is missing.
std::optional<std::uintmax_t> read_kib_field(const char* path, std::string_view wanted) {
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream fields(line);
    std::string key;
    std::uintmax_t kib = 0;
    if (fields >> key >> kib && key == wanted) {
      return kib * 1024;
    }
  }
  return std::nullopt;
}

}  // namespace

// Allocations fail at the address-space limit long before physical memory runs out, so a job
// is checked against it too.
std::optional<std::uintmax_t> address_space_remaining() {
  rlimit limit{};
  if (getrlimit(RLIMIT_AS, &limit) != 0 || limit.rlim_cur == RLIM_INFINITY) {
    return std::nullopt;
  }
  const std::uintmax_t mapped = read_kib_field("/proc/self/status", "VmSize:").value_or(0);
  const std::uintmax_t cap = limit.rlim_cur;
  return cap > mapped ? cap - mapped : 0;
}

std::optional<std::uintmax_t> available_memory() {
  std::optional<std::uintmax_t> available = read_kib_field("/proc/meminfo", "MemAvailable:");
  if (const std::optional<std::uintmax_t> cgroup = cgroup_remaining()) {
    available = available ? std::min(*available, *cgroup) : *cgroup;
  }
  if (const std::optional<std::uintmax_t> address = address_space_remaining()) {
    available = available ? std::min(*available, *address) : *address;
  }
  return available;
}

std::optional<std::uintmax_t> parse_memory_size(std::string_view text) {
  double value = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || !std::isfinite(value) || value < 0) {
    return std::nullopt;
  }
  std::string unit(end, text.data() + text.size());
  std::transform(unit.begin(), unit.end(), unit.begin(),
                 [](unsigned char c) { return static_cast<char>(std::toupper(c)); });
  static const std::pair<const char*, int> kUnits[] = {
      {"", 0},     {"B", 0},   {"K", 10},   {"KB", 10},  {"KIB", 10}, {"M", 20},  {"MB", 20},
      {"MIB", 20}, {"G", 30},  {"GB", 30},  {"GIB", 30}, {"T", 40},   {"TB", 40}, {"TIB", 40},
      {"P", 50},   {"PB", 50}, {"PIB", 50}, {"E", 60},   {"EB", 60},  {"EIB", 60}};
  for (const auto& [name, shift] : kUnits) {
    if (unit == name) {
      const double bytes = std::ldexp(value, shift);
      if (bytes < 1048576.0 || bytes > 0x1p60) {
        return std::nullopt;
      }
      return static_cast<std::uintmax_t>(bytes);
    }
  }
  return std::nullopt;
}

MemoryBudget memory_budget(std::optional<std::uintmax_t> max_memory, std::string_view max_text) {
  MemoryBudget budget;
  if (const std::optional<std::uintmax_t> available = available_memory()) {
    budget.bytes = *available;
    budget.source = "the memory available on this machine";
  }
  if (max_memory && *max_memory < budget.bytes) {
    budget.bytes = *max_memory;
    budget.source = "--max-memory " + std::string(max_text);
  }
  return budget;
}

std::uintmax_t MemoryEstimate::total() const {
  std::uintmax_t sum = 0;
  for (const auto& part : parts) {
    sum += part.second;
  }
  return sum;
}

std::string MemoryEstimate::describe() const {
  std::string text = format_bytes(total()) + " (";
  for (std::size_t k = 0; k < parts.size(); ++k) {
    text += (k ? ", " : "") + parts[k].first + ": " + format_bytes(parts[k].second);
  }
  return text + ")";
}

std::uintmax_t memory_left(const MemoryEstimate& estimate, const MemoryBudget& budget) {
  return budget.bytes > estimate.total() ? budget.bytes - estimate.total() : 0;
}

void check_memory(const MemoryEstimate& estimate, const MemoryBudget& budget, std::string_view job,
                  std::string_view advice) {
  if (estimate.total() <= budget.bytes) {
    return;
  }
  const bool from_option = budget.source.rfind("--max-memory", 0) == 0;
  // Where the scene's files dominate, lowering the viewport or grid would not help: the advice
  // names what does.
  std::string remedy(advice);
  const auto largest =
      std::max_element(estimate.parts.begin(), estimate.parts.end(),
                       [](const auto& a, const auto& b) { return a.second < b.second; });
  if (largest != estimate.parts.end() && 2 * largest->second > estimate.total()) {
    const std::string& part = largest->first;
    // A caller's own way out ("..., or raise RenderOptions::max_memory_bytes") is kept.
    const std::size_t raise = advice.find(", or raise ");
    const std::string tail(raise == std::string_view::npos ? "" : advice.substr(raise));
    if (part.rfind("basis images", 0) == 0) {
      remedy =
          "The basis images dominate: use smaller images or a lower terrain.basis.upsample" + tail;
    } else if (part == "textures") {
      remedy = "The textures dominate: use smaller texture files or shading.texture_size" + tail;
    } else if (part == "height sketch") {
      remedy = "The height sketch dominates: use a smaller terrain.sketch.image" + tail;
    } else if (part == "height field") {
      remedy = "The height field dominates: use a smaller terrain.heightfield.file" + tail;
    }
  }
  throw MemoryLimitError(std::string(job) + " needs about " + estimate.describe() + "; " +
                         budget.source + " is " + format_bytes(budget.bytes) + ". " + remedy +
                         (from_option ? ", or raise --max-memory." : "."));
}

}  // namespace relief
