// NPY v1.0 files written by hand for the tests, independently of brdfcl's own writer and reader:
// numpy's magic and version, then the header dict padded with spaces to a multiple of 64 bytes.
#pragma once
#include <cstddef>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

namespace brdfcl::test {

// Seeded random results to write as (N, 3) NPY rows, in [0, 4).
inline std::vector<float> randomRgb(std::size_t rows, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 4.0f);
  std::vector<float> rgb(3 * rows);
  for (auto& v : rgb) v = u(rng);
  return rgb;
}

// The magic, version, header length and `dict` padded as numpy pads it; the dict may be malformed.
inline std::string npyWithDict(std::string dict) {
  dict.append(63 - (10 + dict.size()) % 64, ' ');
  dict += '\n';
  std::string out("\x93NUMPY\x01\x00", 8);
  out += static_cast<char>(dict.size() & 0xff);
  out += static_cast<char>(dict.size() >> 8);
  return out + dict;
}

// The header of a float32 or float64 (rows, cols) array in C or Fortran order.
inline std::string npyHeader(std::size_t rows, std::size_t cols, bool float32 = true, bool fortran = false) {
  return npyWithDict(std::string("{'descr': '") + (float32 ? "<f4" : "<f8") + "', 'fortran_order': " +
                     (fortran ? "True" : "False") + ", 'shape': (" + std::to_string(rows) + ", " +
                     std::to_string(cols) + "), }");
}

// A whole C-order file of `values` (row-major, `cols` a row) stored as float32 or float64.
inline std::string npyArray(const std::vector<double>& values, std::size_t cols, bool float32) {
  std::string out = npyHeader(values.size() / cols, cols, float32);
  for (double v : values) {
    if (float32) {
      const float f = static_cast<float>(v);
      out.append(reinterpret_cast<const char*>(&f), sizeof f);
    } else {
      out.append(reinterpret_cast<const char*>(&v), sizeof v);
    }
  }
  return out;
}

}  // namespace brdfcl::test
