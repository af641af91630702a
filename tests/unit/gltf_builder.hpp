// Test helper: synthetic glTF files written from code. Build the document with the add* calls
// (or edit `doc` directly), then write a .gltf with an external .bin or data URIs, or a .glb.
// Images are encoded in memory (PNG 8-bit and JPEG by stb_image_write, PNG 16-bit by a small
// stored-deflate encoder here), stored as files, data URIs or GLB buffer views like the buffers.
#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

// The encoders come from Debian's compiled libstb (linked through brdfcl_core), not from a copy
// compiled into the tests: its JPEG writer shifts negative ints, which UBSan would report here.
#include <stb/stb_image_write.h>

namespace brdfcl::test {

enum class Storage { ExternalFiles, DataUris, Glb };

inline std::string base64(const std::string& bytes) {
  static const char* k = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  std::size_t i = 0;
  for (; i + 2 < bytes.size(); i += 3) {
    const std::uint32_t v = std::uint32_t(std::uint8_t(bytes[i])) << 16 | std::uint32_t(std::uint8_t(bytes[i + 1])) << 8 |
                            std::uint8_t(bytes[i + 2]);
    out += {k[v >> 18], k[(v >> 12) & 63], k[(v >> 6) & 63], k[v & 63]};
  }
  if (i + 1 == bytes.size()) {
    const std::uint32_t v = std::uint32_t(std::uint8_t(bytes[i])) << 16;
    out += {k[v >> 18], k[(v >> 12) & 63], '=', '='};
  } else if (i + 2 == bytes.size()) {
    const std::uint32_t v = std::uint32_t(std::uint8_t(bytes[i])) << 16 | std::uint32_t(std::uint8_t(bytes[i + 1])) << 8;
    out += {k[v >> 18], k[(v >> 12) & 63], k[(v >> 6) & 63], '='};
  }
  return out;
}

// PNG of `channels` (1 to 4) 8-bit samples per pixel, rows from the top.
inline std::string encodePng8(int w, int h, int channels, const std::vector<std::uint8_t>& px) {
  std::string out;
  stbi_write_png_to_func([](void* ctx, void* data, int size) { static_cast<std::string*>(ctx)->append(static_cast<char*>(data), std::size_t(size)); },
                         &out, w, h, channels, px.data(), w * channels);
  return out;
}

inline std::string encodeJpeg(int w, int h, int channels, const std::vector<std::uint8_t>& px, int quality = 95) {
  std::string out;
  stbi_write_jpg_to_func([](void* ctx, void* data, int size) { static_cast<std::string*>(ctx)->append(static_cast<char*>(data), std::size_t(size)); },
                         &out, w, h, channels, px.data(), quality);
  return out;
}

// PNG of 16-bit samples (stb_image_write has none): zlib with stored blocks, CRC and Adler computed here.
inline std::string encodePng16(int w, int h, int channels, const std::vector<std::uint16_t>& px) {
  auto crc = [](const std::string& s) {
    std::uint32_t c = 0xFFFFFFFFu;
    for (unsigned char b : s) {
      c ^= b;
      for (int k = 0; k < 8; ++k) c = (c >> 1) ^ (0xEDB88320u & (0u - (c & 1u)));
    }
    return c ^ 0xFFFFFFFFu;
  };
  auto be32 = [](std::uint32_t v) {
    return std::string{char(v >> 24), char((v >> 16) & 255), char((v >> 8) & 255), char(v & 255)};
  };
  auto chunk = [&](const std::string& type, const std::string& data) {
    return be32(std::uint32_t(data.size())) + type + data + be32(crc(type + data));
  };
  std::string raw;
  for (int y = 0; y < h; ++y) {
    raw += '\0';  // filter: none
    for (int i = 0; i < w * channels; ++i) {
      const std::uint16_t v = px[std::size_t(y) * std::size_t(w * channels) + std::size_t(i)];
      raw += char(v >> 8);
      raw += char(v & 255);
    }
  }
  std::string z = "\x78\x01";
  std::uint32_t a = 1, b = 0;
  for (unsigned char c : raw) {
    a = (a + c) % 65521;
    b = (b + a) % 65521;
  }
  for (std::size_t off = 0; off < raw.size() || off == 0; off += 65535) {
    const std::size_t n = std::min<std::size_t>(65535, raw.size() - off);
    const bool last = off + n >= raw.size();
    z += char(last ? 1 : 0);
    z += {char(n & 255), char(n >> 8), char(~n & 255), char((~n >> 8) & 255)};
    z += raw.substr(off, n);
    if (last) break;
  }
  z += be32((b << 16) | a);
  const char colorType = channels == 1 ? 0 : channels == 2 ? 4 : channels == 3 ? 2 : 6;
  const std::string ihdr = be32(std::uint32_t(w)) + be32(std::uint32_t(h)) + std::string{16, colorType, 0, 0, 0};
  return std::string("\x89PNG\r\n\x1a\n", 8) + chunk("IHDR", ihdr) + chunk("IDAT", z) + chunk("IEND", "");
}

class GltfBuilder {
 public:
  using json = nlohmann::json;
  json doc = {{"asset", {{"version", "2.0"}, {"generator", "brdfcl tests"}}}};
  std::string bin;  // buffers[0]
  std::vector<json> extraBuffers;  // buffers[1], [2], ... written as they are (e.g. a buffer without data)

  // Raw bytes appended to buffers[0] at a 4-byte boundary, without a view; returns their byteOffset.
  std::size_t appendBytes(const void* data, std::size_t size) {
    while (bin.size() % 4) bin += '\0';
    const std::size_t offset = bin.size();
    bin.append(static_cast<const char*>(data), size);
    return offset;
  }

  // Raw bytes appended to buffers[0] at a 4-byte boundary; returns the new bufferView's index.
  int addBufferView(const void* data, std::size_t size, int byteStride = 0) {
    while (bin.size() % 4) bin += '\0';
    json v = {{"buffer", 0}, {"byteOffset", bin.size()}, {"byteLength", size}};
    if (byteStride) v["byteStride"] = byteStride;
    bin.append(static_cast<const char*>(data), size);
    return push("bufferViews", v);
  }

  // An accessor over a new tightly packed buffer view. componentType 5120..5126, type "SCALAR", "VEC3", ...
  template <class T>
  int addAccessor(const std::vector<T>& values, int componentType, const std::string& type, bool normalized = false) {
    const int view = addBufferView(values.data(), values.size() * sizeof(T));
    json a = {{"bufferView", view}, {"componentType", componentType}, {"count", values.size() / components(type)},
              {"type", type}};
    if (normalized) a["normalized"] = true;
    if (type == "VEC3" && componentType == 5126) addMinMax(a, values);
    return push("accessors", a);
  }
  int addFloats(const std::vector<float>& v, const std::string& type) { return addAccessor(v, 5126, type); }
  int addIndices(const std::vector<std::uint32_t>& v) { return addAccessor(v, 5125, "SCALAR"); }

  // A primitive object (to put in addMesh); attributes name accessors.
  static json primitive(const std::map<std::string, int>& attributes, int indices = -1, int material = -1, int mode = -1) {
    json p = {{"attributes", json::object()}};
    for (const auto& [k, v] : attributes) p["attributes"][k] = v;
    if (indices >= 0) p["indices"] = indices;
    if (material >= 0) p["material"] = material;
    if (mode >= 0) p["mode"] = mode;
    return p;
  }
  int addMesh(const std::vector<json>& primitives) { return push("meshes", {{"primitives", primitives}}); }
  // A node; extra keys (translation, matrix, children, camera, extensions, ...) merged in.
  int addNode(json node = json::object()) { return push("nodes", node); }
  int addMeshNode(int mesh, json extra = json::object()) {
    extra["mesh"] = mesh;
    return addNode(extra);
  }
  int addScene(const std::vector<int>& nodes) {
    const int s = push("scenes", {{"nodes", nodes}});
    if (!doc.contains("scene")) doc["scene"] = s;
    return s;
  }
  int addMaterial(json m) { return push("materials", m); }
  int addSampler(json s) { return push("samplers", s); }
  int addTexture(int image, int sampler = -1) {
    json t = {{"source", image}};
    if (sampler >= 0) t["sampler"] = sampler;
    return push("textures", t);
  }
  int addCamera(json c) { return push("cameras", c); }
  int addLight(json l) {  // KHR_lights_punctual
    useExtension("KHR_lights_punctual");
    json& list = doc["extensions"]["KHR_lights_punctual"]["lights"];
    list.push_back(l);
    return int(list.size()) - 1;
  }
  void useExtension(const std::string& name, bool required = false) {
    addUnique(doc["extensionsUsed"], name);
    if (required) addUnique(doc["extensionsRequired"], name);
  }
  // An encoded image (PNG or JPEG bytes); `file` names it when written as an external file.
  int addImage(const std::string& encoded, const std::string& mime = "image/png", const std::string& file = "") {
    images_.push_back({encoded, mime, file.empty() ? "image" + std::to_string(images_.size()) + (mime == "image/png" ? ".png" : ".jpg") : file});
    return int(images_.size()) - 1;
  }

  // One triangle list as a mesh: positions (3 per vertex), optional normals/uvs, indices (3 per triangle).
  int addTriangles(const std::vector<float>& positions, const std::vector<std::uint32_t>& indices, int material = -1,
                   const std::vector<float>& normals = {}, const std::vector<float>& uv0 = {}) {
    std::map<std::string, int> attrs{{"POSITION", addFloats(positions, "VEC3")}};
    if (!normals.empty()) attrs["NORMAL"] = addFloats(normals, "VEC3");
    if (!uv0.empty()) attrs["TEXCOORD_0"] = addFloats(uv0, "VEC2");
    return addMesh({primitive(attrs, indices.empty() ? -1 : addIndices(indices), material)});
  }

  // The document as written with `storage`; `binName` names the external .bin.
  json finished(Storage storage, const std::string& binName, std::string* glbBin = nullptr) const {
    json d = doc;
    std::string data = bin;
    for (std::size_t i = 0; i < images_.size(); ++i) {
      json img;
      if (storage == Storage::Glb) {
        while (data.size() % 4) data += '\0';
        d["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", data.size()}, {"byteLength", images_[i].bytes.size()}});
        data += images_[i].bytes;
        img = {{"bufferView", d["bufferViews"].size() - 1}, {"mimeType", images_[i].mime}};
      } else if (storage == Storage::DataUris) {
        img = {{"uri", "data:" + images_[i].mime + ";base64," + base64(images_[i].bytes)}};
      } else {
        img = {{"uri", images_[i].file}};
      }
      d["images"].push_back(img);
    }
    while (data.size() % 4) data += '\0';
    if (!data.empty()) {
      json b = {{"byteLength", data.size()}};
      if (storage == Storage::DataUris) b["uri"] = "data:application/octet-stream;base64," + base64(data);
      if (storage == Storage::ExternalFiles) b["uri"] = binName;
      d["buffers"] = json::array({b});
    }
    for (const json& e : extraBuffers) d["buffers"].push_back(e);
    if (glbBin) *glbBin = data;
    return d;
  }

  // Writes dir/name (.gltf or .glb by the name) and the external files it needs; returns its path.
  std::string write(const std::string& dir, const std::string& name, Storage storage = Storage::DataUris) const {
    const std::string path = dir + "/" + name;
    const std::string binName = name.substr(0, name.find_last_of('.')) + ".bin";
    std::string data;
    const json d = finished(storage, binName, &data);
    if (storage == Storage::Glb) {
      writeFile(path, glb(d.dump(), data));
      return path;
    }
    writeFile(path, d.dump(1));
    if (storage == Storage::ExternalFiles) {
      if (!data.empty()) writeFile(dir + "/" + binName, data);
      for (const auto& img : images_) writeFile(dir + "/" + img.file, img.bytes);
    }
    return path;
  }

  // The bytes of a .glb holding `jsonText` and `binData`.
  static std::string glb(std::string jsonText, std::string binData) {
    while (jsonText.size() % 4) jsonText += ' ';
    while (binData.size() % 4) binData += '\0';
    std::string out = "glTF" + le32(2) + le32(0);
    out += le32(std::uint32_t(jsonText.size())) + "JSON" + jsonText;
    if (!binData.empty()) out += le32(std::uint32_t(binData.size())) + std::string("BIN\0", 4) + binData;
    const std::string len = le32(std::uint32_t(out.size()));
    out.replace(8, 4, len);
    return out;
  }
  static std::string le32(std::uint32_t v) {
    return std::string{char(v & 255), char((v >> 8) & 255), char((v >> 16) & 255), char(v >> 24)};
  }
  static void writeFile(const std::string& path, const std::string& bytes) {
    std::ofstream(path, std::ios::binary).write(bytes.data(), std::streamsize(bytes.size()));
  }

 private:
  struct ImageData {
    std::string bytes, mime, file;
  };
  std::vector<ImageData> images_;

  int push(const char* key, const json& value) {
    doc[key].push_back(value);
    return int(doc[key].size()) - 1;
  }
  static void addUnique(json& list, const std::string& name) {
    for (const auto& e : list)
      if (e == name) return;
    list.push_back(name);
  }
  static std::size_t components(const std::string& type) {
    return type == "SCALAR" ? 1 : type == "VEC2" ? 2 : type == "VEC3" ? 3 : type == "VEC4" ? 4 : type == "MAT4" ? 16 : 1;
  }
  template <class T>
  static void addMinMax(json& a, const std::vector<T>& v) {
    if (v.size() < 3) return;
    for (const T& x : v)
      if (!std::isfinite(double(x))) return;  // JSON has no NaN; tests of bad data write none
    json lo = json::array(), hi = json::array();
    for (std::size_t c = 0; c < 3; ++c) {
      double mn = double(v[c]), mx = double(v[c]);
      for (std::size_t i = c; i < v.size(); i += 3) {
        mn = std::min(mn, double(v[i]));
        mx = std::max(mx, double(v[i]));
      }
      lo.push_back(mn);
      hi.push_back(mx);
    }
    a["min"] = lo;
    a["max"] = hi;
  }
};

// A unit quad (two triangles, one mesh node) in a scene of its own, drawn with `material`.
inline GltfBuilder quadWithMaterial(const nlohmann::json& material) {
  GltfBuilder b;
  const int m = b.addMaterial(material);
  const int mesh = b.addTriangles({0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0}, {0, 1, 2, 0, 2, 3}, m);
  b.addScene({b.addMeshNode(mesh)});
  return b;
}

}  // namespace brdfcl::test
