// Output files appear whole or not at all: bytes go to a temporary file in the target's
// directory, which is renamed over the target only once everything is written and flushed.
// A crash or an error leaves no partial output (the temporary file is removed on error).
#pragma once

#include <filesystem>
#include <span>
#include <stdexcept>
#include <string>

namespace relief {

// An output could not be written (disk full, no permission, missing directory). The message
// names the file.
class OutputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

void write_file_atomically(const std::filesystem::path& path, std::span<const unsigned char> bytes);

// Creates `dir` (and parents) if needed; throws OutputError if it exists as a non-directory
// or cannot be created.
void ensure_directory(const std::filesystem::path& dir);

}  // namespace relief
