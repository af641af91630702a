// Mip chains and sampling of glTF textures: linearization (sRGB for colour slots), box-filtered
// levels in linear space, KHR_texture_transform, glTF wrap and filter modes and the ray-cone
// level of detail. Conventions in docs/gltf.md, Rendering.
#include "gltf/texture.hpp"

#include <algorithm>
#include <cmath>
#include <exception>

#include "brdfcl/error.hpp"

namespace brdfcl::gltf {
namespace {

constexpr unsigned kR = 1, kG = 2, kB = 4, kA = 8, kRgb = kR | kG | kB;

// Every 16-bit code decoded once: sRGB images are sampled millions of times but built once.
const std::vector<float>& srgbTable() {
  static const std::vector<float> table = [] {
    std::vector<float> t(65536);
    for (int i = 0; i < 65536; ++i) t[i] = srgbToLinear(static_cast<float>(i) / 65535.0f);
    return t;
  }();
  return table;
}

// One box-filter step along one axis: destination texel i averages the source interval
// [i r, (i + 1) r), r = src / dst, with fractional weights at its ends, so odd sizes (r = 2 + 1/dst)
// keep every source texel's full weight.
void downsampleAxis(const std::vector<float>& src, int sw, int sh, int count, bool alongX, std::vector<float>& dst,
                    int& dw, int& dh) {
  const int n = alongX ? sw : sh;
  const int m = std::max(1, n / 2);
  dw = alongX ? m : sw;
  dh = alongX ? sh : m;
  dst.assign(static_cast<std::size_t>(dw) * dh * count, 0.0f);
  const double r = static_cast<double>(n) / m;
  for (int i = 0; i < m; ++i) {
    const double a = i * r, b = (i + 1) * r;
    for (int j = static_cast<int>(std::floor(a)); j < n && j < b; ++j) {
      const float w = static_cast<float>((std::min<double>(j + 1, b) - std::max<double>(j, a)) / r);
      if (w <= 0.0f) continue;
      if (alongX) {
        for (int y = 0; y < sh; ++y)
          for (int c = 0; c < count; ++c)
            dst[(static_cast<std::size_t>(y) * dw + i) * count + c] += w * src[(static_cast<std::size_t>(y) * sw + j) * count + c];
      } else {
        for (int x = 0; x < sw; ++x)
          for (int c = 0; c < count; ++c)
            dst[(static_cast<std::size_t>(i) * dw + x) * count + c] += w * src[(static_cast<std::size_t>(j) * sw + x) * count + c];
      }
    }
  }
}

// 8-bit codes to linear values: linear channels and sRGB colour channels.
const float* linear8() {
  static const std::array<float, 256> t = [] {
    std::array<float, 256> a{};
    for (int i = 0; i < 256; ++i) a[i] = static_cast<float>(i) / 255.0f;
    return a;
  }();
  return t.data();
}
const float* srgb8() {
  static const std::array<float, 256> t = [] {
    std::array<float, 256> a{};
    for (int i = 0; i < 256; ++i) a[i] = srgbToLinear(static_cast<float>(i) / 255.0f);
    return a;
  }();
  return t.data();
}

float linearToSrgb(float v) { return v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1.0f / 2.4f) - 0.055f; }

// Stores one level of linear values in the chain's format.
void store(const std::vector<float>& v, const MipChain& chain, bool srgbColour[4], MipChain::Level& L) {
  if (!chain.eightBit) {
    L.texels16.resize(v.size());
    for (std::size_t i = 0; i < v.size(); ++i)
      L.texels16[i] = static_cast<std::uint16_t>(std::lround(std::clamp(v[i], 0.0f, 1.0f) * 65535.0f));
    return;
  }
  L.texels8.resize(v.size());
  const std::size_t count = static_cast<std::size_t>(chain.count);
  for (std::size_t i = 0; i < v.size(); ++i) {
    const float x = std::clamp(v[i], 0.0f, 1.0f);
    L.texels8[i] = static_cast<std::uint8_t>(std::lround((srgbColour[i % count] ? linearToSrgb(x) : x) * 255.0f));
  }
}

MipChain buildChain(const Image& image, unsigned channels, ColorSpace space) {
  MipChain chain;
  chain.channels = channels;
  bool srgbColour[4] = {false, false, false, false};  // per stored channel
  for (int c = 0; c < 4; ++c)
    if (channels & (1u << c)) {
      srgbColour[chain.count] = space == ColorSpace::Srgb && c < 3;  // alpha is linear in sRGB textures too
      chain.slot[c] = chain.count++;
    }
  const int count = chain.count;
  const std::size_t texels = static_cast<std::size_t>(image.width) * image.height;
  chain.eightBit = std::all_of(image.rgba.begin(), image.rgba.end(), [](std::uint16_t v) { return v % 257 == 0; });
  for (int k = 0; k < count; ++k) chain.decode8[k] = srgbColour[k] ? srgb8() : linear8();
  const std::vector<float>& srgb = srgbTable();
  int w = image.width, h = image.height;
  std::vector<float> level(texels * count);
  MipChain::Level L0{w, h, {}, {}};
  if (chain.eightBit) L0.texels8.resize(texels * count);
  for (std::size_t t = 0; t < texels; ++t)
    for (int c = 0; c < 4; ++c)
      if (chain.slot[c] >= 0) {
        const int k = chain.slot[c];
        const std::uint16_t code = image.rgba[t * 4 + c];
        level[t * count + k] = srgbColour[k] ? srgb[code] : static_cast<float>(code) / 65535.0f;
        if (chain.eightBit) L0.texels8[t * count + k] = static_cast<std::uint8_t>(code / 257);
      }
  if (!chain.eightBit) store(level, chain, srgbColour, L0);
  chain.levels.push_back(std::move(L0));
  chain.log2Size = 0.5f * std::log2(static_cast<float>(w) * h);
  std::vector<float> tmp, next;
  while (w > 1 || h > 1) {
    int tw = w, th = h, nw = w, nh = h;
    if (w > 1) {
      downsampleAxis(level, w, h, count, true, tmp, tw, th);
    } else {
      tmp = level;
    }
    if (th > 1) {
      downsampleAxis(tmp, tw, th, count, false, next, nw, nh);
    } else {
      next = tmp;
      nw = tw;
      nh = th;
    }
    level.swap(next);
    w = nw;
    h = nh;
    MipChain::Level L{w, h, {}, {}};
    store(level, chain, srgbColour, L);
    chain.levels.push_back(std::move(L));
  }
  return chain;
}

int wrapIndex(int i, int n, Wrap mode) {
  if (i >= 0 && i < n) return i;
  switch (mode) {
    case Wrap::ClampToEdge:
      return std::clamp(i, 0, n - 1);
    case Wrap::MirroredRepeat: {
      int k = i % (2 * n);
      if (k < 0) k += 2 * n;
      return k < n ? k : 2 * n - 1 - k;
    }
    case Wrap::Repeat:
    default: {
      int k = i % n;
      return k < 0 ? k + n : k;
    }
  }
}

// Texel coordinates far outside the image only matter modulo the (mirrored) period; bounding
// them keeps the float -> int conversion defined.
float boundCoord(float x) { return std::clamp(x, -1.0e8f, 1.0e8f); }

// The index after wrapIndex(i) under the same mode, without a second division.
int nextIndex(int wrapped, int i, int n, Wrap mode) {
  if (mode == Wrap::Repeat) return wrapped + 1 == n ? 0 : wrapped + 1;
  if (mode == Wrap::ClampToEdge) return std::min(std::max(i + 1, 0), n - 1);
  return wrapIndex(i + 1, n, mode);
}

// Texel decoders: 16-bit unorm, or an 8-bit code through its channel's table.
struct Decode16 {
  float operator()(int, std::uint16_t v) const { return v * (1.0f / 65535.0f); }
};
struct Decode8 {
  const std::array<const float*, 4>& table;
  float operator()(int c, std::uint8_t v) const { return table[c][v]; }
};

template <int Count, typename T, typename Decode>
void blend(const T* t00, const T* t10, const T* t01, const T* t11, float fx, float fy, const Decode& d, float* out) {
  for (int c = 0; c < Count; ++c) {
    const float a = d(c, t00[c]), b = d(c, t10[c]), e = d(c, t01[c]), f = d(c, t11[c]);
    const float top = a + fx * (b - a), bottom = e + fx * (f - e);
    out[c] = top + fy * (bottom - top);
  }
}

template <typename T, typename Decode>
void fetchFrom(const T* base, const MipChain& chain, const MipChain::Level& L, const Sampler& s, bool nearest, float u,
               float v, const Decode& d, float out[4]) {
  const int count = chain.count;
  if (nearest) {
    const int i = wrapIndex(static_cast<int>(std::floor(boundCoord(u * L.width))), L.width, s.wrapS);
    const int j = wrapIndex(static_cast<int>(std::floor(boundCoord(v * L.height))), L.height, s.wrapT);
    const T* t = base + (static_cast<std::size_t>(j) * L.width + i) * count;
    for (int c = 0; c < count; ++c) out[c] = d(c, t[c]);
    return;
  }
  const float x = boundCoord(u * L.width - 0.5f), y = boundCoord(v * L.height - 0.5f);
  const float x0 = std::floor(x), y0 = std::floor(y);
  const float fx = x - x0, fy = y - y0;
  const int i = static_cast<int>(x0), j = static_cast<int>(y0);
  const int i0 = wrapIndex(i, L.width, s.wrapS), i1 = nextIndex(i0, i, L.width, s.wrapS);
  const int j0 = wrapIndex(j, L.height, s.wrapT), j1 = nextIndex(j0, j, L.height, s.wrapT);
  const T* r0 = base + static_cast<std::size_t>(j0) * L.width * count;
  const T* r1 = base + static_cast<std::size_t>(j1) * L.width * count;
  const T *t00 = r0 + i0 * count, *t10 = r0 + i1 * count, *t01 = r1 + i0 * count, *t11 = r1 + i1 * count;
  switch (count) {
    case 1: return blend<1>(t00, t10, t01, t11, fx, fy, d, out);
    case 2: return blend<2>(t00, t10, t01, t11, fx, fy, d, out);
    case 3: return blend<3>(t00, t10, t01, t11, fx, fy, d, out);
    default: return blend<4>(t00, t10, t01, t11, fx, fy, d, out);
  }
}

void fetch(const MipChain& chain, int level, const Sampler& s, bool nearest, float u, float v, float out[4]) {
  const MipChain::Level& L = chain.levels[level];
  if (chain.eightBit)
    fetchFrom(L.texels8.data(), chain, L, s, nearest, u, v, Decode8{chain.decode8}, out);
  else
    fetchFrom(L.texels16.data(), chain, L, s, nearest, u, v, Decode16{}, out);
}

}  // namespace

float srgbToLinear(float c) {
  return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

std::size_t MipChain::bytes() const {
  std::size_t b = 0;
  for (const Level& L : levels) b += L.texels16.size() * sizeof(std::uint16_t) + L.texels8.size();
  return b;
}

Textures::Textures(const Asset& asset) : textures_(asset.textures), samplers_(asset.samplers) {
  const int nImages = static_cast<int>(asset.images.size());
  std::vector<unsigned> need(2 * asset.images.size(), 0u);
  for (std::size_t mi = 0; mi < asset.materials.size(); ++mi) {
    const Material& m = asset.materials[mi];
    auto use = [&](const TextureRef& ref, const char* slot, ColorSpace space, unsigned channels) {
      if (!ref.present()) return;
      if (ref.texture >= static_cast<int>(asset.textures.size()))
        throw Error("materials[" + std::to_string(mi) + "]." + slot + ": texture " + std::to_string(ref.texture) +
                    " does not exist (the asset has " + std::to_string(asset.textures.size()) + ")");
      const Texture& t = asset.textures[ref.texture];
      if (t.image < 0 || t.image >= nImages)
        throw Error("textures[" + std::to_string(ref.texture) + "]: image " + std::to_string(t.image) +
                    " does not exist (the asset has " + std::to_string(nImages) + ")");
      if (t.sampler >= static_cast<int>(asset.samplers.size()))
        throw Error("textures[" + std::to_string(ref.texture) + "]: sampler " + std::to_string(t.sampler) +
                    " does not exist (the asset has " + std::to_string(asset.samplers.size()) + ")");
      const Image& img = asset.images[t.image];
      if (img.width <= 0 || img.height <= 0 ||
          img.rgba.size() != static_cast<std::size_t>(img.width) * img.height * 4)
        throw Error("images[" + std::to_string(t.image) + "] '" + img.name + "': " + std::to_string(img.rgba.size()) +
                    " values for " + std::to_string(img.width) + "x" + std::to_string(img.height) + " RGBA texels");
      need[2 * t.image + static_cast<int>(space)] |= channels;
    };
    use(m.baseColorTexture, "baseColorTexture", ColorSpace::Srgb, kRgb | (m.alphaMode != AlphaMode::Opaque ? kA : 0u));
    use(m.metallicRoughnessTexture, "metallicRoughnessTexture", ColorSpace::Linear, kG | kB);
    use(m.normalTexture, "normalTexture", ColorSpace::Linear, kRgb);
    use(m.occlusionTexture, "occlusionTexture", ColorSpace::Linear, kR);
    use(m.emissiveTexture, "emissiveTexture", ColorSpace::Srgb, kRgb);
    use(m.sheenColorTexture, "sheenColorTexture", ColorSpace::Srgb, kRgb);
    use(m.sheenRoughnessTexture, "sheenRoughnessTexture", ColorSpace::Linear, kA);
    use(m.clearcoatTexture, "clearcoatTexture", ColorSpace::Linear, kR);
    use(m.clearcoatRoughnessTexture, "clearcoatRoughnessTexture", ColorSpace::Linear, kG);
    use(m.clearcoatNormalTexture, "clearcoatNormalTexture", ColorSpace::Linear, kRgb);
    use(m.anisotropyTexture, "anisotropyTexture", ColorSpace::Linear, kRgb);
  }
  chains_.resize(need.size());
  // Chains are independent: build them on every core (7 chains of 2048^2 take seconds on one),
  // one at a time to whichever thread is free. An exception must not leave the OpenMP region:
  // each chain's is kept, and the first in the chains' order rethrown after it.
  std::vector<std::exception_ptr> failures(need.size());
  const long count = long(need.size());
#pragma omp parallel for schedule(dynamic, 1)
  for (long k = 0; k < count; ++k) {
    if (!need[std::size_t(k)]) continue;
    try {
      chains_[std::size_t(k)] =
          buildChain(asset.images[std::size_t(k) / 2], need[std::size_t(k)], static_cast<ColorSpace>(k % 2));
    } catch (...) {
      failures[std::size_t(k)] = std::current_exception();
    }
  }
  for (const std::exception_ptr& e : failures)
    if (e) std::rethrow_exception(e);
}

std::size_t Textures::bytes() const {
  std::size_t b = 0;
  for (const MipChain& c : chains_) b += c.bytes();
  return b;
}

std::array<float, 4> Textures::sample(const TextureRef& ref, ColorSpace space, float u, float v, float coneLod) const {
  const Texture& tex = textures_[ref.texture];
  const MipChain& chain = chains_[2 * tex.image + static_cast<int>(space)];
  static const Sampler kDefault;
  const Sampler& s = tex.sampler >= 0 ? samplers_[tex.sampler] : kDefault;

  const TextureTransform& tr = ref.transform;
  const float x = tr.scale[0] * u, y = tr.scale[1] * v;
  float ut = x + tr.offset[0], vt = y + tr.offset[1];
  if (tr.rotation != 0.0f) {
    const float c = std::cos(tr.rotation), sn = std::sin(tr.rotation);
    ut = c * x + sn * y + tr.offset[0];
    vt = -sn * x + c * y + tr.offset[1];
  }
  const float scaleArea = std::fabs(tr.scale[0] * tr.scale[1]);
  const float lod = coneLod + chain.log2Size + (scaleArea != 1.0f ? 0.5f * std::log2(scaleArea) : 0.0f);
  float vals[4] = {0, 0, 0, 0};
  const int last = static_cast<int>(chain.levels.size()) - 1;
  if (!(lod > 0.0f)) {  // magnification (NaN included)
    fetch(chain, 0, s, s.magNearest, ut, vt, vals);
  } else if (!s.mipmaps) {
    fetch(chain, 0, s, s.minNearest, ut, vt, vals);
  } else if (s.mipNearest) {
    fetch(chain, std::min(last, static_cast<int>(std::lround(lod))), s, s.minNearest, ut, vt, vals);
  } else {
    const float l = std::min(lod, static_cast<float>(last));
    const int l0 = static_cast<int>(std::floor(l)), l1 = std::min(last, l0 + 1);
    const float f = l - l0;
    fetch(chain, l0, s, s.minNearest, ut, vt, vals);
    if (f > 0.0f && l1 != l0) {
      float upper[4];
      fetch(chain, l1, s, s.minNearest, ut, vt, upper);
      for (int k = 0; k < chain.count; ++k) vals[k] += f * (upper[k] - vals[k]);
    }
  }
  std::array<float, 4> out{0.0f, 0.0f, 0.0f, 1.0f};
  for (int k = 0; k < 4; ++k)
    if (chain.slot[k] >= 0) out[k] = vals[chain.slot[k]];
  return out;
}

}  // namespace brdfcl::gltf
