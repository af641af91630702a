// Files of `brdfcl sample`: the views it samples at (CSV or NPY, with or without the caller's
// uniforms) and the tables it and `brdfcl pdf` write (named float columns as CSV or NPY).
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace brdfcl {

// Views in the shading frame (N = +Z), normalized by the samples readers' arithmetic, with one
// material index a row (empty without a material column: material 0) and, when the file has
// them, the uniforms u1 u2 u3 (3 a row, each in [0, 1); empty otherwise).
struct SampleViews {
  std::vector<std::uint32_t> material;
  std::vector<float> V, u;
  std::size_t size() const { return V.size() / 3; }
};

// CSV whose header names material,Vx,Vy,Vz,u1,u2,u3 in any order (material optional, the three
// u's all or none), or .npy float32/float64 (N,7) / (N,4) in that order ((N,6) / (N,3) without
// material), "-" for stdin (NPY by its magic). Errors name the file and line ("v.csv:3: field
// 'u2' must be in [0, 1), got 1") or row ("v.npy: row 2: ..."), as the samples readers word them.
SampleViews readSampleViews(const std::string& path, std::size_t materialCount);

// `values` as rows of columns.size() floats: CSV with the names as header and %.9g numbers, or
// float32 NPY (N, columns) by the extension, through the atomic output layer (io.hpp).
void writeTable(const std::string& path, const std::vector<std::string>& columns, const std::vector<float>& values);

}  // namespace brdfcl
