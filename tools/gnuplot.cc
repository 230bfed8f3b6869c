#include "tools/gnuplot.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <system_error>

extern char** environ;

namespace relief {

namespace {

namespace fs = std::filesystem;

// A directory of our own under the system's temporary directory (mkdtemp: mode 0700, a fresh
// name), removed with its contents when done.
class PrivateDirectory {
 public:
  PrivateDirectory() {
    std::string pattern = (fs::temp_directory_path() / "relief-gnuplot-XXXXXX").string();
    if (mkdtemp(pattern.data()) != nullptr) {
      path_ = pattern;
    }
  }
  ~PrivateDirectory() {
    std::error_code ignored;
    if (!path_.empty()) {
      fs::remove_all(path_, ignored);
    }
  }
  PrivateDirectory(const PrivateDirectory&) = delete;
  PrivateDirectory& operator=(const PrivateDirectory&) = delete;
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

std::string read_text(const fs::path& path, std::size_t limit) {
  std::ifstream in(path, std::ios::binary);
  std::string text(std::istreambuf_iterator<char>(in), {});
  if (text.size() > limit) {
    text.resize(limit);
  }
  while (!text.empty() && (text.back() == '\n' || text.back() == '\r')) {
    text.pop_back();
  }
  return text;
}

}  // namespace

GnuplotResult run_gnuplot(const std::string& script) {
  GnuplotResult result;
  PrivateDirectory dir;
  if (dir.path().empty()) {
    result.message = std::string("cannot make a temporary directory: ") + std::strerror(errno);
    return result;
  }
  const std::string script_path = (dir.path() / "plot.gp").string();
  const std::string png_path = (dir.path() / "plot.png").string();
  const std::string log_path = (dir.path() / "gnuplot.log").string();
  {
    std::ofstream file(script_path, std::ios::binary);
    file << script;
    if (!file.flush()) {
      result.message = "cannot write the script to " + script_path;
      return result;
    }
  }
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, log_path.c_str(),
                                   O_WRONLY | O_CREAT | O_TRUNC, 0600);
  std::string program = "gnuplot", flag = "-c";
  std::string script_arg = script_path, png_arg = png_path;
  char* argv[] = {program.data(), flag.data(), script_arg.data(), png_arg.data(), nullptr};
  pid_t pid = 0;
  const int spawned = posix_spawnp(&pid, "gnuplot", &actions, nullptr, argv, environ);
  posix_spawn_file_actions_destroy(&actions);
  if (spawned != 0) {
    result.status =
        spawned == ENOENT ? GnuplotResult::Status::kMissing : GnuplotResult::Status::kFailed;
    result.message = std::string("cannot run gnuplot: ") + std::strerror(spawned);
    return result;
  }
  int status = 0;
  while (waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) {
      result.message = std::string("cannot wait for gnuplot: ") + std::strerror(errno);
      return result;
    }
  }
  const std::string log = read_text(log_path, 2000);
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    // 127: the child could not execute it (some C libraries report that only this way).
    if (WIFEXITED(status) && WEXITSTATUS(status) == 127 && log.empty()) {
      result.status = GnuplotResult::Status::kMissing;
      result.message = "cannot run gnuplot";
      return result;
    }
    result.message = "gnuplot failed" + (log.empty() ? std::string() : ": " + log);
    return result;
  }
  std::ifstream png(png_path, std::ios::binary);
  result.png.assign(std::istreambuf_iterator<char>(png), {});
  if (result.png.size() < 8) {
    result.message = "gnuplot wrote no image" + (log.empty() ? std::string() : ": " + log);
    return result;
  }
  result.status = GnuplotResult::Status::kDrawn;
  return result;
}

}  // namespace relief
