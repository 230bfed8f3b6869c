// Uses Relief through its installed header alone: loads the default scene with small
// overrides, renders it, checks the image, checks that a bad override comes back as an Error,
// and encodes a PNG. Exits 0 when every check passes.
#include <relief/relief.h>

#include <algorithm>
#include <cstdio>
#include <iterator>
#include <string>
#include <vector>

// The C++20 the header needs came from relief::relief: this project sets no standard.
static_assert(__cplusplus >= 202002L, "relief::relief carries C++20");

namespace {

namespace api = relief::api;

int failures = 0;

void check(bool ok, const char* what) {
  if (!ok) {
    std::fprintf(stderr, "relief_consumer: FAILED: %s\n", what);
    ++failures;
  }
}

}  // namespace

int main() {
  const api::Result<api::Scene> scene = api::Scene::load(
      "", {"viewport.width=64", "viewport.height=48", "grid.width=32", "grid.height=32"});
  if (!scene) {
    std::fprintf(stderr, "relief_consumer: %s\n", scene.error().message.c_str());
    return 1;
  }
  check(scene->width() == 64 && scene->height() == 48, "the viewport is 64x48");

  const api::Result<api::Rendering> frame = api::render(*scene, {.threads = 2, .linear = true});
  if (!frame) {
    std::fprintf(stderr, "relief_consumer: %s\n", frame.error().message.c_str());
    return 1;
  }
  const api::Image& image = frame->image;
  check(image.width == 64 && image.height == 48, "the image is 64x48");
  check(image.srgb.size() == 64 * 48 * 3, "3 sRGB bytes a pixel");
  check(image.linear.size() == 64 * 48 * 3, "3 linear floats a pixel");
  check(image.depth.empty(), "no depth unless asked for");
  check(std::any_of(image.srgb.begin(), image.srgb.end(),
                    [&](unsigned char v) { return v != image.srgb.front(); }),
        "the image is not uniform");

  const api::Result<api::Scene> bad = api::Scene::load("", {"grid.width=1"});
  check(!bad, "grid.width=1 is refused");
  if (!bad) {
    check(bad.error().exit_code == api::kExitBadInput, "bad input has exit code 2");
    check(bad.error().message.find("grid.width") != std::string::npos,
          "the message names the field");
  }

  const api::Result<std::vector<unsigned char>> png = api::encode_png(image);
  const unsigned char signature[] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  check(png && png->size() > sizeof signature &&
            std::equal(std::begin(signature), std::end(signature), png->begin()),
        "encode_png gives a PNG");

  std::printf("relief %s: %dx%d image, %zu-byte PNG, %.1f ms, %d failure(s)\n",
              std::string(api::version()).c_str(), image.width, image.height, png ? png->size() : 0,
              frame->statistics.total_ms, failures);
  return failures == 0 ? 0 : 1;
}
