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
// KHR_materials_sheen is the draft when it has intensityFactor, colorFactor or
// colorIntensityTexture, the ratified extension otherwise; mixing the two key families is an
// error. Values are checked against the glTF schema ranges; errors name the file and the JSON
// path ("m.json: materials[2].pbrMetallicRoughness.roughnessFactor: ..."). Texture references
// are ignored with one warning per material, passed to `warn` (if set). Unknown extensions are
// ignored silently.
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
// materialColumnOptional and absent), or .npy float32/float64 of shape (N,7) or (N,6), chosen
// by the extension (.npy, any case). Rejects short or non-numeric rows, NaN/Inf, zero-length
// directions, non-integer material indices and, when materialCount != 0, indices >= it.
// Errors say "s.csv:17: ..." (1-based file lines, the header is line 1) or "s.npy: row 12: ..."
// (0-based rows, as numpy indexes them). Large files are parsed on several threads.
Samples readSamples(const std::string& path, std::size_t materialCount, bool materialColumnOptional);

// Writes N rows of r,g,b: CSV with header and 9 significant digits (%.9g), or float32 .npy
// (N,3) v1.0, chosen by extension. Writes a temporary file beside `path`, then renames it into
// place. rgb.size() must be a multiple of 3 (std::invalid_argument otherwise: a caller bug).
void writeResults(const std::string& path, const std::vector<float>& rgb);

// Runs `write` on a temporary path beside `path` (".<name>.tmp.<pid>.<n>", already created
// empty) and renames it into place on success; on any exception the temporary is removed and
// the exception propagates. No half-written outputs. A missing or unwritable directory fails
// before `write` runs: "cannot write 'out/x.csv': No such file or directory".
void writeAtomically(const std::string& path, const std::function<void(const std::string& tmpPath)>& write);

}  // namespace brdfcl
