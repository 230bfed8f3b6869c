// relief_scene_docs: writes, or checks, what the scene-field schema generates in the
// repository: docs/scene-reference.md's scene table (between its BEGIN/END markers) and the
// scene fuzzers' dictionaries (fuzz/scene.dict, fuzz/override.dict).
//
//   relief_scene_docs --write ROOT   rewrite them after a scene field changed
//   relief_scene_docs --check ROOT   exit 1 naming each file that differs (ctest runs this)
//   relief_scene_docs --print        the table on standard output
#include <cstdio>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <string_view>

#include "core/scene/scene_reference.h"

namespace {

constexpr std::string_view kBegin =
    "<!-- BEGIN scene table: generated from core/scene/*_section.cc by relief_scene_docs --write "
    ". -->\n";
constexpr std::string_view kEnd = "<!-- END scene table -->\n";

// The page that holds the table, relative to the repository root.
constexpr std::string_view kTablePage = "docs/scene-reference.md";

bool read_file(const std::string& path, std::string& text) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    return false;
  }
  std::ostringstream buffer;
  buffer << in.rdbuf();
  text = buffer.str();
  return true;
}

bool write_file(const std::string& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out << text;
  return static_cast<bool>(out.flush());
}

// The page with the generated table between the markers; false if the markers are missing.
bool with_table(const std::string& page, std::string& out) {
  const std::size_t begin = page.find(kBegin);
  const std::size_t end = page.find(kEnd);
  if (begin == std::string::npos || end == std::string::npos || end < begin) {
    return false;
  }
  out = page.substr(0, begin + kBegin.size()) + relief::scene_reference_table() + page.substr(end);
  return true;
}

int run(const std::string& mode, const std::string& root) {
  const std::string table_page = root + "/" + std::string(kTablePage);
  std::string page;
  std::string generated_page;
  if (!read_file(table_page, page) || !with_table(page, generated_page)) {
    std::cerr << "relief_scene_docs: " << table_page
              << " is missing or has no scene-table markers\n";
    return 2;
  }
  const std::pair<std::string, std::string> files[] = {
      {table_page, generated_page},
      {root + "/fuzz/scene.dict", relief::scene_dictionary()},
      {root + "/fuzz/override.dict", relief::override_dictionary()},
  };
  int status = 0;
  for (const auto& [path, text] : files) {
    std::string current;
    const bool same = read_file(path, current) && current == text;
    if (mode == "--write" && !same && !write_file(path, text)) {
      std::cerr << "relief_scene_docs: cannot write " << path << "\n";
      status = 1;
    } else if (mode == "--check" && !same) {
      std::cerr << "relief_scene_docs: " << path
                << " differs from what the scene schema generates; run relief_scene_docs --write "
                << root << " and review the change\n";
      status = 1;
    }
  }
  return status;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string mode = argc > 1 ? argv[1] : "";
  if (argc == 2 && mode == "--print") {
    std::cout << relief::scene_reference_table();
    return 0;
  }
  if (argc == 3 && (mode == "--write" || mode == "--check")) {
    return run(mode, argv[2]);
  }
  std::cerr << "usage: relief_scene_docs --write ROOT | --check ROOT | --print\n";
  return 2;
}
