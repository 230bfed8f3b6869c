// Reading files that come from users (scene files, textures, triangle soups): only regular
// files, opened without blocking and with their size checked before a byte is read, so that a
// directory, a FIFO with no writer, /dev/zero or a multi-gigabyte file behind an innocent name
// is refused at once with a reason instead of hanging, aborting or exhausting memory.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <string_view>

namespace relief {

// Why a file cannot be read. what() is the reason alone ("is a directory, not a regular
// file"); the caller names the file and the field it came from.
class InputFileError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class InputFile {
 public:
  // Opens `path` read-only and non-blocking, and checks that it is a regular file of at most
  // `max_bytes` bytes. Throws InputFileError.
  InputFile(const std::filesystem::path& path, std::uintmax_t max_bytes);
  ~InputFile();
  InputFile(const InputFile&) = delete;
  InputFile& operator=(const InputFile&) = delete;

  std::uintmax_t size() const { return size_; }
  // Reads up to `count` bytes into `data`; fewer only at the end of the file. Throws
  // InputFileError on a read error or if the file grows past its checked size.
  std::size_t read(void* data, std::size_t count);
  // The rest of the file.
  std::string read_rest();

 private:
  int fd_ = -1;
  std::uintmax_t size_ = 0;
  std::uintmax_t position_ = 0;
  std::uintmax_t max_bytes_ = 0;
};

// Whether `name` ends in `extension` (lower case, with its dot), in any letter case.
bool has_extension(const std::string& name, std::string_view extension);

// "16 MiB", "1.5 GiB", "512 bytes": a size for messages.
std::string format_bytes(std::uintmax_t bytes);

}  // namespace relief
