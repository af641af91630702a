// writeDemoAsset: the built-in sphere sweep as a .glb, assembled here (JSON with nlohmann, GLB
// container by hand) so that every extension object is written exactly as the specs spell it.
// Geometry and texture designs are described in gltf/demo_asset.hpp.
#include "gltf/demo_asset.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "brdfcl/error.hpp"
#include "brdfcl/image.hpp"
#include "brdfcl/io.hpp"
#include "io/files.hpp"
#include "io/messages.hpp"
#include "io/png.hpp"

static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__, "the BIN chunk copies little-endian values as-is");

namespace brdfcl::gltf {
namespace {

using json = nlohmann::json;
constexpr double kPi = 3.14159265358979323846;

constexpr float kRadius = 0.46f;
constexpr int kSegmentsU = 64, kSegmentsV = 32;

constexpr int kClothSize = 128, kClothThreads = 4;
constexpr double kThreadHalfWidth = 0.4;  // of the thread pitch; the rest is gap
constexpr int kFlakeSize = 256, kFlakeCell = 8;
constexpr double kFlakeMaxTiltDegrees = 12.0;
constexpr int kBrushedSize = 256;
constexpr double kBrushJitterDegrees = 4.0;

// glTF enums.
constexpr int kFloat = 5126, kUnsignedShort = 5123;
constexpr int kArrayBuffer = 34962, kElementArrayBuffer = 34963;
constexpr int kNearest = 9728, kLinear = 9729, kLinearMipmapLinear = 9987;
constexpr int kRepeat = 10497, kClampToEdge = 33071;

std::uint8_t unorm8(double v) { return static_cast<std::uint8_t>(std::lround(std::clamp(v, 0.0, 1.0) * 255.0)); }

// --- Procedural textures -------------------------------------------------------------------

// Plain weave: warp threads run down the image (along v), weft threads across (along u); in
// thread cell (i, j) the warp lies on top when i + j is even. A thread is brightest along its
// middle and where it floats highest (mid-cell), so the crossings read as woven.
std::vector<std::uint8_t> clothTexels() {
  const int pitch = kClothSize / kClothThreads;
  std::vector<std::uint8_t> rgba(4 * kClothSize * kClothSize);
  for (int y = 0; y < kClothSize; ++y)
    for (int x = 0; x < kClothSize; ++x) {
      const int i = x / pitch, j = y / pitch;
      const double fx = ((x % pitch) + 0.5) / pitch - 0.5, fy = ((y % pitch) + 0.5) / pitch - 0.5;
      const bool inWarp = std::fabs(fx) < kThreadHalfWidth, inWeft = std::fabs(fy) < kThreadHalfWidth;
      const bool warpOnTop = (i + j) % 2 == 0;
      std::array<double, 3> colour{0.08, 0.08, 0.08};
      double roughness = 0.5;
      if (inWarp || inWeft) {
        const bool warp = inWarp && (warpOnTop || !inWeft);
        const double across = warp ? fx : fy, along = warp ? fy : fx;
        const double shade =
            (0.55 + 0.45 * std::cos(0.5 * kPi * across / kThreadHalfWidth)) * (0.8 + 0.2 * std::cos(kPi * along));
        const std::array<double, 3> tint = warp ? std::array<double, 3>{1.0, 1.0, 1.0} : std::array<double, 3>{0.8, 0.85, 0.95};
        for (int c = 0; c < 3; ++c) colour[c] = tint[c] * shade;
        roughness = 1.0;
      }
      std::uint8_t* t = &rgba[4 * (std::size_t(y) * kClothSize + x)];
      for (int c = 0; c < 3; ++c) t[c] = encodeSrgb8(float(colour[c]));
      t[3] = unorm8(roughness);
    }
  return rgba;
}

// Chris Wellons' "lowbias32" integer hash: well mixed, so neighbouring cells look independent.
std::uint32_t hash32(std::uint32_t x) {
  x ^= x >> 16;
  x *= 0x7feb352du;
  x ^= x >> 15;
  x *= 0x846ca68bu;
  x ^= x >> 16;
  return x;
}

// One random tilt per cell, uniform over the disc of directions within the maximum tilt (hence the
// square root), so most flakes are slightly tilted and a few catch the light from far off.
std::vector<std::uint8_t> flakeTexels() {
  const int cells = kFlakeSize / kFlakeCell;
  std::vector<std::uint8_t> rgb(3 * kFlakeSize * kFlakeSize);
  for (int y = 0; y < kFlakeSize; ++y)
    for (int x = 0; x < kFlakeSize; ++x) {
      const std::uint32_t h = hash32(std::uint32_t((y / kFlakeCell) * cells + x / kFlakeCell));
      const double tilt = kFlakeMaxTiltDegrees * kPi / 180.0 * std::sqrt((h & 0xffffu) / 65536.0);
      const double azimuth = 2.0 * kPi * (h >> 16) / 65536.0;
      const double n[3] = {std::sin(tilt) * std::cos(azimuth), std::sin(tilt) * std::sin(azimuth), std::cos(tilt)};
      for (int c = 0; c < 3; ++c) rgb[3 * (std::size_t(y) * kFlakeSize + x) + c] = unorm8(0.5 * n[c] + 0.5);
    }
  return rgb;
}

// Circular brushing around the point that faces the camera. Positions are measured on the sphere
// near its front, where a step in u is twice as long as a step in v; tangent-space +Y is -v. Each
// ring one texel wide (along u) turns its direction a little, as the grooves of a turned or
// brushed disc do, so the highlight breaks into streaks.
std::vector<std::uint8_t> brushedTexels() {
  std::vector<std::uint8_t> rgb(3 * kBrushedSize * kBrushedSize);
  for (int y = 0; y < kBrushedSize; ++y)
    for (int x = 0; x < kBrushedSize; ++x) {
      const double a = 2.0 * ((x + 0.5) / kBrushedSize - 0.5);  // along T
      const double b = -((y + 0.5) / kBrushedSize - 0.5);       // along B
      const double l = std::hypot(a, b);                        // > 0: texel centres miss (0.5, 0.5)
      const auto ring = std::uint32_t(l * kBrushedSize / 2);
      const double jitter =
          kBrushJitterDegrees * kPi / 180.0 * (2.0 * (hash32(ring) & 0xffffu) / 65535.0 - 1.0);
      const double dx = -b / l, dy = a / l;
      std::uint8_t* t = &rgb[3 * (std::size_t(y) * kBrushedSize + x)];
      t[0] = unorm8(0.5 * (dx * std::cos(jitter) - dy * std::sin(jitter)) + 0.5);
      t[1] = unorm8(0.5 * (dx * std::sin(jitter) + dy * std::cos(jitter)) + 0.5);
      t[2] = 255;
    }
  return rgb;
}

// --- Binary buffer -----------------------------------------------------------------------------

class Bin {
 public:
  // Appends `bytes` 4-byte aligned (what float accessors need) as a new bufferView.
  int view(json& gltf, const void* bytes, std::size_t size, int target = 0) {
    data_.resize((data_.size() + 3) & ~std::size_t(3), '\0');
    json v = {{"buffer", 0}, {"byteOffset", data_.size()}, {"byteLength", size}};
    if (target) v["target"] = target;
    data_.append(static_cast<const char*>(bytes), size);
    gltf["bufferViews"].push_back(v);
    return int(gltf["bufferViews"].size()) - 1;
  }
  const std::string& data() const { return data_; }

 private:
  std::string data_;
};

int accessor(json& gltf, int view, int componentType, std::size_t count, const char* type) {
  gltf["accessors"].push_back({{"bufferView", view}, {"componentType", componentType}, {"count", count}, {"type", type}});
  return int(gltf["accessors"].size()) - 1;
}

// --- Scene ---------------------------------------------------------------------------------------

struct SphereMesh {
  std::vector<float> positions, normals, tangents, uvs;
  std::vector<std::uint16_t> indices;
};

// P(u, v) = r (-sin(theta) sin(phi), cos(theta), -sin(theta) cos(phi)), phi = 2 pi u, theta = pi v:
// u = 0.5 faces +Z, and dP/du is along (-cos(phi), 0, sin(phi)) = Y x N, the analytic scene's
// tangent (kernels/gbuffer_spheres.cl), also at the poles where dP/du vanishes.
SphereMesh sphereMesh() {
  SphereMesh m;
  for (int i = 0; i <= kSegmentsV; ++i)
    for (int j = 0; j <= kSegmentsU; ++j) {
      const double u = double(j) / kSegmentsU, v = double(i) / kSegmentsV;
      const double phi = 2.0 * kPi * u, theta = kPi * v;
      const double n[3] = {-std::sin(theta) * std::sin(phi), std::cos(theta), -std::sin(theta) * std::cos(phi)};
      for (int c = 0; c < 3; ++c) {
        m.positions.push_back(float(kRadius * n[c]));
        m.normals.push_back(float(n[c]));
      }
      m.tangents.insert(m.tangents.end(), {float(-std::cos(phi)), 0.0f, float(std::sin(phi)), 1.0f});
      m.uvs.insert(m.uvs.end(), {float(u), float(v)});
    }
  auto at = [](int i, int j) { return std::uint16_t(i * (kSegmentsU + 1) + j); };
  // Counter-clockwise seen from outside: u grows to the right and v downwards on the front.
  for (int i = 0; i < kSegmentsV; ++i)
    for (int j = 0; j < kSegmentsU; ++j) {
      const std::uint16_t a = at(i, j), b = at(i + 1, j), c = at(i + 1, j + 1), d = at(i, j + 1);
      if (i != kSegmentsV - 1) m.indices.insert(m.indices.end(), {a, b, c});  // b == c at the south pole
      if (i != 0) m.indices.insert(m.indices.end(), {a, c, d});               // a == d at the north pole
    }
  return m;
}

// The quaternion (x, y, z, w) turning -Z, the direction a glTF light shines along, onto `d` (unit,
// not +Z).
std::array<double, 4> rotationFromMinusZ(const std::array<double, 3>& d) {
  // q = (a x d, 1 + a.d) normalized, a = (0, 0, -1).
  std::array<double, 4> q{d[1], -d[0], 0.0, 1.0 - d[2]};
  const double l = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
  for (double& c : q) c /= l;
  return q;
}

json textureInfo(int texture, double scaleU = 0.0, double scaleV = 0.0) {
  json t = {{"index", texture}};
  if (scaleU > 0.0) t["extensions"]["KHR_texture_transform"] = {{"scale", {scaleU, scaleV}}};
  return t;
}

// The factors are renderSpheresGBuffer()'s (host/src/render/spheres_gbuffer.cpp), row by row.
json material(int row, int col, int cloth, int flakes, int brushed) {
  static const char* const kRowName[] = {"white sheen", "coloured sheen", "clearcoat", "anisotropy strength",
                                         "anisotropy rotation", "gold"};
  const double t = col / 5.0;
  std::array<double, 3> base{0.5, 0.5, 0.5};
  double metallic = 0.0, roughness = 0.5;
  json ext = json::object();
  switch (row) {
    case 0:
    case 1:
      base = {row ? 0.25 : 0.02, 0.02, row ? 0.03 : 0.12};
      roughness = 0.8;
      ext["KHR_materials_sheen"] = {
          {"sheenColorFactor", {1.0, row ? 0.45 : 1.0, row ? 0.3 : 1.0}},
          {"sheenRoughnessFactor", 0.05 + 0.95 * t},
          {"sheenColorTexture", textureInfo(cloth, 8.0, 4.0)},
          {"sheenRoughnessTexture", textureInfo(cloth, 8.0, 4.0)}};
      break;
    case 2:
      base = {0.8, 0.25, 0.05};
      roughness = 0.7;
      ext["KHR_materials_clearcoat"] = {{"clearcoatFactor", 1.0},
                                        {"clearcoatRoughnessFactor", t},
                                        {"clearcoatNormalTexture", textureInfo(flakes, 2.0, 1.0)}};
      break;
    case 3:
    case 4:
      base = row == 3 ? std::array<double, 3>{0.95, 0.93, 0.88} : std::array<double, 3>{0.95, 0.64, 0.54};
      metallic = 1.0;
      roughness = 0.3;
      ext["KHR_materials_anisotropy"] = {{"anisotropyStrength", row == 3 ? t : 0.8},
                                         {"anisotropyRotation", row == 3 ? 0.0 : kPi * t},
                                         {"anisotropyTexture", textureInfo(brushed)}};
      break;
    default:
      base = {1.0, 0.78, 0.34};
      metallic = col % 2 == 0 ? 1.0 : 0.0;
      roughness = t;
  }
  json m = {{"name", std::string(kRowName[row]) + " r" + std::to_string(row) + " c" + std::to_string(col)},
            {"pbrMetallicRoughness",
             {{"baseColorFactor", {base[0], base[1], base[2], 1.0}}, {"metallicFactor", metallic}, {"roughnessFactor", roughness}}}};
  if (!ext.empty()) m["extensions"] = ext;
  return m;
}

void appendU32(std::string& s, std::uint32_t v) { s.append(reinterpret_cast<const char*>(&v), 4); }

// The sphere's vertex and index accessors, all spheres share them.
struct SphereAccessors {
  int position, normal, tangent, uv, indices;
};

SphereAccessors sphereAccessors(json& gltf, Bin& bin) {
  const SphereMesh sphere = sphereMesh();
  const std::size_t vertices = sphere.positions.size() / 3;
  const int position = accessor(gltf, bin.view(gltf, sphere.positions.data(), sphere.positions.size() * 4, kArrayBuffer),
                                kFloat, vertices, "VEC3");
  // The spec requires POSITION bounds; taken from the floats written so they are exact.
  for (int c = 0; c < 3; ++c) {
    float lo = sphere.positions[c], hi = lo;
    for (std::size_t k = c; k < sphere.positions.size(); k += 3)
      lo = std::min(lo, sphere.positions[k]), hi = std::max(hi, sphere.positions[k]);
    gltf["accessors"][position]["min"].push_back(lo);
    gltf["accessors"][position]["max"].push_back(hi);
  }
  const int normal = accessor(gltf, bin.view(gltf, sphere.normals.data(), sphere.normals.size() * 4, kArrayBuffer),
                              kFloat, vertices, "VEC3");
  const int tangent = accessor(gltf, bin.view(gltf, sphere.tangents.data(), sphere.tangents.size() * 4, kArrayBuffer),
                               kFloat, vertices, "VEC4");
  const int uv = accessor(gltf, bin.view(gltf, sphere.uvs.data(), sphere.uvs.size() * 4, kArrayBuffer), kFloat,
                          vertices, "VEC2");
  const int indices = accessor(gltf, bin.view(gltf, sphere.indices.data(), sphere.indices.size() * 2, kElementArrayBuffer),
                               kUnsignedShort, sphere.indices.size(), "SCALAR");

  return {position, normal, tangent, uv, indices};
}

// The 6 x 6 spheres, a material, mesh and node each; their nodes join `roots`.
void addSpheres(json& gltf, json& roots, const SphereAccessors& a, int cloth, int flakes, int brushed) {
  for (int row = 0; row < 6; ++row)
    for (int col = 0; col < 6; ++col) {
      gltf["materials"].push_back(material(row, col, cloth, flakes, brushed));
      const int index = row * 6 + col;
      // A mesh binds its material per primitive: one mesh per sphere, all on the same accessors.
      gltf["meshes"].push_back(
          {{"name", "sphere r" + std::to_string(row) + " c" + std::to_string(col)},
           {"primitives",
            {{{"attributes", {{"POSITION", a.position}, {"NORMAL", a.normal}, {"TANGENT", a.tangent}, {"TEXCOORD_0", a.uv}}},
              {"indices", a.indices},
              {"material", index}}}}});
      gltf["nodes"].push_back({{"name", "sphere r" + std::to_string(row) + " c" + std::to_string(col)},
                               {"mesh", index},
                               {"translation", {(col - 2.5) * 1.05, (2.5 - row) * 1.05, 0.0}}});
      roots.push_back(index);
    }
}

// The camera, the key and the fill light; their nodes join `roots`.
void addCameraAndLights(json& gltf, json& roots) {
  gltf["cameras"] = {{{"name", "camera"},
                      {"type", "perspective"},
                      {"perspective", {{"yfov", 30.0 * kPi / 180.0}, {"aspectRatio", 1.0}, {"znear", 0.1}}}}};
  gltf["nodes"].push_back({{"name", "camera"}, {"camera", 0}, {"translation", {0.0, 0.0, 13.0}}});
  roots.push_back(gltf["nodes"].size() - 1);

  const double kl = std::sqrt(0.5 * 0.5 + 0.6 * 0.6 + 0.62 * 0.62);
  const std::array<double, 4> keyRotation = rotationFromMinusZ({0.5 / kl, -0.6 / kl, -0.62 / kl});
  gltf["extensions"]["KHR_lights_punctual"]["lights"] = {
      {{"name", "key"}, {"type", "directional"}, {"intensity", 2.5}, {"color", {1.0, 0.96, 0.9}}},
      {{"name", "fill"}, {"type", "point"}, {"intensity", 30.0}, {"color", {0.8, 0.85, 1.0}}}};
  gltf["nodes"].push_back({{"name", "key light"},
                           {"rotation", {keyRotation[0], keyRotation[1], keyRotation[2], keyRotation[3]}},
                           {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
  roots.push_back(gltf["nodes"].size() - 1);
  gltf["nodes"].push_back({{"name", "fill light"},
                           {"translation", {-6.0, 2.0, 6.0}},
                           {"extensions", {{"KHR_lights_punctual", {{"light", 1}}}}}});
  roots.push_back(gltf["nodes"].size() - 1);
}

// GLB: 12-byte header, then the JSON chunk padded with spaces and the BIN chunk padded with
// zeros, both to 4 bytes.
std::string glbBytes(const json& gltf, const std::string& bin) {
  std::string text = gltf.dump();
  text.resize((text.size() + 3) & ~std::size_t(3), ' ');
  std::string binary = bin;
  binary.resize((binary.size() + 3) & ~std::size_t(3), '\0');
  std::string glb;
  glb.reserve(12 + 8 + text.size() + 8 + binary.size());
  appendU32(glb, 0x46546C67u);  // "glTF"
  appendU32(glb, 2);
  appendU32(glb, std::uint32_t(12 + 8 + text.size() + 8 + binary.size()));
  appendU32(glb, std::uint32_t(text.size()));
  appendU32(glb, 0x4E4F534Au);  // "JSON"
  glb += text;
  appendU32(glb, std::uint32_t(binary.size()));
  appendU32(glb, 0x004E4942u);  // "BIN\0"
  glb += binary;
  return glb;
}

}  // namespace

void writeDemoAsset(const std::string& path) {
  const std::string shown = detail::printable(path, 300);
  json gltf = {{"asset", {{"version", "2.0"}, {"generator", "brdfcl writeDemoAsset"}}},
               {"extensionsUsed",
                {"KHR_materials_sheen", "KHR_materials_clearcoat", "KHR_materials_anisotropy", "KHR_texture_transform",
                 "KHR_lights_punctual"}},
               {"scene", 0},
               {"bufferViews", json::array()},
               {"accessors", json::array()}};
  Bin bin;

  const SphereAccessors accessors = sphereAccessors(gltf, bin);

  gltf["samplers"] = {
      {{"magFilter", kLinear}, {"minFilter", kLinearMipmapLinear}, {"wrapS", kRepeat}, {"wrapT", kRepeat}},
      // Flakes stay crisp cells when magnified.
      {{"magFilter", kNearest}, {"minFilter", kLinearMipmapLinear}, {"wrapS", kRepeat}, {"wrapT", kRepeat}},
      // The brushing field does not tile; clamping keeps the seam from mixing its two ends.
      {{"magFilter", kLinear}, {"minFilter", kLinearMipmapLinear}, {"wrapS", kClampToEdge}, {"wrapT", kClampToEdge}}};
  auto addTexture = [&](const char* name, const std::vector<std::uint8_t>& texels, int size, int channels, int sampler) {
    const std::string png = detail::encodePng(texels.data(), size, size, channels);
    if (png.empty()) throw Error("cannot write '" + shown + "': the PNG encoder failed (out of memory?)");
    gltf["images"].push_back({{"name", name}, {"mimeType", "image/png"}, {"bufferView", bin.view(gltf, png.data(), png.size())}});
    gltf["textures"].push_back({{"name", name}, {"source", gltf["images"].size() - 1}, {"sampler", sampler}});
    return int(gltf["textures"].size()) - 1;
  };
  const int cloth = addTexture("cloth", clothTexels(), kClothSize, 4, 0);
  const int flakes = addTexture("flakes", flakeTexels(), kFlakeSize, 3, 1);
  const int brushed = addTexture("brushed", brushedTexels(), kBrushedSize, 3, 2);

  json roots = json::array();
  addSpheres(gltf, roots, accessors, cloth, flakes, brushed);
  addCameraAndLights(gltf, roots);
  gltf["scenes"] = {{{"name", "spheres"}, {"nodes", roots}}};
  gltf["buffers"] = {{{"byteLength", bin.data().size()}}};

  const std::string glb = glbBytes(gltf, bin.data());
  writeOutput(path, glb.data(), glb.size());
}

}  // namespace brdfcl::gltf
