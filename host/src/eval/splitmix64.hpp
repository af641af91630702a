// SplitMix64 (Steele, Lea and Flood, "Fast Splittable Pseudorandom Number Generators", OOPSLA
// 2014): a counter hashed to 64 random bits, the same sequence on every platform and standard
// library, which std:: distributions do not promise. Used where generated inputs must repeat.
#pragma once
#include <cstdint>

namespace brdfcl::detail {

struct SplitMix64 {
  std::uint64_t state;
  std::uint64_t next() {
    std::uint64_t z = (state += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
  }
  float uniformFloat() { return float(next() >> 40) * (1.0f / 16777216.0f); }  // [0, 1), 24 bits
  double uniformDouble() { return double(next() >> 11) * 0x1.0p-53; }          // [0, 1), 53 bits
};

}  // namespace brdfcl::detail
