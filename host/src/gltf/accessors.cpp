// Accessor decoding (accessors.hpp): bounds checks against buffer views and buffers, component
// conversion with the glTF normalization formulas, sparse substitution. Every failure is a
// one-line brdfcl::Error naming the accessor (or buffer view) and telling the user what to do.
#include "gltf/accessors.hpp"

#include <tiny_gltf.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>

#include "brdfcl/error.hpp"
#include "io/messages.hpp"

namespace brdfcl::gltf::detail {
namespace {

std::string at(const char* kind, std::size_t i) { return std::string(kind) + "[" + std::to_string(i) + "]"; }

[[noreturn]] void fail(const std::string& source, const std::string& where, const std::string& message) {
  throw Error(source + ": " + where + ": " + message);
}

int componentSize(int type) {
  switch (type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 2;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return 4;
    default: return 0;  // INT and DOUBLE are not glTF 2.0 accessor types
  }
}


std::string typeName(int components) {
  return components == 1 ? "SCALAR" : "VEC" + std::to_string(components);
}

// One component as a double (exact for every integer type), normalized per the glTF spec when asked.
double component(const unsigned char* p, int type, bool normalized) {
  switch (type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: {
      std::int8_t v;
      std::memcpy(&v, p, 1);
      return normalized ? std::max(v / 127.0, -1.0) : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return normalized ? p[0] / 255.0 : p[0];
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
      std::int16_t v;
      std::memcpy(&v, p, 2);
      return normalized ? std::max(v / 32767.0, -1.0) : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      std::uint16_t v;
      std::memcpy(&v, p, 2);
      return normalized ? v / 65535.0 : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
      std::uint32_t v;
      std::memcpy(&v, p, 4);
      return normalized ? v / 4294967295.0 : v;
    }
    default: {
      float v;
      std::memcpy(&v, p, 4);
      return v;
    }
  }
}

struct View {
  const unsigned char* data = nullptr;
  std::size_t length = 0;
  std::size_t stride = 0;  // 0 = tightly packed
  int index = -1;
};

// bufferViews[v], checked to lie inside its buffer.
View viewOf(const tinygltf::Model& m, int v, const std::string& source, const std::string& where) {
  if (v < 0 || std::size_t(v) >= m.bufferViews.size())
    fail(source, where, "bufferView " + std::to_string(v) + " does not exist (the file has " +
                            std::to_string(m.bufferViews.size()) + "); re-export the file");
  const tinygltf::BufferView& bv = m.bufferViews[std::size_t(v)];
  const std::string self = at("bufferViews", std::size_t(v));
  if (bv.buffer < 0 || std::size_t(bv.buffer) >= m.buffers.size())
    fail(source, self, "buffer " + std::to_string(bv.buffer) + " does not exist (the file has " +
                           std::to_string(m.buffers.size()) + "); re-export the file");
  const std::vector<unsigned char>& data = m.buffers[std::size_t(bv.buffer)].data;
  if (bv.byteOffset > data.size() || bv.byteLength > data.size() - bv.byteOffset)
    fail(source, self, "bytes " + std::to_string(bv.byteOffset) + " + " + std::to_string(bv.byteLength) +
                           " lie outside buffers[" + std::to_string(bv.buffer) + "] of " +
                           std::to_string(data.size()) + " bytes; re-export the file");
  return {data.data() + bv.byteOffset, bv.byteLength, bv.byteStride, v};
}

// Whether `count` elements of `size` bytes, `stride` apart from `offset`, fit in `length` bytes;
// written to avoid overflow for any 64-bit inputs.
bool fits(std::size_t offset, std::size_t count, std::size_t stride, std::size_t size, std::size_t length) {
  if (count == 0) return offset <= length;
  if (offset > length || size > length - offset) return false;
  return stride == 0 ? true : (count - 1) <= (length - offset - size) / stride;
}

void requireFit(const View& view, std::size_t offset, std::size_t count, std::size_t stride, std::size_t size,
                const std::string& source, const std::string& where) {
  if (!fits(offset, count, stride, size, view.length))
    fail(source, where, std::to_string(count) + " elements of " + std::to_string(size) + " bytes (stride " +
                            std::to_string(stride) + ") from byteOffset " + std::to_string(offset) +
                            " run past the end of bufferViews[" + std::to_string(view.index) + "] (" +
                            std::to_string(view.length) + " bytes); re-export the file");
}

// The accessor's elements as doubles, count * components of them, sparse values substituted.
template <class Emit>
void decode(const tinygltf::Model& m, std::size_t index, int components, const std::string& source,
            std::size_t maxCount, Emit&& emit) {
  const tinygltf::Accessor& a = m.accessors[index];
  const std::string where = at("accessors", index);
  const int csize = componentSize(a.componentType);
  const std::size_t esize = std::size_t(csize) * std::size_t(components);
  if (a.bufferView >= 0) {
    const View view = viewOf(m, a.bufferView, source, where);
    const std::size_t stride = view.stride ? view.stride : esize;
    if (stride < esize)
      fail(source, where, "bufferViews[" + std::to_string(view.index) + "].byteStride " + std::to_string(stride) +
                              " is smaller than one element (" + std::to_string(esize) + " bytes); re-export the file");
    requireFit(view, a.byteOffset, a.count, stride, esize, source, where);
    for (std::size_t i = 0; i < a.count; ++i) {
      const unsigned char* p = view.data + a.byteOffset + i * stride;
      for (int c = 0; c < components; ++c) emit(i, c, component(p + c * csize, a.componentType, a.normalized));
    }
  } else {
    // No bufferView: zeros (then sparse values); nothing in the file bounds the count.
    if (a.count > maxCount)
      fail(source, where, "count " + std::to_string(a.count) + " without a bufferView is more than brdfcl's limit of " +
                              std::to_string(maxCount) + "; re-export the file");
    for (std::size_t i = 0; i < a.count; ++i)
      for (int c = 0; c < components; ++c) emit(i, c, 0.0);
  }
  if (!a.sparse.isSparse) return;
  const std::string sw = where + ".sparse";
  const int n = a.sparse.count;
  if (n < 1 || std::size_t(n) > a.count)
    fail(source, sw + ".count", "expected 1 to " + std::to_string(a.count) + " (the accessor's count), got " +
                                    std::to_string(n) + "; re-export the file");
  const int itype = a.sparse.indices.componentType;
  if (itype != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && itype != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
      itype != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
    fail(source, sw + ".indices.componentType", "expected 5121, 5123 or 5125, got " + std::to_string(itype));
  if (a.sparse.indices.byteOffset < 0 || a.sparse.values.byteOffset < 0)
    fail(source, sw, "negative byteOffset; re-export the file");
  const View iv = viewOf(m, a.sparse.indices.bufferView, source, sw + ".indices");
  const View vv = viewOf(m, a.sparse.values.bufferView, source, sw + ".values");
  const std::size_t isize = std::size_t(componentSize(itype));
  requireFit(iv, std::size_t(a.sparse.indices.byteOffset), std::size_t(n), isize, isize, source, sw + ".indices");
  requireFit(vv, std::size_t(a.sparse.values.byteOffset), std::size_t(n), esize, esize, source, sw + ".values");
  for (std::size_t k = 0; k < std::size_t(n); ++k) {
    const double target = component(iv.data + a.sparse.indices.byteOffset + k * isize, itype, false);
    if (target >= double(a.count))
      fail(source, sw + ".indices", "index " + brdfcl::detail::formatNumber(target) + " is out of range (count " +
                                        std::to_string(a.count) + "); re-export the file");
    const unsigned char* p = vv.data + a.sparse.values.byteOffset + k * esize;
    for (int c = 0; c < components; ++c)
      emit(std::size_t(target), c, component(p + c * csize, a.componentType, a.normalized));
  }
}

// The checks common to both readers; returns the component count.
int checkHeader(const tinygltf::Model& m, int index, const std::string& use, const std::string& source) {
  if (index < 0 || std::size_t(index) >= m.accessors.size())
    fail(source, use, "accessor " + std::to_string(index) + " does not exist (the file has " +
                          std::to_string(m.accessors.size()) + "); re-export the file");
  const tinygltf::Accessor& a = m.accessors[std::size_t(index)];
  const std::string where = at("accessors", std::size_t(index));
  if (componentSize(a.componentType) == 0)
    fail(source, where + ".componentType", "unsupported component type " + std::to_string(a.componentType) +
                                               "; expected 5120, 5121, 5122, 5123, 5125 or 5126");
  return componentCount(a.type);
}

}  // namespace

Decoded readAccessor(const tinygltf::Model& m, int index, std::initializer_list<int> allowed, const std::string& use,
                     const std::string& source, std::size_t maxCount) {
  const int components = checkHeader(m, index, use, source);
  const tinygltf::Accessor& a = m.accessors[std::size_t(index)];
  const std::string where = at("accessors", std::size_t(index));
  if (std::find(allowed.begin(), allowed.end(), components) == allowed.end()) {
    std::string list;
    for (int k : allowed) list += (list.empty() ? "" : " or ") + typeName(k);
    fail(source, where + ".type", "the " + use + " accessor must be " + list + "; re-export the file");
  }
  Decoded d;
  d.components = components;
  d.count = a.count;
  bool resized = false;
  decode(m, std::size_t(index), components, source, maxCount, [&](std::size_t i, int c, double v) {
    if (!resized) {
      d.values.assign(a.count * std::size_t(components), 0.0f);  // only after the range checks passed
      resized = true;
    }
    if (!std::isfinite(v))
      fail(source, where, use + " element " + std::to_string(i) + " component " + std::to_string(c) + " is " +
                              brdfcl::detail::formatNumber(v) + "; the data is corrupt: re-export the file");
    d.values[i * std::size_t(components) + std::size_t(c)] = static_cast<float>(v);
  });
  return d;
}

std::vector<std::uint32_t> readIndices(const tinygltf::Model& m, int index, std::size_t vertexCount,
                                       const std::string& source, std::size_t maxCount) {
  const int components = checkHeader(m, index, "indices", source);
  const tinygltf::Accessor& a = m.accessors[std::size_t(index)];
  const std::string where = at("accessors", std::size_t(index));
  if (components != 1 || a.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT ||
      a.componentType == TINYGLTF_COMPONENT_TYPE_BYTE || a.componentType == TINYGLTF_COMPONENT_TYPE_SHORT)
    fail(source, where, "indices must be SCALAR of 5121, 5123 or 5125 (unsigned byte, short or int); re-export the file");
  std::vector<std::uint32_t> out;
  bool resized = false;
  decode(m, std::size_t(index), 1, source, maxCount, [&](std::size_t i, int, double v) {
    if (!resized) {
      out.assign(a.count, 0u);
      resized = true;
    }
    out[i] = static_cast<std::uint32_t>(v);
  });
  for (std::size_t i = 0; i < out.size(); ++i)
    if (out[i] >= vertexCount)
      fail(source, where, "index " + std::to_string(out[i]) + " at position " + std::to_string(i) +
                              " is out of range (the primitive has " + std::to_string(vertexCount) +
                              " vertices); re-export the file");
  return out;
}

// Vectors only (accessors.hpp): matrices have column padding rules that no attribute brdfcl reads needs.
int componentCount(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR: return 1;
    case TINYGLTF_TYPE_VEC2: return 2;
    case TINYGLTF_TYPE_VEC3: return 3;
    case TINYGLTF_TYPE_VEC4: return 4;
    default: return 0;
  }
}

}  // namespace brdfcl::gltf::detail
