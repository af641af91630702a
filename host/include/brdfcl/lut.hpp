// Look-up tables for engines: the sheen albedo E, the split-sum GGX DFG terms and the Charlie
// sheen DFG, baked on the device on a uniform grid (x = N.V, y = perceptual roughness), and their
// writers (.exr FLOAT channels, .csv, C header, float32 .npy).
#pragma once
#include <cstddef>
#include <string>
#include <vector>

#include "brdfcl/material.hpp"
#include "brdfcl/runtime.hpp"

namespace brdfcl {

// SheenE: E(mu, r) of the white sheen lobe of the options' D and V (1 channel).
// GgxDfg: A, B with F0 A + B = directional albedo of the GGX lobe with Schlick F, f90 = 1 (2 channels).
// CharlieDfg: directional albedo of the white Charlie lobe (Charlie D, Charlie V; 1 channel).
enum class LutKind { SheenE, GgxDfg, CharlieDfg };

LutKind parseLutKind(const std::string& s);  // "sheen-e" | "ggx-dfg" | "charlie-dfg", else Error
const char* toString(LutKind k);

struct Lut {
  LutKind kind;
  std::size_t size;  // size x size texels
  int channels;
  SheenDistribution distribution = SheenDistribution::Charlie;  // the lobe baked (sheen-e, charlie-dfg)
  SheenVisibility visibility = SheenVisibility::Charlie;
  // size * size * channels: row y (roughness) major, x (N.V) fastest, channels interleaved.
  // Texel (i, j) holds N.V = max(i / (size - 1), 1e-4), roughness = j / (size - 1).
  std::vector<float> values;
  float at(std::size_t i, std::size_t j, int c = 0) const { return values[(j * size + i) * channels + c]; }
};

constexpr std::size_t kMinLutSize = 2, kMaxLutSize = 4096;

// Throws brdfcl::Error for a size outside [2, 4096]. nodesPerPanel sets the quadrature order
// (tests double it to show convergence).
Lut bakeLut(Runtime& rt, LutKind kind, std::size_t size, const EvalOptions& o = {}, int nodesPerPanel = 12);

// By extension (any case): .exr (FLOAT channels R[, G], scanline j = roughness row j), .csv
// (header nv,roughness,<channels>, %.9g), .h (C array + #defines), .npy (float32, shape
// (size, size) or (size, size, channels): lut[j, i] is the texel at N.V = i/(size-1),
// roughness = j/(size-1), as in the EXR and CSV). "-" (and an extensionless FIFO or device)
// gets CSV. Other extensions: Error. Written by the output rules of io.hpp (atomic for files).
void writeLut(const Lut& lut, const std::string& path);

// The extension check of writeLut alone, so the CLI can reject a bad --out before a long bake.
void checkLutPath(const std::string& path);

// Channel names: "E" (sheen-e, charlie-dfg) or "A", "B" (ggx-dfg).
std::vector<std::string> lutChannelNames(LutKind k);

}  // namespace brdfcl
