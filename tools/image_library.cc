#include "tools/image_library.h"

#include <dlfcn.h>
#include <link.h>

#include <algorithm>
#include <filesystem>
#include <mutex>
#include <thread>

#include "core/input_file.h"
#include "pipeline/heightfield_files.h"
#include "pipeline/memory_budget.h"

namespace relief {

namespace {

namespace fs = std::filesystem;

// The address space loading OpenImageIO takes: its 250 libraries and what their static
// initialisers start (log4cplus a thread, OpenImageIO its pool). Below it those initialisers die
// of a signal inside dlopen instead of failing, so the load is refused with a message, as the GL
// driver's is (pipeline/gl_backend.cc). Measured on Debian 12 (OpenImageIO 2.4, 2 cores): a
// load with 428 MiB of address space left succeeds and one with 423 MiB dies; counted as
// 448 MiB and 8 MiB a CPU for threads' stacks.
std::uintmax_t load_address_space() {
  return (std::uintmax_t{448} << 20) +
         (std::uintmax_t{8} << 20) * std::max(1u, std::thread::hardware_concurrency());
}

// Where the module may be: $RELIEF_IMAGE_LIBRARY; beside the executable (the build tree's
// tools/); ../lib/relief of an installed binary; the build tree's path for binaries elsewhere
// in it (the tests).
std::vector<fs::path> candidates() {
  std::vector<fs::path> paths;
  if (const char* env = std::getenv("RELIEF_IMAGE_LIBRARY"); env != nullptr && *env != '\0') {
    paths.emplace_back(env);
  }
  std::error_code error;
  const fs::path self = fs::read_symlink("/proc/self/exe", error);
  if (!error) {
    paths.push_back(self.parent_path() / "librelief_images.so");
    paths.push_back(self.parent_path() / RELIEF_IMAGE_LIBRARY_INSTALLED);
  }
  if (std::find(paths.begin(), paths.end(), fs::path(RELIEF_IMAGE_LIBRARY_BUILT)) == paths.end()) {
    paths.emplace_back(RELIEF_IMAGE_LIBRARY_BUILT);
  }
  return paths;
}

const ImageLibrary* load(std::string& error) {
  if (const std::optional<std::uintmax_t> left = address_space_remaining();
      left && *left < load_address_space()) {
    error = "the address-space limit (ulimit -v) leaves " + format_bytes(*left) +
            "; loading OpenImageIO needs about " + format_bytes(load_address_space()) +
            ". Raise ulimit -v";
    return nullptr;
  }
  std::string tried;
  for (const fs::path& path : candidates()) {
    std::error_code missing;
    if (!fs::is_regular_file(path, missing)) {
      tried += (tried.empty() ? "" : ", ") + path.string();
      continue;
    }
    // Never closed: the library's objects live as long as the process.
    void* const handle = ::dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (handle == nullptr) {
      const char* reason = ::dlerror();
      error = "cannot load " + path.string() + ": " + (reason ? reason : "no reason given");
      return nullptr;
    }
    void* const symbol = ::dlsym(handle, kImageLibrarySymbol);
    // A data object of that name would be called as code: only a function is taken.
    Dl_info info{};
    void* entry_symbol_raw = nullptr;
    if (symbol == nullptr || ::dladdr1(symbol, &info, &entry_symbol_raw, RTLD_DL_SYMENT) == 0 ||
        entry_symbol_raw == nullptr ||
        ELF64_ST_TYPE(static_cast<const ElfW(Sym)*>(entry_symbol_raw)->st_info) != STT_FUNC) {
      error = path.string() + " is not Relief's image library (no function " + kImageLibrarySymbol +
              ")";
      return nullptr;
    }
    const ImageLibrary* library = reinterpret_cast<ImageLibraryEntry>(symbol)();
    if (library == nullptr) {
      error = path.string() + " is not Relief's image library (its " + kImageLibrarySymbol +
              " returned nothing)";
    }
    return library;
  }
  error = "Relief's image library (OpenImageIO) is not installed: looked for " + tried;
  return nullptr;
}

}  // namespace

const ImageLibrary& image_library() {
  static std::mutex mutex;
  static const ImageLibrary* library = nullptr;
  const std::lock_guard<std::mutex> lock(mutex);
  if (library == nullptr) {
    std::string error;
    library = load(error);
    if (library == nullptr) {
      throw ImageLibraryError(error);
    }
  }
  return *library;
}

}  // namespace relief

namespace relief {

namespace {

// terrain.heightfield's EXR and TIFF files (pipeline/heightfield_files.h), through the module:
// the header first, the pixels only when asked.
bool read_height_field_image(const std::string& path, bool header_only, HeightFieldImage& image,
                             std::string& error) {
  std::unique_ptr<ImageReader> reader;
  try {
    reader = image_library().open(path, error);
  } catch (const ImageLibraryError& e) {
    error = e.what();
    return false;
  }
  if (!reader) {
    return false;
  }
  const ImageHeader& header = reader->header();
  if (header.deep || header.depth != 1) {
    error = "a deep or volume image";
    return false;
  }
  // The extension names the format: OpenImageIO would read any image behind it (a JPEG named
  // .exr, lossy), which the field's `file` does not allow.
  const bool exr = has_extension(path, ".exr");
  if (header.format != (exr ? "openexr" : "tiff")) {
    error = "its contents are " + header.format + ", not " + (exr ? "OpenEXR" : "TIFF");
    return false;
  }
  if (!header_only && (header.width != image.width || header.height != image.height ||
                       header.channels != image.channels)) {
    error = "it changed while it was read";  // refused before anything is allocated
    return false;
  }
  image.width = header.width;
  image.height = header.height;
  image.channels = header.channels;
  if (header_only) {
    return true;
  }
  image.values.resize(std::size_t(header.width) * std::size_t(header.height) *
                      std::size_t(header.channels));
  return reader->read(image.values.data(), error);
}

}  // namespace

void install_height_field_image_reader() {
  set_height_field_image_reader(&read_height_field_image);
}

}  // namespace relief
