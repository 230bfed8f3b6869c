// relief_scene_docs: writes, or checks, what the scene-field schema generates in the
// repository: README.md's scene table (between its BEGIN/END markers) and the scene fuzzers'
// dictionaries (fuzz/scene.dict, fuzz/override.dict).
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

// README.md with the generated table between the markers; false if the markers are missing.
bool with_table(const std::string& readme, std::string& out) {
  const std::size_t begin = readme.find(kBegin);
  const std::size_t end = readme.find(kEnd);
  if (begin == std::string::npos || end == std::string::npos || end < begin) {
    return false;
  }
  out = readme.substr(0, begin + kBegin.size()) + relief::scene_reference_table() +
        readme.substr(end);
  return true;
}

int run(const std::string& mode, const std::string& root) {
  std::string readme;
  std::string generated_readme;
  if (!read_file(root + "/README.md", readme) || !with_table(readme, generated_readme)) {
    std::cerr << "relief_scene_docs: " << root
              << "/README.md is missing or has no scene-table markers\n";
    return 2;
  }
  const std::pair<std::string, std::string> files[] = {
      {root + "/README.md", generated_readme},
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
