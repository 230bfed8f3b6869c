#include "tools/soup.h"

#include <charconv>
#include <cmath>
#include <sstream>
#include <utility>

#include "core/input_file.h"
#include "core/limits.h"
#include "core/scene/json_input.h"
#include "raster/raster_types.h"

namespace relief {

namespace {

std::string shortest(double v) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, v);
  return std::string(buffer, result.ptr);
}

// Splits a line into numbers; throws on anything that is not a finite number.
std::vector<double> numbers_of(const std::string& line, const std::string& where) {
  std::vector<double> values;
  std::istringstream words(line);
  std::string word;
  while (words >> word) {
    double v = 0;
    const auto [end, ec] = std::from_chars(word.data(), word.data() + word.size(), v);
    if (ec == std::errc::result_out_of_range && end == word.data() + word.size()) {
      throw SoupError(where + ": '" + brief_text(word) +
                      "' is out of the range of a double (it overflows or underflows)");
    }
    if (ec != std::errc() || end != word.data() + word.size() || !std::isfinite(v)) {
      throw SoupError(where + ": '" + brief_text(word) + "' is not a finite number");
    }
    values.push_back(v);
  }
  return values;
}

// Takes the soup one line at a time, so that a file is never held in memory whole.
class SoupParser {
 public:
  explicit SoupParser(std::string name) : name_(std::move(name)) {}
  void line(std::string text);
  TriangleSoup finish();

 private:
  void header(const std::vector<double>& v, const std::string& where);
  void triangle(const std::vector<double>& v, const std::string& where);

  std::string name_;
  TriangleSoup soup_;
  int line_number_ = 0;
  bool have_header_ = false;
  int first_triangle_line_ = 0;
};

void SoupParser::line(std::string text) {
  ++line_number_;
  const std::string where = name_ + ":" + std::to_string(line_number_);
  if (const std::size_t hash = text.find('#'); hash != std::string::npos) {
    text.erase(hash);
  }
  const std::vector<double> v = numbers_of(text, where);
  if (v.empty()) {
    return;
  }
  if (!have_header_) {
    header(v, where);
  } else {
    triangle(v, where);
  }
}

void SoupParser::header(const std::vector<double>& v, const std::string& where) {
  const int max_side = limits::kMaxViewportSide;
  if (v.size() != 2 || v[0] != std::floor(v[0]) || v[1] != std::floor(v[1]) || v[0] < 1 ||
      v[1] < 1 || v[0] > max_side || v[1] > max_side) {
    throw SoupError(where + ": the header must be 'W H', two integers from 1 to " +
                    std::to_string(max_side));
  }
  soup_.width = static_cast<int>(v[0]);
  soup_.height = static_cast<int>(v[1]);
  have_header_ = true;
}

void SoupParser::triangle(const std::vector<double>& v, const std::string& where) {
  if (v.size() != 9 && v.size() != 12) {
    throw SoupError(where +
                    ": a triangle is 9 numbers (window x y z per vertex) or 12 (clip x y "
                    "z w per vertex); found " +
                    std::to_string(v.size()));
  }
  const bool clip = v.size() == 12;
  if (first_triangle_line_ == 0) {
    first_triangle_line_ = line_number_;
    soup_.clip_coordinates = clip;
  } else if (clip != soup_.clip_coordinates) {
    throw SoupError(
        where + ": " + (clip ? "clip" : "window") + " coordinates, but the first triangle (line " +
        std::to_string(first_triangle_line_) + ") has " +
        (soup_.clip_coordinates ? "clip" : "window") + " coordinates; use one kind per file");
  }
  const int stride = clip ? 4 : 3;
  for (int k = 0; k < 3; ++k) {
    const double x = v[k * stride], y = v[k * stride + 1], z = v[k * stride + 2];
    const double w = clip ? v[k * stride + 3] : 1.0;
    if (!clip) {
      const double band = raster::kGuardBandPixels;
      if (std::abs(x) > band || std::abs(y) > band) {
        throw SoupError(where + ": vertex " + std::to_string(k) +
                        " lies outside the guard band; allowed |x|, |y| <= 2097152 px");
      }
      if (z < 0.0 || z > 1.0) {
        throw SoupError(where + ": vertex " + std::to_string(k) + " has depth z = " + shortest(z) +
                        "; allowed 0 <= z <= 1");
      }
    } else if (std::abs(x) > 1e30 || std::abs(y) > 1e30 || std::abs(z) > 1e30 ||
               std::abs(w) > 1e30) {
      throw SoupError(where + ": vertex " + std::to_string(k) +
                      " has a coordinate beyond 1e30; allowed |x|, |y|, |z|, |w| <= 1e30");
    }
    soup_.indices.push_back(static_cast<std::uint32_t>(soup_.x.size()));
    soup_.x.push_back(static_cast<float>(x));
    soup_.y.push_back(static_cast<float>(y));
    soup_.z.push_back(static_cast<float>(z));
    soup_.w.push_back(static_cast<float>(w));
  }
}

TriangleSoup SoupParser::finish() {
  if (!have_header_) {
    throw SoupError(name_ + ": empty; the first line must be the header 'W H'");
  }
  return std::move(soup_);
}

// The bytes of a soup, in pieces of any size, cut into lines for SoupParser: a UTF-8 byte
// order mark at the start is skipped, CRs are whitespace, a NUL byte and a line longer than
// limits::kMaxSoupLineBytes are errors. The file and the in-memory entry point share it, so
// the same bytes give the same soup or the same message.
class SoupText {
 public:
  explicit SoupText(const std::string& name) : name_(name), parser_(name) {}

  void feed(std::string_view bytes) {
    std::size_t k = 0;
    // A UTF-8 byte order mark, as some editors write, is not part of the text.
    if (at_start_ && bytes.substr(0, 3) == "\xef\xbb\xbf") {
      k = 3;
    }
    at_start_ = at_start_ && bytes.empty();
    for (; k < bytes.size(); ++k) {
      const char c = bytes[k];
      if (c == '\r') {
        continue;  // CRLF line ends (and stray CRs) are whitespace
      }
      if (c == '\n') {
        parser_.line(std::move(line_));
        line_.clear();
        ++line_number_;
      } else if (c == '\0') {
        throw SoupError(name_ + ":" + std::to_string(line_number_) +
                        ": a NUL byte; a soup is text");
      } else if (line_.size() < limits::kMaxSoupLineBytes) {
        line_ += c;
      } else {
        throw SoupError(name_ + ":" + std::to_string(line_number_) + ": longer than " +
                        std::to_string(limits::kMaxSoupLineBytes) + " bytes");
      }
    }
  }

  TriangleSoup finish() {
    if (!line_.empty()) {
      parser_.line(std::move(line_));
    }
    return parser_.finish();
  }

 private:
  std::string name_;
  SoupParser parser_;
  std::string line_;
  int line_number_ = 1;
  bool at_start_ = true;
};

}  // namespace

TriangleSoup parse_triangle_soup(std::string_view text, const std::string& name) {
  SoupText soup(brief_text(name));
  soup.feed(text);
  return soup.finish();
}

TriangleSoup read_triangle_soup(const std::string& path,
                                const std::function<void(std::uintmax_t)>& check_size) {
  const std::string name = brief_text(path);
  try {
    InputFile file(path, limits::kMaxSoupFileBytes);
    check_size(file.size());
    SoupText soup(name);
    char chunk[1 << 16];
    while (const std::size_t n = file.read(chunk, sizeof chunk)) {
      soup.feed(std::string_view(chunk, n));
    }
    return soup.finish();
  } catch (const InputFileError& e) {
    throw SoupError(name + ": " + e.what());
  }
}

}  // namespace relief
