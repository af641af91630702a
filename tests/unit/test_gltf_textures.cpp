// Texture decoding through the whole ray caster: a quad exactly covered by an orthographic
// camera, one pixel per texel, so every G-buffer value must equal its texel times the factors,
// with the expected values computed here (own sRGB decode, transform, wrap and normal maths).
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "gltf_support.hpp"

namespace brdfcl::test {
namespace {

using namespace brdfcl::gltf;

constexpr int kN = 4;  // image and texture size: pixel (x, y) sees texel (x, y)
constexpr double kTol = 1e-4;

int texel(int x, int y, int c) { return (x * 53 + y * 97 + c * 31 + 11) % 256; }
double unit(int x, int y, int c) { return texel(x, y, c) / 255.0; }

Sampler nearest(Wrap s = Wrap::Repeat, Wrap t = Wrap::Repeat) {
  Sampler sm;
  sm.magNearest = sm.minNearest = true;
  sm.mipmaps = false;
  sm.wrapS = s;
  sm.wrapT = t;
  return sm;
}

// A quad over [-1, 1]^2 with material 0, one texture (0) of the texel() image, nearest sampler.
Asset texturedQuad(const Material& m, int size = kN) {
  Asset a;
  a.primitives.push_back(quad(-1, -1, 1, 1, 0, 0));
  a.materials.push_back(m);
  a.images.push_back(image(size, size, texel));
  a.samplers.push_back(nearest());
  a.textures.push_back({0, 0});
  a.cameras.push_back(frontOrtho());
  a.boundsMin = {-1, -1, 0};
  a.boundsMax = {1, 1, 0};
  return a;
}

TextureRef ref(int texCoord = 0, float value = 1.0f) {
  TextureRef r;
  r.texture = 0;
  r.texCoord = texCoord;
  r.value = value;
  return r;
}

GBuffer render(const Asset& a, int n = kN) {
  Raycaster rc(a);
  const View v = chooseView(a, "", n, n);
  GBuffer g = rc.trace(v, n, n);
  expectValid(g);
  return g;
}

TEST(GltfTextures, BaseColorIsSrgbTexelTimesFactorTimesColor0) {
  Material m;
  m.baseColorFactor = {0.5f, 0.8f, 1.0f, 1.0f};
  m.baseColorTexture = ref();
  Asset a = texturedQuad(m);
  const float color[4] = {0.5f, 1.0f, 0.25f, 1.0f};
  for (int v = 0; v < 4; ++v) a.primitives[0].color0.insert(a.primitives[0].color0.end(), color, color + 4);
  const GBuffer g = render(a);
  for (int y = 0; y < kN; ++y)
    for (int x = 0; x < kN; ++x) {
      const std::size_t i = std::size_t(y) * kN + x;
      ASSERT_EQ(g.mask[i], 1.0f);
      for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(g.baseColor[3 * i + c], m.baseColorFactor[c] * srgbDecode(unit(x, y, c)) * color[c], kTol)
            << x << "," << y << " channel " << c;
    }
}

TEST(GltfTextures, MetallicRoughnessAndOcclusionAreLinear) {
  Material m;
  m.metallicFactor = 0.7f;
  m.roughnessFactor = 0.6f;
  m.metallicRoughnessTexture = ref();
  m.occlusionTexture = ref(0, 0.8f);
  const GBuffer g = render(texturedQuad(m));
  for (int y = 0; y < kN; ++y)
    for (int x = 0; x < kN; ++x) {
      const std::size_t i = std::size_t(y) * kN + x;
      EXPECT_NEAR(g.metallic[i], 0.7 * unit(x, y, 2), kTol);
      EXPECT_NEAR(g.roughness[i], 0.6 * unit(x, y, 1), kTol);
      EXPECT_NEAR(g.occlusion[i], 1.0 + 0.8 * (unit(x, y, 0) - 1.0), kTol);
    }
}

TEST(GltfTextures, EmissiveIsSrgbTimesFactorTimesStrength) {
  Material m;
  m.emissiveFactor = {1.0f, 0.5f, 0.25f};
  m.emissiveStrength = 3.0f;
  m.emissiveTexture = ref();
  const GBuffer g = render(texturedQuad(m));
  for (int y = 0; y < kN; ++y)
    for (int x = 0; x < kN; ++x) {
      const std::size_t i = std::size_t(y) * kN + x;
      for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(g.emissive[3 * i + c], 3.0 * m.emissiveFactor[c] * srgbDecode(unit(x, y, c)), 3 * kTol);
    }
}

TEST(GltfTextures, SheenColorSrgbAndSheenRoughnessAlpha) {
  Material m;
  m.sheenColorFactor = {0.9f, 0.5f, 0.3f};
  m.sheenColorTexture = ref();
  m.sheenRoughnessFactor = 0.75f;
  m.sheenRoughnessTexture = ref();
  const GBuffer g = render(texturedQuad(m));
  for (int y = 0; y < kN; ++y)
    for (int x = 0; x < kN; ++x) {
      const std::size_t i = std::size_t(y) * kN + x;
      for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(g.sheenColor[3 * i + c], m.sheenColorFactor[c] * srgbDecode(unit(x, y, c)), kTol);
      EXPECT_NEAR(g.sheenRoughness[i], 0.75 * unit(x, y, 3), kTol);
    }
}

TEST(GltfTextures, ClearcoatRedAndClearcoatRoughnessGreen) {
  Material m;
  m.clearcoatFactor = 0.9f;
  m.clearcoatTexture = ref();
  m.clearcoatRoughnessFactor = 0.4f;
  m.clearcoatRoughnessTexture = ref();
  const GBuffer g = render(texturedQuad(m));
  for (int y = 0; y < kN; ++y)
    for (int x = 0; x < kN; ++x) {
      const std::size_t i = std::size_t(y) * kN + x;
      EXPECT_NEAR(g.clearcoat[i], 0.9 * unit(x, y, 0), kTol);
      EXPECT_NEAR(g.clearcoatRoughness[i], 0.4 * unit(x, y, 1), kTol);
      // Without a clearcoat normal map the coat follows the geometry.
      EXPECT_NEAR(g.clearcoatN[3 * i + 2], 1.0, 1e-6);
    }
}

TEST(GltfTextures, FactorsOutsideTheirDomainAreClamped) {
  Material m;
  m.metallicFactor = 1.5f;
  m.roughnessFactor = -0.5f;
  m.clearcoatFactor = 2.0f;
  const GBuffer g = render(texturedQuad(m));
  EXPECT_EQ(g.metallic[0], 1.0f);
  EXPECT_EQ(g.roughness[0], 0.0f);
  EXPECT_EQ(g.clearcoat[0], 1.0f);
}

// The quad's frame: N = +Z, T = +X and, for glTF's v running down the image, B = +Y.
std::array<double, 3> mapped(int x, int y, double scale, std::array<double, 3> T, std::array<double, 3> B,
                             std::array<double, 3> N) {
  double n[3] = {(2 * unit(x, y, 0) - 1) * scale, (2 * unit(x, y, 1) - 1) * scale, 2 * unit(x, y, 2) - 1};
  std::array<double, 3> r;
  for (int k = 0; k < 3; ++k) r[k] = T[k] * n[0] + B[k] * n[1] + N[k] * n[2];
  const double l = std::sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]);
  for (double& c : r) c /= l;
  return r;
}

bool onEdgeOf(double coord) {
  const double f = coord * kN - std::floor(coord * kN);
  return f < 1e-3 || f > 1 - 1e-3;
}

void expectVec(const std::vector<float>& v, std::size_t i, const std::array<double, 3>& e, const char* what) {
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(v[3 * i + k], e[k], 2e-4) << what << " pixel " << i << " axis " << k;
}

TEST(GltfTextures, NormalMapTiltsTheNormalInTheUvFrame) {
  Material m;
  m.normalTexture = ref(0, 0.7f);
  for (int variant = 0; variant < 3; ++variant) {
    Asset a = texturedQuad(m);
    // 0: generated from the UV derivative; 1: TANGENT +X with w = +1; 2: w = -1 flips B.
    if (variant > 0) {
      const float w = variant == 1 ? 1.0f : -1.0f;
      a.primitives[0].tangents = {1, 0, 0, w, 1, 0, 0, w, 1, 0, 0, w, 1, 0, 0, w};
    }
    const double b = variant == 2 ? -1.0 : 1.0;
    const GBuffer g = render(a);
    for (int y = 0; y < kN; ++y)
      for (int x = 0; x < kN; ++x) {
        const std::size_t i = std::size_t(y) * kN + x;
        const auto e = mapped(x, y, 0.7, {1, 0, 0}, {0, b, 0}, {0, 0, 1});
        SCOPED_TRACE("variant " + std::to_string(variant));
        expectVec(g.N, i, e, "N");
        expectVec(g.clearcoatN, i, {0, 0, 1}, "clearcoatN");
        // T: +X made perpendicular to the mapped normal.
        std::array<double, 3> t{1 - e[0] * e[0], -e[0] * e[1], -e[0] * e[2]};
        const double l = std::sqrt(t[0] * t[0] + t[1] * t[1] + t[2] * t[2]);
        for (double& c : t) c /= l;
        expectVec(g.T, i, t, "T");
      }
  }
}

TEST(GltfTextures, GeneratedTangentsFollowTheNormalMapsTransform) {
  // Rotating the UVs by 90 degrees (u' = v, v' = -u) turns the texture's +u' to the quad's -Y
  // (+v) and its -v' (image up) to +X (+u).
  Material m;
  m.normalTexture = ref(0, 1.0f);
  m.normalTexture.transform.rotation = float(M_PI / 2);
  const GBuffer g = render(texturedQuad(m), 16);
  int checked = 0;
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 16; ++x) {
      const double u = (x + 0.5) / 16, v = (y + 0.5) / 16;
      const double ut = v, vt = -u;
      if (onEdgeOf(ut) || onEdgeOf(vt)) continue;
      const int tx = ((int(std::floor(ut * kN)) % kN) + kN) % kN, ty = ((int(std::floor(vt * kN)) % kN) + kN) % kN;
      expectVec(g.N, std::size_t(y) * 16 + x, mapped(tx, ty, 1.0, {0, -1, 0}, {1, 0, 0}, {0, 0, 1}), "N");
      ++checked;
    }
  EXPECT_GT(checked, 100);
}

TEST(GltfTextures, ClearcoatNormalMapHasItsOwnScaleAndLeavesNAlone) {
  Material m;
  m.clearcoatFactor = 1.0f;
  m.clearcoatNormalTexture = ref(0, 0.5f);
  const GBuffer g = render(texturedQuad(m));
  for (int y = 0; y < kN; ++y)
    for (int x = 0; x < kN; ++x) {
      const std::size_t i = std::size_t(y) * kN + x;
      expectVec(g.clearcoatN, i, mapped(x, y, 0.5, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}), "clearcoatN");
      expectVec(g.N, i, {0, 0, 1}, "N");
    }
}

TEST(GltfTextures, AnisotropyTextureDirectionAndStrength) {
  Material m;
  m.anisotropyStrength = 0.8f;
  m.anisotropyRotation = 0.3f;
  m.anisotropyTexture = ref();
  for (float w : {1.0f, -1.0f}) {
    Asset a = texturedQuad(m);
    a.primitives[0].tangents = {1, 0, 0, w, 1, 0, 0, w, 1, 0, 0, w, 1, 0, 0, w};
    const GBuffer g = render(a);
    for (int y = 0; y < kN; ++y)
      for (int x = 0; x < kN; ++x) {
        const std::size_t i = std::size_t(y) * kN + x;
        const double dx = 2 * unit(x, y, 0) - 1, dy = 2 * unit(x, y, 1) - 1;
        EXPECT_NEAR(g.anisotropyStrength[i], 0.8 * unit(x, y, 2), kTol);
        // The shader measures the angle from T towards N x T = +Y; the file's B is w (N x T).
        EXPECT_NEAR(g.anisotropyRotation[i], w * (0.3 + std::atan2(dy, dx)), 2e-4) << "w " << w << " pixel " << i;
        expectVec(g.T, i, {1, 0, 0}, "T");
      }
  }
}

TEST(GltfTextures, AnisotropyWithoutTextureUsesTheFactors) {
  Material m;
  m.anisotropyStrength = 0.5f;
  m.anisotropyRotation = 1.0f;
  const GBuffer g = render(texturedQuad(m));
  EXPECT_NEAR(g.anisotropyStrength[5], 0.5, 1e-6);
  EXPECT_NEAR(g.anisotropyRotation[5], 1.0, 1e-6);
}

// Nearest texel of the transformed uv, wrapped per axis, computed independently.
int wrapped(double coord, int n, Wrap mode) {
  int i = int(std::floor(coord * n));
  if (mode == Wrap::ClampToEdge) return std::min(std::max(i, 0), n - 1);
  if (mode == Wrap::Repeat) return ((i % n) + n) % n;
  int k = ((i % (2 * n)) + 2 * n) % (2 * n);
  return k < n ? k : 2 * n - 1 - k;
}

// True when coord sits within 1e-3 texel of a texel edge, where float rounding may pick either.
bool onEdge(double coord, int n) {
  const double f = coord * n - std::floor(coord * n);
  return f < 1e-3 || f > 1 - 1e-3;
}

TEST(GltfTextures, TextureTransformOffsetRotationScaleOnTexCoord1) {
  constexpr int kPixels = 24;
  Material m;
  m.metallicRoughnessTexture = ref(1);
  m.metallicRoughnessTexture.transform.offset = {0.1f, 0.2f};
  m.metallicRoughnessTexture.transform.rotation = 0.3f;
  m.metallicRoughnessTexture.transform.scale = {1.5f, 0.75f};
  Asset a = texturedQuad(m);
  // TEXCOORD_1 mirrors u, so reading TEXCOORD_0 by mistake shows.
  a.primitives[0].uv1 = {1, 0, 0, 0, 1, 1, 0, 1};
  const GBuffer g = render(a, kPixels);
  int checked = 0;
  for (int y = 0; y < kPixels; ++y)
    for (int x = 0; x < kPixels; ++x) {
      const double u = 1.0 - (x + 0.5) / kPixels, v = (y + 0.5) / kPixels;
      const double c = std::cos(0.3), s = std::sin(0.3);
      const double su = 1.5 * u, sv = 0.75 * v;
      // KHR_texture_transform: rotation [cos sin; -sin cos], after the scale, before the offset.
      const double ut = c * su + s * sv + 0.1, vt = -s * su + c * sv + 0.2;
      if (onEdge(ut, kN) || onEdge(vt, kN)) continue;
      const int tx = wrapped(ut, kN, Wrap::Repeat), ty = wrapped(vt, kN, Wrap::Repeat);
      const std::size_t i = std::size_t(y) * kPixels + x;
      EXPECT_NEAR(g.metallic[i], unit(tx, ty, 2), kTol) << x << "," << y;
      EXPECT_NEAR(g.roughness[i], unit(tx, ty, 1), kTol) << x << "," << y;
      ++checked;
    }
  EXPECT_GT(checked, kPixels * kPixels / 2);
}

TEST(GltfTextures, WrapModesPerAxis) {
  constexpr int kPixels = 24;
  const Wrap modes[3] = {Wrap::Repeat, Wrap::ClampToEdge, Wrap::MirroredRepeat};
  for (Wrap ws : modes)
    for (Wrap wt : modes) {
      Material m;
      m.metallicRoughnessTexture = ref();
      Asset a = texturedQuad(m);
      a.samplers[0] = nearest(ws, wt);
      // uv from -1.1 to 1.9 across the quad: two and a bit periods on each axis.
      a.primitives[0].uv0 = {-1.1f, -1.1f, 1.9f, -1.1f, -1.1f, 1.9f, 1.9f, 1.9f};
      const GBuffer g = render(a, kPixels);
      for (int y = 0; y < kPixels; ++y)
        for (int x = 0; x < kPixels; ++x) {
          const double u = -1.1 + 3.0 * (x + 0.5) / kPixels, v = -1.1 + 3.0 * (y + 0.5) / kPixels;
          if (onEdge(u, kN) || onEdge(v, kN)) continue;
          const int tx = wrapped(u, kN, ws), ty = wrapped(v, kN, wt);
          const std::size_t i = std::size_t(y) * kPixels + x;
          ASSERT_NEAR(g.roughness[i], unit(tx, ty, 1), kTol)
              << "wrap " << int(ws) << "/" << int(wt) << " pixel " << x << "," << y;
        }
    }
}

// Alpha per texel: a checkerboard of 0.2 and 0.9 (times COLOR_0 alpha where given).
Asset cutoutScene(AlphaMode mode, float cutoff, bool behind) {
  Material front;
  front.alphaMode = mode;
  front.alphaCutoff = cutoff;
  front.baseColorFactor = {1, 0, 0, 1};
  front.baseColorTexture = ref();
  Asset a = texturedQuad(front);
  a.images[0] = image(kN, kN, [](int x, int y, int c) { return c < 3 ? 255 : ((x + y) % 2 ? 230 : 51); });
  if (behind) {
    Material back;
    back.baseColorFactor = {0, 1, 0, 1};
    a.materials.push_back(back);
    a.primitives.push_back(quad(-1, -1, 1, 1, -1, 1));
    a.boundsMin[2] = -1;
  }
  return a;
}

TEST(GltfTextures, MaskCutoffLetsRaysThrough) {
  for (bool behind : {true, false}) {
    const GBuffer g = render(cutoutScene(AlphaMode::Mask, 0.5f, behind));
    for (int y = 0; y < kN; ++y)
      for (int x = 0; x < kN; ++x) {
        const std::size_t i = std::size_t(y) * kN + x;
        const bool opaque = (x + y) % 2 == 1;  // alpha 0.9
        if (opaque) {
          EXPECT_EQ(g.mask[i], 1.0f);
          EXPECT_NEAR(g.P[3 * i + 2], 0.0, 1e-6);
          EXPECT_NEAR(g.baseColor[3 * i], 1.0, kTol);
        } else if (behind) {
          EXPECT_EQ(g.mask[i], 1.0f);
          EXPECT_NEAR(g.P[3 * i + 2], -1.0, 1e-6) << "pixel " << i << " sees the cut-out surface";
          EXPECT_NEAR(g.baseColor[3 * i + 1], 1.0, kTol);
        } else {
          EXPECT_EQ(g.mask[i], 0.0f) << "pixel " << i;
        }
      }
  }
  // A cutoff below both alphas keeps the whole quad.
  const GBuffer g = render(cutoutScene(AlphaMode::Mask, 0.1f, false));
  for (float v : g.mask) EXPECT_EQ(v, 1.0f);
}

TEST(GltfTextures, BlendIsOpaqueFromHalfAlpha) {
  // alphaCutoff does not apply to BLEND: 0.95 would cut everything under MASK.
  const GBuffer g = render(cutoutScene(AlphaMode::Blend, 0.95f, false));
  for (int y = 0; y < kN; ++y)
    for (int x = 0; x < kN; ++x) EXPECT_EQ(g.mask[std::size_t(y) * kN + x], (x + y) % 2 ? 1.0f : 0.0f);
}

TEST(GltfTextures, Color0AlphaTakesPartInTheCutoff) {
  Asset a = cutoutScene(AlphaMode::Mask, 0.5f, false);
  for (int v = 0; v < 4; ++v) a.primitives[0].color0.insert(a.primitives[0].color0.end(), {1.0f, 1.0f, 1.0f, 0.5f});
  const GBuffer g = render(a);  // 0.9 * 0.5 < 0.5: nothing left
  for (float v : g.mask) EXPECT_EQ(v, 0.0f);
}

TEST(GltfTextures, SingleSidedBackFacesAreCulled) {
  Material m;
  Asset a = texturedQuad(m);
  a.primitives[0] = quad(-1, -1, 1, 1, 0, 0, /*frontPlusZ=*/false);
  GBuffer g = render(a);
  for (float v : g.mask) EXPECT_EQ(v, 0.0f);
  // The same quad facing the camera is seen.
  a.primitives[0] = quad(-1, -1, 1, 1, 0, 0, true);
  g = render(a);
  for (float v : g.mask) EXPECT_EQ(v, 1.0f);
}

TEST(GltfTextures, DoubleSidedBackFacesTurnTheFrameToTheViewer) {
  Material m;
  m.doubleSided = true;
  m.normalTexture = ref(0, 1.0f);
  for (bool tangents : {false, true}) {
    Asset a = texturedQuad(m);
    a.primitives[0] = quad(-1, -1, 1, 1, 0, 0, /*frontPlusZ=*/false);
    // The TANGENT that matches the UVs: +X, and w = -1 since B (image up, +Y) = -(N x T) for N = -Z.
    if (tangents) a.primitives[0].tangents = {1, 0, 0, -1, 1, 0, 0, -1, 1, 0, 0, -1, 1, 0, 0, -1};
    const GBuffer g = render(a);
    for (int y = 0; y < kN; ++y)
      for (int x = 0; x < kN; ++x) {
        const std::size_t i = std::size_t(y) * kN + x;
        ASSERT_EQ(g.mask[i], 1.0f);
        // Seen from behind, the frame of the front face (T +X, B +Y, N -Z) is negated whole:
        // T -X, B -Y, N +Z.
        SCOPED_TRACE(tangents ? "TANGENT" : "generated");
        expectVec(g.N, i, mapped(x, y, 1.0, {-1, 0, 0}, {0, -1, 0}, {0, 0, 1}), "N");
        expectVec(g.clearcoatN, i, {0, 0, 1}, "clearcoatN");
      }
  }
}

TEST(GltfTextures, SixteenBitImagesKeepTheirPrecision) {
  Material m;
  m.baseColorTexture = ref();
  m.metallicRoughnessTexture = ref();
  Asset a = texturedQuad(m);
  auto code = [](int x, int y, int c) { return (x * 4099 + y * 12345 + c * 777 + 1) % 65536; };
  a.images[0].bits = 16;
  for (int y = 0; y < kN; ++y)
    for (int x = 0; x < kN; ++x)
      for (int c = 0; c < 4; ++c) a.images[0].rgba[(std::size_t(y) * kN + x) * 4 + c] = std::uint16_t(code(x, y, c));
  const GBuffer g = render(a);
  for (int y = 0; y < kN; ++y)
    for (int x = 0; x < kN; ++x) {
      const std::size_t i = std::size_t(y) * kN + x;
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(g.baseColor[3 * i + c], srgbDecode(code(x, y, c) / 65535.0), 2e-5);
      EXPECT_NEAR(g.roughness[i], code(x, y, 1) / 65535.0, 2e-5);
    }
}

TEST(GltfTextures, OddSizedImageMipsDownToItsMean) {
  Material m;
  m.metallicRoughnessTexture = ref();
  Asset a = texturedQuad(m);
  a.images[0] = image(3, 5, texel);
  a.samplers[0] = Sampler{};  // LINEAR_MIPMAP_LINEAR
  // Tiled 100 times: the footprint covers the whole image, so the 1x1 level is read.
  for (float& uv : a.primitives[0].uv0) uv *= 100.0f;
  double mean = 0;
  for (int y = 0; y < 5; ++y)
    for (int x = 0; x < 3; ++x) mean += unit(x, y, 1) / 15.0;
  const GBuffer g = render(a);
  for (float r : g.roughness) EXPECT_NEAR(r, mean, 0.5 / 255.0 + 1e-6);
}

TEST(GltfTextures, RaycasterOutlivesItsAsset) {
  Material m;
  m.baseColorTexture = ref();
  m.baseColorFactor = {0.5f, 1.0f, 1.0f, 1.0f};
  std::unique_ptr<Raycaster> rc;
  View v;
  {
    const Asset a = texturedQuad(m);
    rc = std::make_unique<Raycaster>(a);
    v = chooseView(a, "", kN, kN);
  }
  const GBuffer g = rc->trace(v, kN, kN);
  expectValid(g);
  EXPECT_NEAR(g.baseColor[3 * 5], 0.5 * srgbDecode(unit(1, 1, 0)), kTol);
}

TEST(GltfTextures, NonexistentTextureIsAnError) {
  Material m;
  m.baseColorTexture.texture = 3;
  EXPECT_THROW(Raycaster{texturedQuad(m)}, brdfcl::Error);
}

}  // namespace
}  // namespace brdfcl::test
