// EXT_meshopt_compression (meshopt.hpp): the extension's JSON read with key paths in every
// message, then libmeshoptimizer's decoders and filters. libmeshoptimizer asserts on sizes it
// does not expect, so every stride, count and mode is checked here before a decoder sees it.
#include "gltf/meshopt.hpp"

#include <meshoptimizer.h>
#include <tiny_gltf.h>

#include <cstdint>
#include <limits>

#include "brdfcl/error.hpp"
#include "gltf/json_lookup.hpp"
#include "io/messages.hpp"

namespace brdfcl::gltf::detail {
namespace {

using json = nlohmann::json;

constexpr const char* kName = "EXT_meshopt_compression";

// No meshopt bitstream expands more than this: the attribute codec spends at least 2 bits per
// byte of 16 vertices (1/64 byte per decoded byte), the index codecs at least a byte per
// triangle or index. A view that claims more than 64x its compressed size is refused before
// anything is allocated.
constexpr std::uint64_t kMaxExpansion = 64;

std::string at(const char* kind, std::size_t i) { return std::string(kind) + "[" + std::to_string(i) + "]"; }

const json* extensionOf(const json& obj) {
  const json* ext = member(obj, "extensions");
  return ext ? member(*ext, kName) : nullptr;
}

std::uint64_t unsignedAt(const json& obj, const char* key, const std::string& path, const std::string& source,
                         bool required, std::uint64_t fallback = 0) {
  const json* v = member(obj, key);
  if (!v) {
    if (required) fail(source, path, std::string("missing \"") + key + "\"; re-export the file");
    return fallback;
  }
  if (!v->is_number_unsigned() && !(v->is_number_integer() && v->get<long long>() >= 0))
    fail(source, path + "." + key, "expected an integer >= 0, got " + brdfcl::detail::describeJson(*v));
  return v->get<std::uint64_t>();
}

std::string stringAt(const json& obj, const char* key, const std::string& path, const std::string& source,
                     const char* fallback, const char* expected) {
  const json* v = member(obj, key);
  if (!v) {
    if (!fallback) fail(source, path, std::string("missing \"") + key + "\"; re-export the file");
    return fallback;
  }
  const std::string s = v->is_string() ? v->get<std::string>() : "";
  if (!v->is_string()) fail(source, path + "." + key, std::string("expected ") + expected + ", got " + brdfcl::detail::describeJson(*v));
  return s;
}

}  // namespace

std::vector<bool> meshoptFallbacks(const json& doc, const std::string& source) {
  std::vector<bool> out;
  const json* buffers = member(doc, "buffers");
  if (!buffers || !buffers->is_array()) return out;
  for (std::size_t i = 0; i < buffers->size(); ++i) {
    const json* ext = extensionOf((*buffers)[i]);
    bool fallback = false;
    if (ext) {
      const std::string path = at("buffers", i) + ".extensions." + kName;
      if (!ext->is_object()) fail(source, path, "expected an object, got " + brdfcl::detail::describeJson(*ext));
      if (const json* f = member(*ext, "fallback")) {
        if (!f->is_boolean()) fail(source, path + ".fallback", "expected true or false, got " + brdfcl::detail::describeJson(*f));
        fallback = f->get<bool>();
      }
    }
    const json* uri = member((*buffers)[i], "uri");
    out.push_back(fallback && !(uri && uri->is_string()));
  }
  return out;
}

json withoutFallbackBuffers(const json& doc, const std::vector<bool>& fallbacks) {
  json out = doc;
  for (std::size_t i = 0; i < fallbacks.size(); ++i)
    if (fallbacks[i]) out["buffers"][i] = {{"byteLength", 1}, {"uri", "data:application/octet-stream;base64,AA=="}};
  return out;
}

void checkFallbackUse(const json& doc, const std::vector<bool>& fallbacks, const std::string& source) {
  const json* views = member(doc, "bufferViews");
  if (!views || !views->is_array()) return;
  // checkBuffers (loader.cpp) has made sure every view names an existing buffer.
  auto inFallback = [&](std::size_t v) {
    const json* b = v < views->size() ? member((*views)[v], "buffer") : nullptr;
    return b && b->is_number_unsigned() && b->get<std::uint64_t>() < fallbacks.size() &&
           fallbacks[std::size_t(b->get<std::uint64_t>())];
  };
  for (std::size_t i = 0; i < views->size(); ++i)
    if (inFallback(i) && !extensionOf((*views)[i]))
      fail(source, at("bufferViews", i), "buffers[" + member((*views)[i], "buffer")->dump() + "] is an " + kName +
                                             " fallback without data, but this view is not compressed; re-export the file");
  const json* images = member(doc, "images");
  if (!images || !images->is_array()) return;
  for (std::size_t i = 0; i < images->size(); ++i) {
    const json* v = member((*images)[i], "bufferView");
    if (v && v->is_number_unsigned() && inFallback(std::size_t(v->get<std::uint64_t>())))
      fail(source, at("images", i) + ".bufferView", "bufferViews[" + v->dump() + "] lies in an " + kName +
                                                        " fallback buffer, which has no data; brdfcl reads images from "
                                                        "uncompressed views only: re-export the file");
  }
}

void decodeMeshopt(const json& doc, tinygltf::Model& model, const std::vector<bool>& fallbacks, const std::string& source,
                   const LoadOptions& options) {
  const json* views = member(doc, "bufferViews");
  if (!views || !views->is_array()) return;
  auto isFallback = [&](std::uint64_t b) { return b < fallbacks.size() && fallbacks[std::size_t(b)]; };
  const std::size_t fileBuffers = model.buffers.size();  // decoded views are appended after these
  for (std::size_t i = 0; i < views->size() && i < model.bufferViews.size(); ++i) {
    const json& view = (*views)[i];
    const std::string self = at("bufferViews", i);
    const json* ext = extensionOf(view);
    tinygltf::BufferView& bv = model.bufferViews[i];
    if (!ext) continue;
    const std::string path = self + ".extensions." + kName;
    if (!ext->is_object()) fail(source, path, "expected an object, got " + brdfcl::detail::describeJson(*ext));
    const std::uint64_t buffer = unsignedAt(*ext, "buffer", path, source, true);
    const std::uint64_t offset = unsignedAt(*ext, "byteOffset", path, source, false, 0);
    const std::uint64_t length = unsignedAt(*ext, "byteLength", path, source, true);
    const std::uint64_t stride = unsignedAt(*ext, "byteStride", path, source, true);
    const std::uint64_t count = unsignedAt(*ext, "count", path, source, true);
    const std::string mode = stringAt(*ext, "mode", path, source, nullptr, "\"ATTRIBUTES\", \"TRIANGLES\" or \"INDICES\"");
    const std::string filter = stringAt(*ext, "filter", path, source, "NONE",
                                        "\"NONE\", \"OCTAHEDRAL\", \"QUATERNION\" or \"EXPONENTIAL\"");

    if (buffer >= fileBuffers)
      fail(source, path + ".buffer", "buffer " + std::to_string(buffer) + " does not exist (the file has " +
                                         std::to_string(fileBuffers) + "); re-export the file");
    if (isFallback(buffer))
      fail(source, path + ".buffer", "buffers[" + std::to_string(buffer) +
                                         "] is a fallback without data; the compressed data must be in a buffer that has it");
    const std::vector<unsigned char>& data = model.buffers[std::size_t(buffer)].data;
    if (length == 0) fail(source, path + ".byteLength", "expected at least 1, got 0; re-export the file");
    if (offset > data.size() || length > data.size() - offset)
      fail(source, path, "bytes " + std::to_string(offset) + " + " + std::to_string(length) + " lie outside buffers[" +
                             std::to_string(buffer) + "] of " + std::to_string(data.size()) + " bytes; re-export the file");

    if (mode == "ATTRIBUTES") {
      if (stride == 0 || stride > 256 || stride % 4 != 0)
        fail(source, path + ".byteStride", "expected a multiple of 4 from 4 to 256 for mode ATTRIBUTES, got " +
                                               std::to_string(stride) + "; re-export the file");
    } else if (mode == "TRIANGLES" || mode == "INDICES") {
      if (stride != 2 && stride != 4)
        fail(source, path + ".byteStride", "expected 2 or 4 for mode " + mode + ", got " + std::to_string(stride) +
                                               "; re-export the file");
      if (mode == "TRIANGLES" && count % 3 != 0)
        fail(source, path + ".count", "expected a multiple of 3 for mode TRIANGLES, got " + std::to_string(count) +
                                          "; re-export the file");
    } else {
      fail(source, path + ".mode", "expected \"ATTRIBUTES\", \"TRIANGLES\" or \"INDICES\", got " +
                                       brdfcl::detail::describeJson(*member(*ext, "mode")));
    }
    if (filter != "NONE") {
      if (filter != "OCTAHEDRAL" && filter != "QUATERNION" && filter != "EXPONENTIAL")
        fail(source, path + ".filter", "expected \"NONE\", \"OCTAHEDRAL\", \"QUATERNION\" or \"EXPONENTIAL\", got " +
                                           brdfcl::detail::describeJson(*member(*ext, "filter")));
      if (mode != "ATTRIBUTES")
        fail(source, path + ".filter", "filter " + filter + " needs mode ATTRIBUTES, not " + mode + "; re-export the file");
      const bool ok = filter == "OCTAHEDRAL" ? stride == 4 || stride == 8 : filter == "QUATERNION" ? stride == 8 : true;
      if (!ok)
        fail(source, path + ".byteStride", "expected " + std::string(filter == "OCTAHEDRAL" ? "4 or 8" : "8") +
                                               " for filter " + filter + ", got " + std::to_string(stride) + "; re-export the file");
    }
    if (count == 0) fail(source, path + ".count", "expected at least 1, got 0; re-export the file");
    if (count > options.maxElements)
      fail(source, path + ".count", std::to_string(count) + " is more than brdfcl's limit of " +
                                        std::to_string(options.maxElements) + "; re-export the file");
    // count <= maxElements (far below 2^56) and stride <= 256: the product cannot overflow.
    const std::uint64_t decodedSize = count * stride;
    if (decodedSize / kMaxExpansion > length)
      fail(source, path, std::to_string(count) + " elements of " + std::to_string(stride) + " bytes cannot come from " +
                             std::to_string(length) + " compressed bytes; the file is corrupt: re-export it");

    tinygltf::Buffer decoded;
    decoded.data.resize(std::size_t(decodedSize));
    const unsigned char* in = data.data() + offset;
    int rc = 0;
    if (mode == "ATTRIBUTES") rc = meshopt_decodeVertexBuffer(decoded.data.data(), count, stride, in, length);
    else if (mode == "TRIANGLES") rc = meshopt_decodeIndexBuffer(decoded.data.data(), count, stride, in, length);
    else rc = meshopt_decodeIndexSequence(decoded.data.data(), count, stride, in, length);
    if (rc != 0)
      fail(source, self, std::string(kName) + " data does not decode (meshopt error " + std::to_string(rc) +
                             "); re-export the file");
    if (filter == "OCTAHEDRAL") meshopt_decodeFilterOct(decoded.data.data(), count, stride);
    else if (filter == "QUATERNION") meshopt_decodeFilterQuat(decoded.data.data(), count, stride);
    else if (filter == "EXPONENTIAL") meshopt_decodeFilterExp(decoded.data.data(), count, stride);

    bv.buffer = int(model.buffers.size());
    bv.byteOffset = 0;
    bv.byteLength = decoded.data.size();
    model.buffers.push_back(std::move(decoded));
  }
}

}  // namespace brdfcl::gltf::detail
