// The text forms gpu/param_codegen.cc reads, parsed by hand: std::regex draws false
// maybe-uninitialized warnings from GCC 12 under the sanitizers (and is slow).
#pragma once

#include <cstddef>
#include <string>

namespace relief::param_codegen {

// [A-Za-z0-9_].
bool is_word(char c);
// One or more decimal digits and nothing else.
bool all_digits(const std::string& s);
// `s` without leading and trailing white space.
std::string trimmed(const std::string& s);
// The length of a decimal literal -?D+.D*([eE][-+]?D+)? at `at`, 0 when there is none.
std::size_t decimal_literal_length(const std::string& s, std::size_t at);
// det_math's text in one precision (the @real directive): REAL(literal) becomes the literal
// (with LF in double), then every other word REAL the type ("float" or "double").
std::string in_precision(const std::string& text, const std::string& type);
// A template line "@kind argument@tail" (leading white space allowed, kind a word, one space
// before the argument, which runs to the next @); false for any other line.
bool parse_directive(const std::string& line, std::string& kind, std::string& argument,
                     std::string& tail);

}  // namespace relief::param_codegen
