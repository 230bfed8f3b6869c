// The awkward ranges every Highway kernel is tried on (tests/simd/*_ranges_test.cc), and the
// sentinel that shows which elements a kernel wrote. A kernel works a whole vector at a time and
// handles the rest of its range as a tail: every length from 0 to 33 is 0, 1, N - 1, N and
// N + 1 for every lane count N up to 32 (AVX3: 16 floats, 8 doubles), and 3 * 16 + 5 = 53 is
// several whole vectors and a tail on every target. Each range is also tried starting one and
// five elements into its buffer, so that no load or store of the kernel is aligned.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <span>
#include <string>
#include <type_traits>
#include <vector>

namespace relief::test {

inline std::vector<std::size_t> awkward_lengths() {
  std::vector<std::size_t> lengths;
  for (std::size_t n = 0; n <= 33; ++n) {
    lengths.push_back(n);
  }
  lengths.push_back(3 * 16 + 5);
  return lengths;
}

// Where a range starts in its buffer.
inline constexpr std::size_t kRangeStarts[] = {0, 1, 5};

// Elements after a range's end that must keep the sentinel: a whole AVX3 vector of floats, so a
// store of one vector too many lands on them.
inline constexpr std::size_t kGuardElements = 16;

// Quiet NaNs with a payload no arithmetic produces (it yields the default NaN, payload 0), and
// byte patterns for the integer outputs: an element still holding one was not written.
template <class T>
T sentinel() {
  if constexpr (std::is_same_v<T, float>) {
    constexpr std::uint32_t kBits = 0x7fc5a5a5u;
    float value;
    std::memcpy(&value, &kBits, sizeof value);
    return value;
  } else if constexpr (std::is_same_v<T, double>) {
    constexpr std::uint64_t kBits = 0x7ff8a5a5a5a5a5a5u;
    double value;
    std::memcpy(&value, &kBits, sizeof value);
    return value;
  } else {
    static_assert(std::is_integral_v<T>);
    T value;
    std::memset(&value, 0xa5, sizeof value);
    return value;
  }
}

// Bit for bit, NaN payloads and signed zeros included.
template <class T>
bool same_bits(std::span<const T> a, std::span<const T> b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0;
}

template <class T>
bool same_bits(const std::vector<T>& a, const std::vector<T>& b) {
  return same_bits(std::span<const T>(a), std::span<const T>(b));
}

// Whether every element of `buffer` outside [begin, end) still holds the sentinel.
template <class T>
bool untouched_outside(std::span<const T> buffer, std::size_t begin, std::size_t end) {
  const T expected = sentinel<T>();
  for (std::size_t k = 0; k < buffer.size(); ++k) {
    if ((k < begin || k >= end) && std::memcmp(&buffer[k], &expected, sizeof(T)) != 0) {
      return false;
    }
  }
  return true;
}

template <class T>
bool untouched_outside(const std::vector<T>& buffer, std::size_t begin, std::size_t end) {
  return untouched_outside(std::span<const T>(buffer), begin, end);
}

// A buffer for a range of `length` elements from `start`, with kGuardElements after it, all
// holding the sentinel.
template <class T>
std::vector<T> sentinel_buffer(std::size_t start, std::size_t length) {
  return std::vector<T>(start + length + kGuardElements, sentinel<T>());
}

}  // namespace relief::test
