// Sample files for the streaming tests (test_stream.cpp, test_stream_cli.cpp): random rows and
// their CSV and NPY bytes (NPY in any dtype and order).
#pragma once
#include <cstdint>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "npy.hpp"
#include "support.hpp"

namespace brdfcl::test {

// The file: values given row-major, stored float32 or float64, C or Fortran order.
inline std::string npyFile(const std::vector<double>& values, std::size_t cols, bool float32, bool fortran) {
  const std::size_t rows = values.size() / cols;
  std::string out = npyHeader(rows, cols, float32, fortran);
  for (std::size_t k = 0; k < values.size(); ++k) {
    const std::size_t i = fortran ? k % rows : k / cols, j = fortran ? k / rows : k % cols;
    const double v = values[i * cols + j];
    if (float32) {
      const float f = static_cast<float>(v);
      out.append(reinterpret_cast<const char*>(&f), 4);
    } else {
      out.append(reinterpret_cast<const char*>(&v), 8);
    }
  }
  return out;
}

// Row-major material, L, V (or L, V) values of random samples; directions are not unit length,
// so the readers' normalization is exercised too.
inline std::vector<double> randomRows(std::size_t n, bool withMaterial, std::uint32_t materials, std::uint64_t salt) {
  std::mt19937_64 rng(seed() + salt);
  std::uniform_real_distribution<double> u(-2.0, 2.0);
  std::uniform_int_distribution<std::uint32_t> pick(0, materials - 1);
  std::vector<double> v;
  for (std::size_t i = 0; i < n; ++i) {
    if (withMaterial) v.push_back(pick(rng));
    for (int k = 0; k < 6; ++k) v.push_back(u(rng));
    v.back() += 2.5;  // mostly above the horizon
  }
  return v;
}

// The file as CSV: a header, then the rows with 17 significant digits, ended by `eol`.
inline std::string csvFile(const std::vector<double>& values, bool withMaterial, const std::string& eol = "\n",
                           bool terminateLast = true) {
  std::ostringstream o;
  o.precision(17);
  o << (withMaterial ? "material,Lx,Ly,Lz,Vx,Vy,Vz" : "Lx,Ly,Lz,Vx,Vy,Vz") << eol;
  const std::size_t cols = withMaterial ? 7 : 6;
  for (std::size_t i = 0; i < values.size(); i += cols) {
    for (std::size_t k = 0; k < cols; ++k) o << (k ? "," : "") << values[i + k];
    if (i + cols < values.size() || terminateLast) o << eol;
  }
  return o.str();
}

}  // namespace brdfcl::test
