// Document (document.hpp): glTF JSON read with the file's key paths in every message. Ranges are
// the glTF schema's; a number beyond float range counts as infinite and is refused.
#include "gltf/document.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "brdfcl/error.hpp"
#include "io/messages.hpp"
#include "model/gltf_material.hpp"

namespace brdfcl::gltf::detail {
namespace {

using json = nlohmann::json;

constexpr double kHalfPi = 1.57079632679489662;

std::string at(const std::string& path, std::size_t i) { return path + "[" + std::to_string(i) + "]"; }
std::string join(const std::string& path, const char* key) { return path.empty() ? key : path + "." + key; }

// What brdfcl reads; anything else in extensionsUsed is ignored (one warning), and anything else
// in extensionsRequired refuses the file.
const char* const kSupported[] = {"KHR_materials_sheen",      "KHR_materials_clearcoat",   "KHR_materials_anisotropy",
                                  "KHR_materials_emissive_strength", "KHR_materials_variants", "KHR_texture_transform",
                                  "KHR_lights_punctual",      "KHR_mesh_quantization",
                                  "EXT_meshopt_compression", "KHR_draco_mesh_compression"};

bool supported(const std::string& name) {
  return std::any_of(std::begin(kSupported), std::end(kSupported), [&](const char* s) { return name == s; });
}

bool any(double) { return true; }
bool unitRange(double d) { return d >= 0.0 && d <= 1.0; }
bool nonNegative(double d) { return d >= 0.0; }
bool positive(double d) { return d > 0.0; }
bool nonZero(double d) { return d != 0.0; }

}  // namespace

void Document::fail(const std::string& path, const std::string& message) const {
  throw Error(source_ + ": " + path + ": " + message);
}

const json* Document::member(const json& obj, const char* key) const {
  if (!obj.is_object()) return nullptr;
  const auto it = obj.find(key);
  return it == obj.end() ? nullptr : &*it;
}

const json* Document::element(const json& array, std::size_t i) const {
  return array.is_array() && i < array.size() ? &array[i] : nullptr;
}

const json& Document::object(const json& v, const std::string& path) const {
  if (!v.is_object()) fail(path, "expected an object, got " + brdfcl::detail::describeJson(v));
  return v;
}

double Document::number(const json& obj, const char* key, const std::string& path, double fallback,
                        const char* expected, bool (*ok)(double)) const {
  const json* v = member(obj, key);
  return v ? checked(*v, join(path, key), expected, ok) : fallback;
}

double Document::checked(const json& value, const std::string& p, const char* expected, bool (*ok)(double)) const {
  const json* v = &value;
  if (!v->is_number()) fail(p, std::string("expected ") + expected + ", got " + brdfcl::detail::describeJson(*v));
  const double d = v->get<double>();
  if (!std::isfinite(d) || !ok(d)) fail(p, std::string("expected ") + expected + ", got " + brdfcl::detail::formatNumber(d));
  if (std::fabs(d) > std::numeric_limits<float>::max())
    fail(p, std::string("expected ") + expected + ", got " + brdfcl::detail::formatNumber(d) + " (too large for float)");
  return d;
}

int Document::index(const json& obj, const char* key, const std::string& path, int fallback, std::size_t count,
                    const char* what) const {
  const json* v = member(obj, key);
  if (!v) return fallback;
  const std::string p = join(path, key);
  if (!v->is_number_integer() || v->get<long long>() < 0 || std::size_t(v->get<long long>()) >= count)
    fail(p, std::string(what) + " " + brdfcl::detail::describeJson(*v) + " does not exist (the file has " +
                std::to_string(count) + "); re-export the file");
  return static_cast<int>(v->get<long long>());
}

template <std::size_t N>
std::array<float, N> Document::numbers(const json& obj, const char* key, const std::string& path,
                                       std::array<float, N> fallback, bool unit) const {
  const json* v = member(obj, key);
  if (!v) return fallback;
  const std::string p = join(path, key);
  const std::string expected = "an array of " + std::to_string(N) + (unit ? " numbers in [0, 1]" : " finite numbers");
  if (!v->is_array() || v->size() != N) fail(p, "expected " + expected + ", got " + brdfcl::detail::describeJson(*v));
  std::array<float, N> out{};
  for (std::size_t i = 0; i < N; ++i) {
    out[i] = float(checked((*v)[i], at(p, i), unit ? "a number in [0, 1]" : "a finite number", unit ? unitRange : any));
  }
  return out;
}

void Document::checkExtensions(std::vector<std::string>& warnings) const {
  auto names = [&](const char* key) {
    std::vector<std::string> out;
    const json* list = member(doc_, key);
    if (!list) return out;
    if (!list->is_array()) fail(key, "expected an array of extension names, got " + brdfcl::detail::describeJson(*list));
    for (std::size_t i = 0; i < list->size(); ++i) {
      if (!(*list)[i].is_string()) fail(at(key, i), "expected an extension name, got " + brdfcl::detail::describeJson((*list)[i]));
      const std::string name = (*list)[i].get<std::string>();
      if (!supported(name) && std::find(out.begin(), out.end(), name) == out.end()) out.push_back(name);
    }
    return out;
  };
  auto listed = [](const std::vector<std::string>& v) {
    std::string s;
    for (const auto& n : v) s += (s.empty() ? "" : ", ") + brdfcl::detail::printable(n, 80);
    return s;
  };
  std::vector<std::string> required = names("extensionsRequired");
  std::string why;
  if (std::find(required.begin(), required.end(), "KHR_texture_basisu") == required.end() && ktx2WithoutFallback()) {
    required.push_back("KHR_texture_basisu");
    why = " (not listed there, but its textures are KTX2 images without a PNG/JPEG fallback)";
  }
  if (!required.empty())
    fail("extensionsRequired", "brdfcl does not support " + listed(required) + why +
                                   "; use a version of the model without them (e.g. PNG/JPEG textures instead of KTX2)");
  const std::vector<std::string> used = names("extensionsUsed");
  if (!used.empty())
    warnings.push_back(source_ + ": extensionsUsed: brdfcl ignores " + listed(used) +
                       "; the render leaves out what they add");
}

// Exporters have written KTX2 images as a texture's plain "source" without listing
// KHR_texture_basisu as required; such a file cannot be shown without the extension either.
bool Document::ktx2WithoutFallback() const {
  const json* textures = member(doc_, "textures");
  const json* images = member(doc_, "images");
  if (!textures || !images || !textures->is_array() || !images->is_array()) return false;
  for (const json& t : *textures) {
    const json* s = member(t, "source");
    if (!s || !s->is_number_integer() || s->get<long long>() < 0 || std::size_t(s->get<long long>()) >= images->size()) continue;
    const json& img = (*images)[std::size_t(s->get<long long>())];
    const json* uri = member(img, "uri");
    const json* mime = member(img, "mimeType");
    const auto endsKtx2 = [](const std::string& u) { return u.size() >= 5 && u.compare(u.size() - 5, 5, ".ktx2") == 0; };
    if ((uri && uri->is_string() && endsKtx2(uri->get<std::string>())) || (mime && *mime == "image/ktx2")) return true;
  }
  return false;
}

std::vector<Sampler> Document::samplers() const {
  std::vector<Sampler> out;
  const json* list = member(doc_, "samplers");
  if (!list || !list->is_array()) return out;
  for (std::size_t i = 0; i < list->size(); ++i) {
    const std::string path = at("samplers", i);
    const json& s = object((*list)[i], path);
    Sampler smp;
    auto wrap = [&](const char* key) {
      const double w = number(s, key, path, 10497, "33071, 33648 or 10497", [](double d) {
        return d == 33071 || d == 33648 || d == 10497;
      });
      return w == 33071 ? Wrap::ClampToEdge : w == 33648 ? Wrap::MirroredRepeat : Wrap::Repeat;
    };
    smp.wrapS = wrap("wrapS");
    smp.wrapT = wrap("wrapT");
    smp.magNearest = number(s, "magFilter", path, 9729, "9728 or 9729", [](double d) { return d == 9728 || d == 9729; }) == 9728;
    const int minF = int(number(s, "minFilter", path, 9987, "9728, 9729 or 9984 to 9987", [](double d) {
      return d == 9728 || d == 9729 || (d >= 9984 && d <= 9987 && d == std::floor(d));
    }));
    smp.minNearest = minF == 9728 || minF == 9984 || minF == 9986;
    smp.mipmaps = minF >= 9984;
    smp.mipNearest = minF == 9984 || minF == 9985;
    out.push_back(smp);
  }
  return out;
}

std::vector<Texture> Document::textures(std::size_t imageCount, std::size_t samplerCount) const {
  std::vector<Texture> out;
  const json* list = member(doc_, "textures");
  if (!list || !list->is_array()) return out;
  for (std::size_t i = 0; i < list->size(); ++i) {
    const std::string path = at("textures", i);
    const json& t = object((*list)[i], path);
    Texture tex;
    tex.image = index(t, "source", path, -1, imageCount, "image");
    tex.sampler = index(t, "sampler", path, -1, samplerCount, "sampler");
    out.push_back(tex);
  }
  return out;
}

TextureRef Document::textureRef(const json& obj, const char* key, const std::string& parent, std::size_t textureCount,
                                const char* valueKey) const {
  TextureRef ref;
  const json* v = member(obj, key);
  if (!v) return ref;
  const std::string path = join(parent, key);
  const json& info = object(*v, path);
  if (!member(info, "index")) fail(path, "missing \"index\" (the texture); re-export the file");
  ref.texture = index(info, "index", path, -1, textureCount, "texture");
  auto texCoord = [&](const json& o, const std::string& p, int fallback) {
    return int(number(o, "texCoord", p, fallback, "0 or 1 (brdfcl reads TEXCOORD_0 and TEXCOORD_1)",
                      [](double d) { return d == 0.0 || d == 1.0; }));
  };
  ref.texCoord = texCoord(info, path, 0);
  if (valueKey) ref.value = float(number(info, valueKey, path, 1.0, "a finite number", any));
  if (const json* ext = member(info, "extensions"))
    if (const json* tt = member(*ext, "KHR_texture_transform")) {
      const std::string tp = path + ".extensions.KHR_texture_transform";
      object(*tt, tp);
      ref.transform.offset = numbers<2>(*tt, "offset", tp, {0.0f, 0.0f}, false);
      ref.transform.rotation = float(number(*tt, "rotation", tp, 0.0, "a finite number", any));
      ref.transform.scale = numbers<2>(*tt, "scale", tp, {1.0f, 1.0f}, false);
      ref.texCoord = texCoord(*tt, tp, ref.texCoord);
    }
  return ref;
}

std::vector<Material> Document::materials(std::size_t textureCount, std::vector<std::string>& warnings,
                                         bool strict) const {
  std::vector<Material> out;
  const json* list = member(doc_, "materials");
  if (!list || !list->is_array()) return out;
  for (std::size_t i = 0; i < list->size(); ++i)
    out.push_back(material(object((*list)[i], at("materials", i)), at("materials", i), textureCount, strict, warnings));
  return out;
}

Material Document::material(const json& m, const std::string& path, std::size_t textureCount, bool strict,
                            std::vector<std::string>& warnings) const {
  using brdfcl::detail::MaterialTexture;
  Material out;
  brdfcl::detail::GltfMaterialContext context;
  context.source = source_;
  context.reader = brdfcl::detail::MaterialKeyReader::GltfAsset;
  context.strict = strict;
  context.warn = [&warnings](const std::string& w) { warnings.push_back(w); };
  context.texture = [&](MaterialTexture slot, const json& parent, const char* key, const std::string& parentPath,
                        const char* valueKey) {
    const TextureRef ref = textureRef(parent, key, parentPath, textureCount, valueKey);
    switch (slot) {
      case MaterialTexture::Normal: out.normalTexture = ref; break;
      case MaterialTexture::Occlusion:
        if (!unitRange(ref.value))
          fail(path + ".occlusionTexture.strength",
               "expected a number in [0, 1], got " + brdfcl::detail::formatNumber(ref.value));
        out.occlusionTexture = ref;
        break;
      case MaterialTexture::Emissive: out.emissiveTexture = ref; break;
      case MaterialTexture::BaseColor: out.baseColorTexture = ref; break;
      case MaterialTexture::MetallicRoughness: out.metallicRoughnessTexture = ref; break;
      case MaterialTexture::SheenColor: out.sheenColorTexture = ref; break;
      case MaterialTexture::SheenRoughness: out.sheenRoughnessTexture = ref; break;
      case MaterialTexture::Clearcoat: out.clearcoatTexture = ref; break;
      case MaterialTexture::ClearcoatRoughness: out.clearcoatRoughnessTexture = ref; break;
      case MaterialTexture::ClearcoatNormal: out.clearcoatNormalTexture = ref; break;
      case MaterialTexture::Anisotropy: out.anisotropyTexture = ref; break;
      case MaterialTexture::DraftColorIntensity: break;  // materials files only
    }
  };
  const brdfcl::detail::GltfMaterial g = brdfcl::detail::readGltfMaterial(m, path, context);
  const MaterialParams& p = g.params;
  out.name = p.name;
  out.baseColorFactor = {p.baseColor[0], p.baseColor[1], p.baseColor[2], g.baseColorAlpha};
  out.metallicFactor = p.metallic;
  out.roughnessFactor = p.roughness;
  out.emissiveFactor = p.emissive;
  out.emissiveStrength = g.emissiveStrength;
  out.alphaMode = g.alphaMode;
  out.alphaCutoff = g.alphaCutoff;
  out.doubleSided = g.doubleSided;
  out.sheenColorFactor = p.sheenColor;
  out.sheenRoughnessFactor = p.sheenRoughness;
  out.clearcoatFactor = p.clearcoat;
  out.clearcoatRoughnessFactor = p.clearcoatRoughness;
  out.anisotropyStrength = p.anisotropyStrength;
  out.anisotropyRotation = p.anisotropyRotation;
  return out;
}

std::vector<std::string> Document::variants() const {
  std::vector<std::string> out;
  const json* ext = member(doc_, "extensions");
  const json* v = ext ? member(*ext, "KHR_materials_variants") : nullptr;
  if (!v) return out;
  const std::string p = "extensions.KHR_materials_variants.variants";
  const json* list = member(*v, "variants");
  if (!list || !list->is_array()) fail(p, "expected an array of variants, got " + (list ? brdfcl::detail::describeJson(*list) : std::string("nothing")));
  for (std::size_t i = 0; i < list->size(); ++i) {
    const json* name = member((*list)[i], "name");
    if (!name || !name->is_string()) fail(at(p, i) + ".name", "expected the variant's name as a string");
    out.push_back(name->get<std::string>());
  }
  return out;
}

int Document::variantMaterial(std::size_t mesh, std::size_t prim, int variant, int fallback) const {
  if (variant < 0) return fallback;
  const json* meshes = member(doc_, "meshes");
  const json* mj = meshes ? element(*meshes, mesh) : nullptr;
  const json* prims = mj ? member(*mj, "primitives") : nullptr;
  const json* pj = prims ? element(*prims, prim) : nullptr;
  const json* ext = pj ? member(*pj, "extensions") : nullptr;
  const json* v = ext ? member(*ext, "KHR_materials_variants") : nullptr;
  const json* maps = v ? member(*v, "mappings") : nullptr;
  if (!maps) return fallback;
  const std::string p = "meshes[" + std::to_string(mesh) + "].primitives[" + std::to_string(prim) +
                        "].extensions.KHR_materials_variants.mappings";
  if (!maps->is_array()) fail(p, "expected an array of mappings, got " + brdfcl::detail::describeJson(*maps));
  const json* materials = member(doc_, "materials");
  const std::size_t materialCount = materials && materials->is_array() ? materials->size() : 0;
  for (std::size_t k = 0; k < maps->size(); ++k) {
    const json& mapping = object((*maps)[k], at(p, k));
    const json* list = member(mapping, "variants");
    if (!list || !list->is_array()) fail(at(p, k) + ".variants", "expected an array of variant indices");
    for (const json& i : *list)
      if (i.is_number_integer() && i.get<long long>() == variant)
        return index(mapping, "material", at(p, k), fallback, materialCount, "material");
  }
  return fallback;
}

Camera Document::camera(int i) const {
  const std::string path = at("cameras", std::size_t(i));
  const json* cameras = member(doc_, "cameras");
  const json* cj = cameras ? element(*cameras, std::size_t(i)) : nullptr;
  if (!cj) fail(path, "missing; re-export the file");
  const json& c = object(*cj, path);
  Camera cam;
  cam.index = i;
  if (const json* n = member(c, "name"); n && n->is_string()) cam.name = n->get<std::string>();
  const json* type = member(c, "type");
  const std::string t = type && type->is_string() ? type->get<std::string>() : "";
  if (t != "perspective" && t != "orthographic")
    fail(path + ".type", "expected \"perspective\" or \"orthographic\", got " + (type ? brdfcl::detail::describeJson(*type) : "nothing"));
  cam.orthographic = t == "orthographic";
  const std::string p = path + "." + t;
  const json* body = member(c, t.c_str());
  if (!body) fail(path, "missing \"" + t + "\"; re-export the file");
  object(*body, p);
  auto required = [&](const char* key) {
    if (!member(*body, key)) fail(p, std::string("missing \"") + key + "\"; re-export the file");
  };
  if (!cam.orthographic) {
    required("yfov");
    required("znear");
    cam.yfov = number(*body, "yfov", p, 0.8, "a number of radians > 0", positive);
    cam.aspectRatio = number(*body, "aspectRatio", p, 0.0, "a number > 0", positive);
    cam.znear = number(*body, "znear", p, 0.01, "a number > 0", positive);
    cam.zfar = number(*body, "zfar", p, 0.0, "a number > 0", positive);
    if (member(*body, "zfar") && cam.zfar <= cam.znear)
      fail(p + ".zfar", "expected a number > znear (" + brdfcl::detail::formatNumber(cam.znear) + "), got " +
                            brdfcl::detail::formatNumber(cam.zfar) + "; fix the camera's clipping planes");
  } else {
    for (const char* k : {"xmag", "ymag", "znear", "zfar"}) required(k);
    cam.xmag = number(*body, "xmag", p, 1.0, "a non-zero number", nonZero);
    cam.ymag = number(*body, "ymag", p, 1.0, "a non-zero number", nonZero);
    cam.znear = number(*body, "znear", p, 0.0, "a number >= 0", nonNegative);
    cam.zfar = number(*body, "zfar", p, 0.0, "a number > 0", positive);
    if (cam.zfar <= cam.znear)
      fail(p + ".zfar", "expected a number > znear (" + brdfcl::detail::formatNumber(cam.znear) + "), got " +
                            brdfcl::detail::formatNumber(cam.zfar) + "; fix the camera's clipping planes");
  }
  return cam;
}

std::optional<Light> Document::nodeLight(std::size_t node) const {
  const json* nodes = member(doc_, "nodes");
  const json* n = nodes ? element(*nodes, node) : nullptr;
  const json* ext = n ? member(*n, "extensions") : nullptr;
  const json* kl = ext ? member(*ext, "KHR_lights_punctual") : nullptr;
  if (!kl) return std::nullopt;
  const json* rootExt = member(doc_, "extensions");
  const json* rootKl = rootExt ? member(*rootExt, "KHR_lights_punctual") : nullptr;
  const json* lights = rootKl ? member(*rootKl, "lights") : nullptr;
  const std::size_t count = lights && lights->is_array() ? lights->size() : 0;
  const std::string np = "nodes[" + std::to_string(node) + "].extensions.KHR_lights_punctual";
  const int li = index(object(*kl, np), "light", np, -1, count, "light");
  if (li < 0) fail(np, "missing \"light\"; re-export the file");
  const std::string path = "extensions.KHR_lights_punctual.lights[" + std::to_string(li) + "]";
  const json& l = object((*lights)[std::size_t(li)], path);
  Light out;
  const json* type = member(l, "type");
  const std::string t = type && type->is_string() ? type->get<std::string>() : "";
  if (t == "directional") out.type = Light::Type::Directional;
  else if (t == "point") out.type = Light::Type::Point;
  else if (t == "spot") out.type = Light::Type::Spot;
  else fail(path + ".type", "expected \"directional\", \"point\" or \"spot\", got " + (type ? brdfcl::detail::describeJson(*type) : "nothing"));
  out.color = numbers<3>(l, "color", path, out.color, false);
  if (std::any_of(out.color.begin(), out.color.end(), [](float c) { return c < 0.0f; }))
    fail(path + ".color", "expected 3 numbers >= 0");
  out.intensity = float(number(l, "intensity", path, 1.0, "a number >= 0", nonNegative));
  out.range = float(number(l, "range", path, 0.0, "a number > 0", positive));
  if (out.type == Light::Type::Spot) {
    const json* spot = member(l, "spot");
    const json empty = json::object();
    const json& s = spot ? object(*spot, path + ".spot") : empty;
    const double inner = number(s, "innerConeAngle", path + ".spot", 0.0, "a number in [0, pi/2)", nonNegative);
    const double outer = number(s, "outerConeAngle", path + ".spot", 0.7853981634, "a number in (0, pi/2]",
                                [](double d) { return d > 0.0 && d <= kHalfPi + 1e-6; });
    if (inner >= outer)
      fail(path + ".spot.innerConeAngle", "expected a number below outerConeAngle (" + brdfcl::detail::formatNumber(outer) +
                                              "), got " + brdfcl::detail::formatNumber(inner));
    out.innerCone = float(inner);
    out.outerCone = float(outer);
  }
  out.position = {0.0f, 0.0f, 0.0f};
  out.direction = {0.0f, 0.0f, -1.0f};
  return out;
}

}  // namespace brdfcl::gltf::detail
