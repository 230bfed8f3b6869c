// Output files appear whole or not at all, and a command's files appear together or not at
// all: bytes go to temporary files in the targets' directories, which are renamed over the
// targets only once every file is written and flushed. An error removes the temporary files
// and leaves no output behind.
#pragma once

#include <filesystem>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "tools/distinct_paths.h"

namespace relief {

// An output could not be written (disk full, no permission, missing directory). The message
// names the file.
class OutputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The files of one command. add() writes each to a temporary file at once (so that no bytes
// are held in memory); commit() renames them all into place. Destroyed without commit(), or
// when add() or commit() throws, it removes every temporary file it made.
class OutputSet {
 public:
  OutputSet() = default;
  ~OutputSet();
  OutputSet(const OutputSet&) = delete;
  OutputSet& operator=(const OutputSet&) = delete;

  // Throws OutputError (and removes the set's temporary files) when `path` is a directory or
  // the bytes cannot be written. A symbolic link is written through (its target replaced).
  void add(const std::filesystem::path& path, std::span<const unsigned char> bytes);
  // Throws OutputError naming the files already renamed if a rename fails (rare: the
  // temporary files sit in the targets' directories, so a rename only fails for a target that
  // turned into a directory meanwhile).
  void commit();

 private:
  void discard();

  std::vector<std::pair<std::filesystem::path, std::filesystem::path>> files_;  // temp, target
};

// An output that would replace one of the process's protected inputs (ProtectedInputs): bad
// input (exit 2), found before anything is renamed into place, so nothing is written.
class OutputAliasError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// While one lives, OutputSet::add refuses (OutputAliasError) any output naming the same file as
// one of `inputs` (distinct_paths.h: links resolved): the files a command reads, its scene's
// above all, are never replaced by its outputs, whatever output a command forgot to check up
// front (a stress --sheet, a file inside stages' or sweep's --out). One at a time.
class ProtectedInputs {
 public:
  explicit ProtectedInputs(std::vector<CommandPath> inputs);
  ~ProtectedInputs();
  ProtectedInputs(const ProtectedInputs&) = delete;
  ProtectedInputs& operator=(const ProtectedInputs&) = delete;
};

// Why `path` cannot be written, checked before the work that makes it (an expensive command
// refuses up front, exit 2, rather than failing after it): it is a directory or a special
// file, its directory does not exist or is not one, or its name is longer than the file system
// allows (NAME_MAX, 255 bytes: the rename into place would fail after earlier files of the set
// were renamed). nullopt when none of these holds.
std::optional<std::string> output_path_problem(const std::filesystem::path& path);

// One file on its own: an OutputSet of one.
void write_file_atomically(const std::filesystem::path& path, std::span<const unsigned char> bytes);

// Creates `dir` (and parents) if needed; throws OutputError if it exists as a non-directory
// or cannot be created. The object removes the directory it created if it is destroyed
// before keep() (a command that failed leaves no empty directory behind; a directory with
// files in it is never removed).
class OutputDirectory {
 public:
  explicit OutputDirectory(const std::filesystem::path& dir);
  ~OutputDirectory();
  OutputDirectory(const OutputDirectory&) = delete;
  OutputDirectory& operator=(const OutputDirectory&) = delete;
  void keep() { created_.clear(); }

 private:
  std::vector<std::filesystem::path> created_;  // innermost first
};

}  // namespace relief
