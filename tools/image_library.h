// OpenImageIO behind a door that opens only when a command needs it. Linked into the relief
// binary, OpenImageIO and the 250 libraries it pulls in (OpenCV, OpenVDB, log4cplus, ...) were
// loaded and initialised on every start, 0.3 to 0.5 s before main, and their static
// initialisers died of a signal under an address-space limit (ulimit -v) between about 387 and
// 449 MB, before any message could be printed. Now the module librelief_images.so (oiio_library.cc)
// holds every OpenImageIO call and is loaded with dlopen by the first command that reads an
// image file or writes EXR; a render to PNG never loads it, and neither does comparing images in
// memory (image_compare.h computes idiff's figures itself), so relief crosscheck runs on a
// machine without OpenImageIO. relief compare loads it to read its two files.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "image/png_text.h"

namespace relief {

// The module could not be loaded (not found, not loadable, or too little address space left
// for it); the message says which and what to do.
class ImageLibraryError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// An image file's header as OpenImageIO reads it (the first subimage).
struct ImageHeader {
  int width = 0, height = 0, depth = 1, channels = 0;
  bool deep = false;
  std::string format;  // OpenImageIO's name: "png", "openexr", "pnm"
  std::vector<std::string> channel_names;
};

class ImageReader {
 public:
  virtual ~ImageReader() = default;
  virtual const ImageHeader& header() const = 0;
  // A string attribute of the header (a PNG text chunk, an EXR attribute); nullopt if none.
  virtual std::optional<std::string> text(const std::string& key) const = 0;
  // Every channel of every pixel as floats, top row first, into `pixels` (width * height *
  // channels); false with `error` set when the file cannot be read.
  virtual bool read(float* pixels, std::string& error) = 0;
};

class ImageLibrary {
 public:
  virtual ~ImageLibrary() = default;
  // Null with `error` set when OpenImageIO cannot open the file as an image.
  virtual std::unique_ptr<ImageReader> open(const std::string& path, std::string& error) const = 0;
  // An EXR file's bytes (float_image_file.h); empty with `error` set on failure.
  virtual std::vector<unsigned char> encode_exr(int width, int height, int channels,
                                                std::span<const float> values, std::size_t stride,
                                                std::span<const ImageText> metadata,
                                                std::string& error) const = 0;
};

// The module's one entry point (extern "C", found with dlsym).
inline constexpr const char* kImageLibrarySymbol = "relief_image_library";
using ImageLibraryEntry = const ImageLibrary* (*)();

// The loaded module, loaded on first use (thread-safe) and never unloaded. Looked for at
// $RELIEF_IMAGE_LIBRARY, beside the executable, in ../lib/relief of an installed binary, and in
// the build tree. Throws ImageLibraryError.
const ImageLibrary& image_library();

// Lets terrain.heightfield read EXR and TIFF files through the module (pipeline's
// set_height_field_image_reader): run_cli installs it; the library reads none by itself.
void install_height_field_image_reader();

}  // namespace relief
