#include "tools/atomic_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>

#include "core/scene/json_input.h"

namespace relief {

namespace {

std::string errno_text() {
  return std::strerror(errno);
}

std::string quoted(const std::filesystem::path& path) {
  return brief_text(path.string());
}

// A temporary name in the target's directory, short whatever the target's name is (a name
// derived from it could pass the file system's 255-byte limit).
// The inputs of the command running now (ProtectedInputs).
std::vector<CommandPath>& protected_inputs() {
  static std::vector<CommandPath> inputs;
  return inputs;
}

std::filesystem::path temporary_for(const std::filesystem::path& path) {
  static std::atomic<unsigned> counter{0};
  return path.parent_path() /
         (".relief-" + std::to_string(::getpid()) + "-" + std::to_string(counter++) + ".tmp");
}

void write_temporary(const std::filesystem::path& temporary, const std::filesystem::path& path,
                     std::span<const unsigned char> bytes) {
  const int fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
  if (fd < 0) {
    throw OutputError("cannot write " + quoted(path) + ": " + errno_text());
  }
  std::size_t written = 0;
  while (written < bytes.size()) {
    const ssize_t n = ::write(fd, bytes.data() + written, bytes.size() - written);
    if (n < 0 && errno == EINTR) {
      continue;
    }
    if (n <= 0) {
      const std::string reason = n < 0 ? errno_text() : "no space written";
      ::close(fd);
      ::unlink(temporary.c_str());
      throw OutputError("cannot write " + quoted(path) + ": " + reason);
    }
    written += static_cast<std::size_t>(n);
  }
  if (::fsync(fd) != 0) {
    const std::string reason = errno_text();
    ::close(fd);
    ::unlink(temporary.c_str());
    throw OutputError("cannot write " + quoted(path) + ": " + reason);
  }
  if (::close(fd) != 0) {
    const std::string reason = errno_text();
    ::unlink(temporary.c_str());
    throw OutputError("cannot write " + quoted(path) + ": " + reason);
  }
}

}  // namespace

OutputSet::~OutputSet() {
  discard();
}

void OutputSet::discard() {
  for (const auto& [temporary, target] : files_) {
    ::unlink(temporary.c_str());
  }
  files_.clear();
}

ProtectedInputs::ProtectedInputs(std::vector<CommandPath> inputs) {
  protected_inputs() = std::move(inputs);
}

ProtectedInputs::~ProtectedInputs() {
  protected_inputs().clear();
}

std::optional<std::string> output_path_problem(const std::filesystem::path& path) {
  constexpr std::size_t kMaxNameBytes = 255;  // NAME_MAX of Linux's file systems
  if (path.filename().string().size() > kMaxNameBytes) {
    return quoted(path) + ": the file name is " + std::to_string(path.filename().string().size()) +
           " bytes; the file system allows at most " + std::to_string(kMaxNameBytes);
  }
  std::error_code ec;
  const std::filesystem::file_status status = std::filesystem::status(path, ec);
  if (std::filesystem::is_symlink(std::filesystem::symlink_status(path, ec)) &&
      !std::filesystem::exists(status)) {
    return quoted(path) + " is a link to " + quoted(std::filesystem::read_symlink(path, ec)) +
           ", which does not exist; give the link a target or another name";
  }
  if (std::filesystem::is_directory(status)) {
    return quoted(path) + " is a directory; give a file name";
  }
  if (std::filesystem::exists(status) && !std::filesystem::is_regular_file(status)) {
    return quoted(path) + " is not a regular file (a device, FIFO or socket); give a file name";
  }
  const std::filesystem::path dir =
      path.has_parent_path() ? path.parent_path() : std::filesystem::path(".");
  if (!std::filesystem::is_directory(dir, ec)) {
    return quoted(path) + ": its directory " + quoted(dir) + " does not exist";
  }
  return std::nullopt;
}

void OutputSet::add(const std::filesystem::path& named, std::span<const unsigned char> bytes) {
  // A symbolic link is written through: its target is replaced, the link kept (renaming over
  // the link itself would have replaced the link, /dev/stdout's included).
  std::error_code link_error;
  std::filesystem::path path = named;
  if (std::filesystem::is_symlink(std::filesystem::symlink_status(named, link_error))) {
    path = std::filesystem::weakly_canonical(named, link_error);
    if (link_error || path.empty() || !std::filesystem::exists(path, link_error)) {
      discard();
      throw OutputError("cannot write " + quoted(named) +
                        ": it is a link to a file that does not exist (or cannot be followed)");
    }
  }
  if (path.filename().string().size() > 255) {  // NAME_MAX: the rename would fail at commit
    discard();
    throw OutputError("cannot write " + quoted(path) + ": the file name is longer than 255 bytes");
  }
  for (const CommandPath& input : protected_inputs()) {
    if (!input.path.empty() && same_file(path, input.path)) {
      discard();
      throw OutputAliasError("the output " + quoted(path) + " names the same file as the input " +
                             input.option + " " + quoted(input.path) +
                             "; nothing was written. Give another output name");
    }
  }
  std::error_code ec;
  const std::filesystem::file_status status = std::filesystem::status(path, ec);
  if (std::filesystem::is_directory(status)) {
    discard();
    throw OutputError("cannot write " + quoted(path) + ": it is a directory");
  }
  // The file is renamed into place: over a device, FIFO or socket (/dev/null, /dev/stdout, a
  // pipe) that would replace the special file itself, which root may do. Refused instead.
  if (std::filesystem::exists(status) && !std::filesystem::is_regular_file(status)) {
    discard();
    throw OutputError("cannot write " + quoted(path) +
                      ": it is not a regular file (a device, FIFO or socket); give a file name");
  }
  const std::filesystem::path temporary = temporary_for(path);
  try {
    write_temporary(temporary, path, bytes);
  } catch (const OutputError&) {
    discard();
    throw;
  }
  files_.emplace_back(temporary, path);
}

void OutputSet::commit() {
  std::string renamed;
  for (std::size_t k = 0; k < files_.size(); ++k) {
    const std::filesystem::path temporary = files_[k].first, target = files_[k].second;
    if (::rename(temporary.c_str(), target.c_str()) != 0) {
      const std::string reason = errno_text();
      // The files before k are in place; the rest are removed.
      files_.erase(files_.begin(), files_.begin() + static_cast<std::ptrdiff_t>(k));
      discard();
      throw OutputError("cannot write " + quoted(target) + ": " + reason +
                        (renamed.empty() ? "" : " (already written: " + renamed + ")"));
    }
    renamed += (renamed.empty() ? "" : ", ") + quoted(target);
  }
  files_.clear();
}

void write_file_atomically(const std::filesystem::path& path,
                           std::span<const unsigned char> bytes) {
  OutputSet set;
  set.add(path, bytes);
  set.commit();
}

OutputDirectory::OutputDirectory(const std::filesystem::path& dir) {
  std::error_code ec;
  if (dir.empty() || std::filesystem::is_directory(dir, ec)) {
    return;
  }
  if (std::filesystem::exists(dir, ec)) {
    throw OutputError("cannot write into " + quoted(dir) + ": it exists and is not a directory");
  }
  // The directories this creates, innermost first, so that they can be removed again.
  for (std::filesystem::path p = dir; !p.empty() && !std::filesystem::exists(p, ec);
       p = p.parent_path()) {
    created_.push_back(p);
    if (p == p.parent_path()) {
      break;
    }
  }
  if (!std::filesystem::create_directories(dir, ec) || ec) {
    created_.clear();
    throw OutputError("cannot create directory " + quoted(dir) + ": " + ec.message());
  }
}

OutputDirectory::~OutputDirectory() {
  std::error_code ec;
  for (const std::filesystem::path& p : created_) {
    std::filesystem::remove(p, ec);  // only while empty
  }
}

}  // namespace relief
