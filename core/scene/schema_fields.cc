#include "core/scene/schema_fields.h"

#include <filesystem>
#include <string>

namespace relief {

std::string range_text(const Range& range) {
  if (!range.lo_open && !range.hi_open && range.lo == -range.hi && range.hi > 0.0) {
    return std::string("|·| ≤ ").append(format_number(range.hi));
  }
  std::string text(range.lo_open ? "(" : "[");
  text.append(format_number(range.lo)).append(", ").append(format_number(range.hi));
  return text.append(range.hi_open ? ")" : "]");
}

std::string powers_of_two_text(long long lo, long long hi) {
  std::vector<std::string> powers;
  for (long long p = lo; p > 0 && p <= hi; p *= 2) {
    powers.push_back(std::to_string(p));
  }
  if (powers.size() <= 4) {
    std::string text;
    for (std::size_t k = 0; k < powers.size(); ++k) {
      text.append(k == 0 ? "" : k + 1 == powers.size() ? " or " : ", ").append(powers[k]);
    }
    return text;
  }
  std::string text = powers[0];
  text.append(", ").append(powers[1]).append(", ").append(powers[2]).append(", ..., ");
  return text.append(powers.back());
}

std::string extensions_text(const std::vector<std::string_view>& extensions) {
  std::string text;
  for (std::size_t k = 0; k < extensions.size(); ++k) {
    text.append(k ? " or `" : "`").append(extensions[k]).append("`");
  }
  return text;
}

std::string resolve_scene_path(std::string name, const std::filesystem::path& base_dir) {
  if (name.rfind("builtin:", 0) == 0 || !std::filesystem::path(name).is_relative()) {
    return name;
  }
  std::error_code ec;
  const std::filesystem::path absolute = std::filesystem::absolute(base_dir / name, ec);
  return ec ? (base_dir / name).lexically_normal().string() : absolute.lexically_normal().string();
}

}  // namespace relief
