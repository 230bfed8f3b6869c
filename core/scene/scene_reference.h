// What the scene-field schema (scene_schema.h) generates besides the reader and the writer:
// docs/scene-reference.md's table and the scene fuzzers' dictionaries. tools/scene_docs_main.cc
// writes them into the repository and checks them there (ctest scene_docs_match_the_schema).
#pragma once

#include <string>
#include <vector>

namespace relief {

// One row per field: its path ("terrain.warp.c1", "shading.layers[k].name"), its default as
// the writer prints it, what is allowed (type, range, then the rules across fields), its unit
// and its meaning.
struct SceneFieldRow {
  std::string path;
  std::string default_text;
  std::string allowed;
  std::string unit;
  std::string meaning;
  std::vector<std::string> words;  // a choice's strings
  bool array_element = false;      // under an array: path holds "[k]"
};
std::vector<SceneFieldRow> scene_field_rows();

// The table of docs/scene-reference.md, Markdown, ending in a newline.
std::string scene_reference_table();

// The fuzzers' dictionaries (libFuzzer's -dict format, one quoted token per line, sorted):
// the scene fuzzer's JSON keys and values, and the override fuzzer's KEY= paths and values.
std::string scene_dictionary();
std::string override_dictionary();

}  // namespace relief
