// Readers and writers for the user's files: glTF material JSON, sample CSV/NPY, result CSV/NPY.
// Every reader throws brdfcl::Error with one line naming the file and the line, row or key.
#pragma once
#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "brdfcl/material.hpp"

namespace brdfcl {

// Materials of a glTF 2.0 document, or of any JSON object with a top-level "materials" array.
// Texture references are ignored with one warning per material, passed to `warn`.
std::vector<MaterialParams> readMaterials(const std::string& path,
                                          const std::function<void(const std::string&)>& warn = {});
std::vector<MaterialParams> parseMaterials(const std::string& jsonText, const std::string& sourceName,
                                           const std::function<void(const std::string&)>& warn = {});

// Samples in the shading frame N = +Z, T = +X, B = +Y. L points to the light, V to the viewer.
struct Samples {
  std::vector<std::uint32_t> material;  // empty when the file has no material column (grid mode)
  std::vector<float> L;                 // 3 per sample, normalized by the reader
  std::vector<float> V;                 // 3 per sample, normalized by the reader
  std::size_t size() const { return L.size() / 3; }
};

// CSV with header material,Lx,Ly,Lz,Vx,Vy,Vz (or Lx..Vz without material when
// materialColumnOptional and absent), or .npy float32/float64 of shape (N,7) or (N,6).
// Rejects short or non-numeric rows, NaN/Inf, zero-length directions and, when materialCount
// is given, material indices out of range.
Samples readSamples(const std::string& path, std::size_t materialCount, bool materialColumnOptional);

// Writes N rows of r,g,b: CSV with header and 9 significant digits, or float32 .npy (N,3),
// chosen by extension. Writes a temporary file beside `path`, then renames it into place.
void writeResults(const std::string& path, const std::vector<float>& rgb);

// Runs `write` on a temporary path beside `path` and renames it into place on success; on any
// exception the temporary is removed and the exception propagates. No half-written outputs.
void writeAtomically(const std::string& path, const std::function<void(const std::string& tmpPath)>& write);

}  // namespace brdfcl
