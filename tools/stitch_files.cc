#include "tools/stitch_files.h"

#include "core/input_file.h"
#include "core/scene/json_input.h"

namespace relief {

std::vector<unsigned char> read_shard_file(const std::string& file, const std::string& what) {
  try {
    InputFile in(file, kMaxShardFileBytes);
    const std::string bytes = in.read_rest();
    return {bytes.begin(), bytes.end()};
  } catch (const InputFileError& e) {
    throw ShardError(what + " " + brief_text(file) + ": " + e.what());
  }
}

std::uintmax_t shard_file_size(const std::filesystem::path& file) {
  std::error_code error;
  const std::uintmax_t size = std::filesystem::file_size(file, error);
  return error ? 0 : size;
}

std::string shard_name(const Shard& s) {
  return std::to_string(s.index) + "/" + std::to_string(s.count);
}

}  // namespace relief
