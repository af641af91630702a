// Rec. 709 / sRGB relative luminance of linear RGB, the one formula behind `brdfcl diff`,
// `brdfcl compare`'s albedo and ratio maps, and the exact IBL's environment sampling weights.
#pragma once

namespace brdfcl {

// 0.2126 R + 0.7152 G + 0.0722 B, summed in double.
inline double luminance709(float r, float g, float b) { return 0.2126 * r + 0.7152 * g + 0.0722 * b; }

}  // namespace brdfcl
