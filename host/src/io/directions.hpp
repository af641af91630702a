// Unit directions from raw rows: the one arithmetic every reader of directions shares (the
// samples files, evaluateArrays), as a per-row function and as vectorized runs over whole blocks
// that give the same bits. A run reports how many rows it could not do; callers redo those rows.
#pragma once
#include <cstddef>
#include <cstdint>

namespace brdfcl::detail {

// Rows i in [0, n) read at src + i * stride (three components) are normalized into
// dx[i], dy[i], dz[i] (planes) or dst + 3 * i (interleaved). Returns the number of rows left
// undone (written with garbage): a non-finite component, zero length, or a length so large or
// so small that the row needs normalizeDirection's rescaling; 0 means every row is done.
std::size_t normalizeToPlanes(const float* src, std::size_t stride, std::size_t n, float* dx, float* dy, float* dz);
std::size_t normalizeToPlanes(const double* src, std::size_t stride, std::size_t n, float* dx, float* dy, float* dz);
std::size_t normalizeToRows(const float* src, std::size_t stride, std::size_t n, float* dst);
std::size_t normalizeToRows(const double* src, std::size_t stride, std::size_t n, float* dst);

// Material indices of rows i in [0, n) at src + i * stride: non-negative integers below
// `count` are stored in dst[i]; returns the number of rows that are not (left for the per-row
// check, which words the problem).
std::size_t materialIndices(const float* src, std::size_t stride, std::size_t n, std::size_t count, std::uint32_t* dst);
std::size_t materialIndices(const double* src, std::size_t stride, std::size_t n, std::size_t count,
                            std::uint32_t* dst);

}  // namespace brdfcl::detail
