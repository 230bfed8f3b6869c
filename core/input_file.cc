#include "core/input_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <system_error>

namespace relief {

namespace {

std::string not_regular(mode_t mode) {
  const char* kind = S_ISDIR(mode)    ? "a directory"
                     : S_ISFIFO(mode) ? "a FIFO (named pipe)"
                     : S_ISCHR(mode)  ? "a character device"
                     : S_ISBLK(mode)  ? "a block device"
                     : S_ISSOCK(mode) ? "a socket"
                                      : nullptr;
  return kind ? std::string("is ") + kind + ", not a regular file" : "is not a regular file";
}

}  // namespace

InputFile::InputFile(const std::filesystem::path& path, std::uintmax_t max_bytes)
    : max_bytes_(max_bytes) {
  // O_NONBLOCK: opening a FIFO must not wait for a writer; it is refused just below.
  fd_ = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd_ < 0) {
    throw InputFileError(std::string("cannot be opened: ") +
                         std::generic_category().message(errno));
  }
  struct stat status {};
  if (::fstat(fd_, &status) != 0) {
    const std::string reason = std::generic_category().message(errno);
    ::close(fd_);
    throw InputFileError("cannot be examined: " + reason);
  }
  if (!S_ISREG(status.st_mode)) {
    ::close(fd_);
    throw InputFileError(not_regular(status.st_mode));
  }
  size_ = static_cast<std::uintmax_t>(status.st_size);
  if (size_ > max_bytes_) {
    ::close(fd_);
    throw InputFileError("is " + format_bytes(size_) + "; allowed at most " +
                         format_bytes(max_bytes_));
  }
}

InputFile::~InputFile() {
  if (fd_ >= 0) {
    ::close(fd_);
  }
}

std::size_t InputFile::read(void* data, std::size_t count) {
  std::size_t done = 0;
  auto* bytes = static_cast<unsigned char*>(data);
  while (done < count) {
    const ssize_t n = ::read(fd_, bytes + done, count - done);
    if (n < 0 && (errno == EINTR || errno == EAGAIN)) {
      continue;
    }
    if (n < 0) {
      throw InputFileError(std::string("cannot be read: ") +
                           std::generic_category().message(errno));
    }
    if (n == 0) {
      break;
    }
    done += static_cast<std::size_t>(n);
    position_ += static_cast<std::uintmax_t>(n);
    if (position_ > max_bytes_) {
      throw InputFileError("grew past " + format_bytes(max_bytes_) + " while being read");
    }
  }
  return done;
}

std::string InputFile::read_rest() {
  std::string text(size_ > position_ ? size_ - position_ : 0, '\0');
  text.resize(read(text.data(), text.size()));
  // A file that grew since fstat: read on, within the limit.
  char chunk[4096];
  while (const std::size_t n = read(chunk, sizeof chunk)) {
    text.append(chunk, n);
  }
  return text;
}

bool has_extension(const std::string& name, std::string_view extension) {
  if (name.size() < extension.size()) {
    return false;
  }
  for (std::size_t k = 0; k < extension.size(); ++k) {
    const char c = name[name.size() - extension.size() + k];
    if (std::tolower(static_cast<unsigned char>(c)) != extension[k]) {
      return false;
    }
  }
  return true;
}

std::string format_bytes(std::uintmax_t bytes) {
  const char* units[] = {"bytes", "KiB", "MiB", "GiB", "TiB"};
  double value = static_cast<double>(bytes);
  int unit = 0;
  while (value >= 1024.0 && unit < 4) {
    value /= 1024.0;
    ++unit;
  }
  char text[32];
  std::snprintf(text, sizeof text, unit == 0 ? "%.0f %s" : "%.1f %s", value, units[unit]);
  return text;
}

}  // namespace relief
