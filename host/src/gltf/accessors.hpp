// Accessor decoding for the glTF loader: every component type, normalized integers, byteStride
// and sparse substitution, with every offset and length checked against the buffer before any
// allocation, so that a small file cannot claim gigabytes.
#pragma once
#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <string>
#include <vector>

namespace tinygltf {
class Model;
}

namespace brdfcl::gltf::detail {

// What a decoded accessor holds: count elements of `components` floats each, row after row.
struct Decoded {
  std::vector<float> values;
  int components = 0;
  std::size_t count = 0;
};

// Reads accessors[index] as floats (normalized integers per the glTF spec, others converted as
// they are). `allowed` lists the accepted component counts (e.g. {3} for POSITION, {3, 4} for
// COLOR_0); `use` names the attribute for messages. An accessor without a bufferView (zeros,
// possibly with sparse values) may have at most `maxCount` elements. Non-finite values are errors.
// Messages are "<source>: accessors[i]: ...".
Decoded readAccessor(const tinygltf::Model& model, int index, std::initializer_list<int> allowed, const std::string& use,
                     const std::string& source, std::size_t maxCount);

// Reads an index accessor (SCALAR of UNSIGNED_BYTE/SHORT/INT, not normalized); each index must be
// below vertexCount.
std::vector<std::uint32_t> readIndices(const tinygltf::Model& model, int index, std::size_t vertexCount,
                                       const std::string& source, std::size_t maxCount);

// Components of a glTF accessor type: 1 to 4 for SCALAR to VEC4, 0 for the matrix types.
int componentCount(int type);

}  // namespace brdfcl::gltf::detail
