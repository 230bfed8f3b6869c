#include "gpu/param_codegen_text.h"

#include <algorithm>
#include <cctype>
#include <stdexcept>

namespace relief::param_codegen {

bool is_word(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '_';
}

bool all_digits(const std::string& s) {
  return !s.empty() && std::all_of(s.begin(), s.end(), [](char c) {
    return std::isdigit(static_cast<unsigned char>(c)) != 0;
  });
}

std::string trimmed(const std::string& s) {
  const auto space = [](char c) { return std::isspace(static_cast<unsigned char>(c)) != 0; };
  std::size_t begin = 0, end = s.size();
  while (begin < end && space(s[begin])) {
    ++begin;
  }
  while (end > begin && space(s[end - 1])) {
    --end;
  }
  return s.substr(begin, end - begin);
}

std::size_t decimal_literal_length(const std::string& s, std::size_t at) {
  const auto digits = [&](std::size_t k) {
    std::size_t n = 0;
    while (k + n < s.size() && std::isdigit(static_cast<unsigned char>(s[k + n])) != 0) {
      ++n;
    }
    return n;
  };
  std::size_t k = at;
  if (k < s.size() && s[k] == '-') {
    ++k;
  }
  const std::size_t whole = digits(k);
  if (whole == 0 || k + whole >= s.size() || s[k + whole] != '.') {
    return 0;
  }
  k += whole + 1;
  k += digits(k);
  if (k < s.size() && (s[k] == 'e' || s[k] == 'E')) {
    std::size_t e = k + 1;
    if (e < s.size() && (s[e] == '+' || s[e] == '-')) {
      ++e;
    }
    const std::size_t exponent = digits(e);
    if (exponent > 0) {
      k = e + exponent;
    }
  }
  return k - at;
}

std::string in_precision(const std::string& text, const std::string& type) {
  if (type != "float" && type != "double") {
    throw std::runtime_error("@real " + type + "@: the precision is float or double");
  }
  // REAL(literal) first, then the other words REAL.
  std::string out;
  for (std::size_t k = 0; k < text.size();) {
    const bool word = text.compare(k, 4, "REAL") == 0 && (k == 0 || !is_word(text[k - 1])) &&
                      (k + 4 == text.size() || !is_word(text[k + 4]));
    if (!word) {
      out += text[k++];
      continue;
    }
    if (k + 4 < text.size() && text[k + 4] == '(') {
      const std::size_t length = decimal_literal_length(text, k + 5);
      if (length > 0 && k + 5 + length < text.size() && text[k + 5 + length] == ')') {
        out += text.substr(k + 5, length) + (type == "double" ? "LF" : "");
        k += 6 + length;
        continue;
      }
    }
    out += type;
    k += 4;
  }
  return out;
}

bool parse_directive(const std::string& line, std::string& kind, std::string& argument,
                     std::string& tail) {
  std::size_t k = 0;
  while (k < line.size() && std::isspace(static_cast<unsigned char>(line[k])) != 0) {
    ++k;
  }
  if (k == line.size() || line[k] != '@') {
    return false;
  }
  const std::size_t kind_begin = ++k;
  while (k < line.size() && is_word(line[k])) {
    ++k;
  }
  if (k == kind_begin || k == line.size() || line[k] != ' ') {
    return false;
  }
  const std::size_t end = line.find('@', k + 1);
  if (end == std::string::npos || line.find_first_of("\r\n", end) != std::string::npos) {
    return false;
  }
  kind = line.substr(kind_begin, k - kind_begin);
  argument = line.substr(k + 1, end - k - 1);
  tail = line.substr(end + 1);
  return true;
}

}  // namespace relief::param_codegen
