// KHR_draco_mesh_compression (draco.hpp): draco::Decoder on the primitive's buffer view, then the
// Draco mesh's faces and mapped attribute values copied out with every index checked, since a
// corrupt stream can decode to a mesh whose maps point outside its own attribute buffers.
#include "gltf/draco.hpp"

#include <draco/compression/decode.h>
#include <draco/mesh/mesh.h>
#include <tiny_gltf.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <memory>
#include <utility>

#include "brdfcl/error.hpp"
#include "gltf/accessors.hpp"
#include "gltf/json_lookup.hpp"
#include "io/messages.hpp"

namespace brdfcl::gltf::detail {
namespace {

using json = nlohmann::json;

constexpr const char* kName = "KHR_draco_mesh_compression";

// One Draco component as a double; false for data types glTF has no use for.
bool component(const std::uint8_t* p, draco::DataType t, double& out) {
  switch (t) {
    case draco::DT_INT8: { std::int8_t v; std::memcpy(&v, p, 1); out = v; return true; }
    case draco::DT_UINT8: out = p[0]; return true;
    case draco::DT_INT16: { std::int16_t v; std::memcpy(&v, p, 2); out = v; return true; }
    case draco::DT_UINT16: { std::uint16_t v; std::memcpy(&v, p, 2); out = v; return true; }
    case draco::DT_INT32: { std::int32_t v; std::memcpy(&v, p, 4); out = v; return true; }
    case draco::DT_UINT32: { std::uint32_t v; std::memcpy(&v, p, 4); out = v; return true; }
    case draco::DT_FLOAT32: { float v; std::memcpy(&v, p, 4); out = v; return true; }
    default: return false;
  }
}

// The glTF formula for a normalized integer of the accessor's componentType.
double normalize(double v, int componentType) {
  switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: return std::max(v / 127.0, -1.0);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return v / 255.0;
    case TINYGLTF_COMPONENT_TYPE_SHORT: return std::max(v / 32767.0, -1.0);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return v / 65535.0;
    default: return v;
  }
}

// Appends `bytes` as a new buffer and a view over it; returns the view's index.
int addView(tinygltf::Model& model, std::vector<unsigned char> bytes) {
  tinygltf::BufferView view;
  view.buffer = int(model.buffers.size());
  view.byteOffset = 0;
  view.byteLength = bytes.size();
  tinygltf::Buffer buffer;
  buffer.data = std::move(bytes);
  model.buffers.push_back(std::move(buffer));
  model.bufferViews.push_back(view);
  return int(model.bufferViews.size()) - 1;
}

// The bytes of the extension's buffer view, after the extension's own fields are checked;
// `attrs` receives its attribute ids.
std::pair<const unsigned char*, std::size_t> compressedBytes(const json& ext, const tinygltf::Model& model,
                                                             const std::string& source, const std::string& path,
                                                             const json*& attrs) {
  if (!ext.is_object()) fail(source, path, "expected an object, got " + brdfcl::detail::describeJson(ext));
  const json* v = member(ext, "bufferView");
  if (!v) fail(source, path, "missing \"bufferView\"; re-export the file");
  if (!v->is_number_integer() || v->get<long long>() < 0 || std::size_t(v->get<long long>()) >= model.bufferViews.size())
    fail(source, path + ".bufferView", "bufferView " + brdfcl::detail::describeJson(*v) + " does not exist (the file has " +
                                           std::to_string(model.bufferViews.size()) + "); re-export the file");
  attrs = member(ext, "attributes");
  if (!attrs || !attrs->is_object())
    fail(source, path + ".attributes", "expected an object of attribute ids, got " +
                                           (attrs ? brdfcl::detail::describeJson(*attrs) : std::string("nothing")));
  const tinygltf::BufferView& bv = model.bufferViews[std::size_t(v->get<long long>())];
  if (bv.buffer < 0 || std::size_t(bv.buffer) >= model.buffers.size())
    fail(source, path + ".bufferView", "its buffer does not exist; re-export the file");
  const std::vector<unsigned char>& data = model.buffers[std::size_t(bv.buffer)].data;
  if (bv.byteOffset > data.size() || bv.byteLength > data.size() - bv.byteOffset)
    fail(source, path + ".bufferView", "bytes " + std::to_string(bv.byteOffset) + " + " + std::to_string(bv.byteLength) +
                                           " lie outside buffers[" + std::to_string(bv.buffer) + "] of " +
                                           std::to_string(data.size()) + " bytes; re-export the file");
  return {data.data() + bv.byteOffset, bv.byteLength};
}

// The Draco mesh in `bytes`, within brdfcl's limit on points and triangles.
std::unique_ptr<draco::Mesh> decodeMesh(std::pair<const unsigned char*, std::size_t> bytes, const std::string& source,
                                        const std::string& prim, const LoadOptions& options) {
  draco::DecoderBuffer in;
  in.Init(reinterpret_cast<const char*>(bytes.first), bytes.second);
  draco::Decoder decoder;
  auto decoded = decoder.DecodeMeshFromBuffer(&in);
  if (!decoded.ok() || !decoded.value())
    fail(source, prim, std::string(kName) + " data does not decode (" +
                           brdfcl::detail::printable(decoded.ok() ? "no mesh" : decoded.status().error_msg_string(), 120) +
                           "); re-export the file");
  std::unique_ptr<draco::Mesh> mesh = std::move(decoded).value();
  const std::size_t points = mesh->num_points(), faces = mesh->num_faces();
  if (points > options.maxElements || faces > options.maxElements - points)
    fail(source, prim, "the Draco mesh has " + std::to_string(points) + " points and " + std::to_string(faces) +
                           " triangles, more than brdfcl's limit of " + std::to_string(options.maxElements) +
                           "; simplify the model");
  return mesh;
}

// One decoded attribute: the accessor it replaces and its values as float32, point by point.
struct DecodedAttribute {
  int accessor;
  std::vector<unsigned char> bytes;
};

// Where the primitive's attribute `name` is stored (`ap`, the extension's entry for it): the
// accessor and the Draco attribute `idv`, with every id, component count and type checked.
std::pair<int, const draco::PointAttribute*> attributeSource(const std::string& name, const json& idv,
                                                              const tinygltf::Primitive& primitive,
                                                              const tinygltf::Model& model, const draco::Mesh& mesh,
                                                              const std::string& source, const std::string& prim,
                                                              const std::string& ap) {
  if (!idv.is_number_integer() || idv.get<long long>() < 0 || idv.get<long long>() > 0xFFFFFFFFll)
    fail(source, ap, "expected a Draco attribute id (an integer >= 0), got " + brdfcl::detail::describeJson(idv));
  const auto it = primitive.attributes.find(name);
  if (it == primitive.attributes.end())
    fail(source, ap, "the primitive has no attribute " + brdfcl::detail::printable(name, 60) + "; re-export the file");
  const int ai = it->second;
  if (ai < 0 || std::size_t(ai) >= model.accessors.size())
    fail(source, prim + ".attributes." + brdfcl::detail::printable(name, 60),
         "accessor " + std::to_string(ai) + " does not exist (the file has " + std::to_string(model.accessors.size()) +
             "); re-export the file");
  const tinygltf::Accessor& acc = model.accessors[std::size_t(ai)];
  const draco::PointAttribute* att = mesh.GetAttributeByUniqueId(std::uint32_t(idv.get<long long>()));
  if (!att)
    fail(source, ap, "Draco attribute " + std::to_string(idv.get<long long>()) + " is not in the compressed data; re-export the file");
  const int n = componentCount(acc.type);
  if (n == 0 || att->num_components() < n)
    fail(source, ap, "Draco attribute " + std::to_string(idv.get<long long>()) + " has " +
                         std::to_string(att->num_components()) + " components, accessors[" + std::to_string(ai) +
                         "] needs " + std::to_string(n) + "; re-export the file");
  double probe;
  const std::uint8_t zero[8] = {};
  if (!component(zero, att->data_type(), probe))
    fail(source, ap, "Draco attribute " + std::to_string(idv.get<long long>()) + " has a data type glTF has no use for (" +
                         std::to_string(int(att->data_type())) + "); re-export the file");
  return {ai, att};
}

// The values of attribute `name` (accessor `ai`, Draco attribute `att`) at every point of the mesh,
// each point's value index and bytes checked against the attribute's own buffer.
DecodedAttribute attributeValues(const std::string& name, int ai, const draco::PointAttribute* att,
                                 const tinygltf::Model& model, std::size_t points, const std::string& source,
                                 const std::string& prim) {
  const tinygltf::Accessor& acc = model.accessors[std::size_t(ai)];
  const int n = componentCount(acc.type);
  const std::size_t csize = draco::DataTypeLength(att->data_type());
  const bool integer = att->data_type() != draco::DT_FLOAT32;
  const std::size_t limit = att->buffer() ? std::size_t(att->buffer()->data_size()) : 0;
  // mapped_index() does not check its argument against the point map.
  if (!att->is_mapping_identity() && att->indices_map_size() < points)
    fail(source, prim, std::string(kName) + " data does not decode (attribute " + brdfcl::detail::printable(name, 60) +
                           " maps " + std::to_string(att->indices_map_size()) + " of " + std::to_string(points) +
                           " points); re-export the file");
  DecodedAttribute out{ai, std::vector<unsigned char>(points * std::size_t(n) * 4)};
  for (std::size_t pt = 0; pt < points; ++pt) {
    const draco::AttributeValueIndex avi = att->mapped_index(draco::PointIndex(std::uint32_t(pt)));
    const std::int64_t pos = att->GetBytePos(avi);
    if (avi.value() >= att->size() || pos < 0 || std::size_t(pos) + std::size_t(n) * csize > limit)
      fail(source, prim, std::string(kName) + " data does not decode (point " + std::to_string(pt) +
                             " has no value for attribute " + brdfcl::detail::printable(name, 60) + "); re-export the file");
    const std::uint8_t* src = att->GetAddress(avi);
    for (int c = 0; c < n; ++c) {
      double d = 0.0;
      component(src + std::size_t(c) * csize, att->data_type(), d);
      if (integer && acc.normalized) d = normalize(d, acc.componentType);
      const float f = float(d);
      std::memcpy(out.bytes.data() + (pt * std::size_t(n) + std::size_t(c)) * 4, &f, 4);
    }
  }
  return out;
}

// The mesh's triangles as uint32 point indices, each checked against the point count.
std::vector<unsigned char> faceIndices(const draco::Mesh& mesh, const std::string& source, const std::string& prim) {
  const std::size_t points = mesh.num_points(), faces = mesh.num_faces();
  std::vector<unsigned char> indices(faces * 3 * 4);
  for (std::size_t f = 0; f < faces; ++f) {
    const draco::Mesh::Face& face = mesh.face(draco::FaceIndex(std::uint32_t(f)));
    for (int c = 0; c < 3; ++c) {
      const std::uint32_t i = face[std::size_t(c)].value();
      if (i >= points)
        fail(source, prim, std::string(kName) + " data does not decode (face " + std::to_string(f) +
                               " names point " + std::to_string(i) + " of " + std::to_string(points) + "); re-export the file");
      std::memcpy(indices.data() + (f * 3 + std::size_t(c)) * 4, &i, 4);
    }
  }
  return indices;
}

// Points the primitive's accessors at the decoded data: each attribute's float32 values, and the
// indices (the primitive's own accessor, or a new one) at the triangles.
void storeDecoded(const json& primJson, tinygltf::Model& model, tinygltf::Primitive& primitive,
                  std::vector<DecodedAttribute>& outs, std::vector<unsigned char> indices, std::size_t points,
                  std::size_t faces, const std::string& source, const std::string& prim) {
  for (DecodedAttribute& out : outs) {
    const int view = addView(model, std::move(out.bytes));
    tinygltf::Accessor& acc = model.accessors[std::size_t(out.accessor)];
    acc.bufferView = view;
    acc.byteOffset = 0;
    acc.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
    acc.normalized = false;
    acc.count = points;
    acc.sparse.isSparse = false;
  }
  if (const json* ij = member(primJson, "indices")) {
    if (!ij->is_number_integer() || ij->get<long long>() < 0 || std::size_t(ij->get<long long>()) >= model.accessors.size())
      fail(source, prim + ".indices", "accessor " + brdfcl::detail::describeJson(*ij) + " does not exist (the file has " +
                                          std::to_string(model.accessors.size()) + "); re-export the file");
    primitive.indices = int(ij->get<long long>());
  } else {
    tinygltf::Accessor acc;
    acc.type = TINYGLTF_TYPE_SCALAR;
    model.accessors.push_back(acc);
    primitive.indices = int(model.accessors.size()) - 1;
  }
  tinygltf::Accessor& ind = model.accessors[std::size_t(primitive.indices)];
  ind.bufferView = addView(model, std::move(indices));
  ind.byteOffset = 0;
  ind.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
  ind.type = TINYGLTF_TYPE_SCALAR;
  ind.normalized = false;
  ind.count = faces * 3;
  ind.sparse.isSparse = false;
  primitive.mode = TINYGLTF_MODE_TRIANGLES;  // Draco's faces are triangles, also for strips
}

void decodePrimitive(const json& primJson, const json& ext, tinygltf::Model& model, std::size_t m, std::size_t p, const std::string& source,
                     const LoadOptions& options) {
  const std::string prim = "meshes[" + std::to_string(m) + "].primitives[" + std::to_string(p) + "]";
  const std::string path = prim + ".extensions." + kName;
  const json* attrs = nullptr;
  const auto bytes = compressedBytes(ext, model, source, path, attrs);
  const std::unique_ptr<draco::Mesh> mesh = decodeMesh(bytes, source, prim, options);
  const std::size_t points = mesh->num_points(), faces = mesh->num_faces();

  tinygltf::Primitive& primitive = model.meshes[m].primitives[p];
  // Attributes first: all checks before the model changes.
  std::vector<DecodedAttribute> outs;
  for (const auto& [name, idv] : attrs->items()) {
    const std::string ap = path + ".attributes." + brdfcl::detail::printable(name, 60);
    const auto [ai, att] = attributeSource(name, idv, primitive, model, *mesh, source, prim, ap);
    outs.push_back(attributeValues(name, ai, att, model, points, source, prim));
  }
  std::vector<unsigned char> indices = faceIndices(*mesh, source, prim);
  storeDecoded(primJson, model, primitive, outs, std::move(indices), points, faces, source, prim);
}

}  // namespace

bool hasDracoPrimitives(const json& doc) {
  const json* meshes = member(doc, "meshes");
  if (!meshes || !meshes->is_array()) return false;
  for (const json& mesh : *meshes)
    if (const json* prims = member(mesh, "primitives"); prims && prims->is_array())
      for (const json& prim : *prims)
        if (const json* ext = member(prim, "extensions"); ext && member(*ext, kName)) return true;
  return false;
}

void withoutDracoIndices(json& doc) {
  for (json& mesh : doc["meshes"])
    if (mesh.is_object() && mesh.contains("primitives") && mesh["primitives"].is_array())
      for (json& prim : mesh["primitives"])
        if (const json* ext = member(prim, "extensions"); ext && member(*ext, kName)) prim.erase("indices");
}

void decodeDraco(const json& doc, tinygltf::Model& model, const std::string& source, const LoadOptions& options) {
  const json* meshes = member(doc, "meshes");
  if (!meshes || !meshes->is_array()) return;
  for (std::size_t m = 0; m < meshes->size() && m < model.meshes.size(); ++m) {
    const json* prims = member((*meshes)[m], "primitives");
    if (!prims || !prims->is_array()) continue;
    for (std::size_t p = 0; p < prims->size() && p < model.meshes[m].primitives.size(); ++p) {
      const json* ext = member((*prims)[p], "extensions");
      const json* draco = ext ? member(*ext, kName) : nullptr;
      if (draco) decodePrimitive((*prims)[p], *draco, model, m, p, source, options);
    }
  }
}

}  // namespace brdfcl::gltf::detail
