// Primary rays through a glTF asset with Embree 3: one triangle geometry per primitive, an
// intersection filter for back-face culling and alpha cut-outs, tiles of 4x4 ray packets traced
// on several threads, hits decoded into the G-buffer by Surfaces.
#include <embree3/rtcore.h>

#include <algorithm>
#include <array>
#include <exception>
#include <cmath>
#include <limits>
#include <vector>
#include <utility>

#include "brdfcl/error.hpp"
#include "brdfcl/gltf_render.hpp"
#include "gltf/surface.hpp"
#include "gltf/texture.hpp"
#include "io/vec3.hpp"

namespace brdfcl::gltf {

using ::brdfcl::detail::norm;
using ::brdfcl::detail::toVec3;

namespace {

// Embree hands the filter the context it was given, so the cone travels with each ray.
struct RayContext {
  RTCIntersectContext embree;
  const Surfaces* surfaces = nullptr;
  bool orthographic = false;
  float coneSpread = 0.0f;  // perspective: width per unit distance along the ray
  float coneWidth = 0.0f;   // orthographic: constant width
};

void filterHit(const RTCFilterFunctionNArguments* args) {
  const RayContext* rc = reinterpret_cast<const RayContext*>(args->context);
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] != -1) continue;
    Hit h;
    h.prim = static_cast<int>(RTCHitN_geomID(args->hit, args->N, i));
    h.tri = RTCHitN_primID(args->hit, args->N, i);
    h.u = RTCHitN_u(args->hit, args->N, i);
    h.v = RTCHitN_v(args->hit, args->N, i);
    h.dir = {RTCRayN_dir_x(args->ray, args->N, i), RTCRayN_dir_y(args->ray, args->N, i),
             RTCRayN_dir_z(args->ray, args->N, i)};
    const float t = RTCRayN_tfar(args->ray, args->N, i);
    h.coneWidth = rc->orthographic ? rc->coneWidth : t * rc->coneSpread;
    if (!rc->surfaces->accepts(h)) args->valid[i] = 0;
  }
}

}  // namespace

struct Raycaster::State {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  Asset geometry;  // primitives and materials only: the images live on as mip chains
  std::unique_ptr<Textures> textures;
  std::unique_ptr<Surfaces> surfaces;
  ~State() {
    if (scene) rtcReleaseScene(scene);
    if (device) rtcReleaseDevice(device);
  }
};

Raycaster::Raycaster(const Asset& asset) : s_(std::make_unique<State>()) {
  State& st = *s_;
  st.textures = std::make_unique<Textures>(asset);
  st.geometry.path = asset.path;
  st.geometry.primitives = asset.primitives;
  st.geometry.materials = asset.materials;
  st.surfaces = std::make_unique<Surfaces>(st.geometry, *st.textures);

  st.device = rtcNewDevice(nullptr);
  if (!st.device) throw Error("Embree: cannot create a device (" + std::to_string(rtcGetDeviceError(nullptr)) + ")");
  st.scene = rtcNewScene(st.device);
  // Rays through a shared edge (a quad's diagonal at a pixel centre) must not slip between triangles.
  rtcSetSceneFlags(st.scene, RTC_SCENE_FLAG_ROBUST);
  for (std::size_t i = 0; i < st.geometry.primitives.size(); ++i) {
    const Primitive& p = st.geometry.primitives[i];
    const std::size_t vc = p.vertexCount(), tc = p.triangleCount();
    if (tc == 0 || vc == 0) continue;
    for (std::uint32_t index : p.indices)
      if (index >= vc)
        throw Error(p.where + ": vertex index " + std::to_string(index) + " out of range (" + std::to_string(vc) +
                    " vertices)");
    const int m = p.material;
    if (m >= static_cast<int>(st.geometry.materials.size()))
      throw Error(p.where + ": material " + std::to_string(m) + " does not exist (the asset has " +
                  std::to_string(st.geometry.materials.size()) + ")");
    RTCGeometry g = rtcNewGeometry(st.device, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* vb = static_cast<float*>(
        rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), vc));
    auto* ib = static_cast<std::uint32_t*>(
        rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(std::uint32_t), tc));
    if (!vb || !ib) {
      rtcReleaseGeometry(g);
      throw Error(ErrorKind::Memory, "Embree: out of memory for " + p.where);
    }
    std::copy(p.positions.begin(), p.positions.begin() + 3 * vc, vb);
    std::copy(p.indices.begin(), p.indices.begin() + 3 * tc, ib);
    if (st.surfaces->mayReject(static_cast<int>(i))) rtcSetGeometryIntersectFilterFunction(g, filterHit);
    rtcCommitGeometry(g);
    rtcAttachGeometryByID(st.scene, g, static_cast<unsigned>(i));
    rtcReleaseGeometry(g);
  }
  rtcCommitScene(st.scene);
  const RTCError err = rtcGetDeviceError(st.device);
  if (err != RTC_ERROR_NONE) throw Error("Embree: cannot build the scene (error " + std::to_string(err) + ")");
}

Raycaster::~Raycaster() = default;

std::size_t Raycaster::textureBytes() const { return s_->textures->bytes(); }

namespace {
// The view as the G-buffer's header records it; the image's aspect gives the orthographic xmag.
GBufferCamera gbufferCamera(const View& v) {
  GBufferCamera c;
  c.orthographic = v.orthographic;
  for (int k = 0; k < 3; ++k) {
    c.position[k] = static_cast<float>(v.position[k]);
    c.right[k] = static_cast<float>(v.right[k]);
    c.up[k] = static_cast<float>(v.up[k]);
    c.forward[k] = static_cast<float>(v.forward[k]);
  }
  c.fovDegrees = static_cast<float>(2.0 * std::atan(v.tanHalfFovY) * 180.0 / 3.14159265358979323846);
  c.ymag = static_cast<float>(v.halfHeight);
  c.xmag = static_cast<float>(v.halfHeight * v.aspect);
  // Beyond float range a plane is as good as absent (the header holds floats).
  const double top = std::numeric_limits<float>::max();
  c.znear = static_cast<float>(std::min(v.znear, top));
  c.zfar = v.zfar < top ? static_cast<float>(v.zfar) : 0.0f;
  return c;
}
}  // namespace

GBuffer Raycaster::trace(const View& view, int width, int height, float jx, float jy) const {
  GBuffer g;
  trace(view, width, height, jx, jy, g);
  return g;
}

namespace {
// Sizes and zeroes every channel of `g` for n pixels. A 1080p G-buffer is 270 MB of zeroed pages:
// channels allocated on every core, so that their page faults and zeroing do not all fall on one.
void zeroChannels(GBuffer& g, std::size_t n) {
  const std::array<std::pair<std::vector<float>*, int>, 17> channels{{
      {&g.P, 3}, {&g.N, 3}, {&g.T, 3}, {&g.baseColor, 3}, {&g.emissive, 3}, {&g.sheenColor, 3}, {&g.clearcoatN, 3},
      {&g.V, 3}, {&g.metallic, 1}, {&g.roughness, 1}, {&g.mask, 1}, {&g.sheenRoughness, 1}, {&g.clearcoat, 1},
      {&g.clearcoatRoughness, 1}, {&g.anisotropyStrength, 1}, {&g.anisotropyRotation, 1}, {&g.occlusion, 1}}};
  // Out of memory must not leave the OpenMP region: caught, and rethrown after it.
  std::array<std::exception_ptr, std::tuple_size<decltype(channels)>::value> failures;
  const int count = int(channels.size());
#pragma omp parallel for schedule(dynamic, 1)
  for (int c = 0; c < count; ++c) {
    try {
      channels[std::size_t(c)].first->assign(channels[std::size_t(c)].second * n, 0.0f);
    } catch (...) {
      failures[std::size_t(c)] = std::current_exception();
    }
  }
  for (const std::exception_ptr& e : failures)
    if (e) std::rethrow_exception(e);
}

// The primary rays of the 4x4 pixels from (x0, y0) into `rh`, their unit directions into `dirs`;
// `valid` marks the pixels inside the image.
void primaryRays(const View& view, int width, int height, float jx, float jy, int x0, int y0, RTCRayHit16& rh,
                 int valid[16], float dirs[16][3]) {
  const double aspect = view.aspect;
  const double ext = view.orthographic ? view.halfHeight : view.tanHalfFovY;
  const Imath::V3d f = toVec3(view.forward), r = toVec3(view.right), u = toVec3(view.up), p = toVec3(view.position);
  const float inf = std::numeric_limits<float>::infinity();
  for (int lane = 0; lane < 16; ++lane) {
    const int x = x0 + lane % 4, y = y0 + lane / 4;
    valid[lane] = x < width && y < height ? -1 : 0;
    const double s = 2.0 * (x + jx) / width - 1.0, t = 1.0 - 2.0 * (y + jy) / height;
    Imath::V3d o, d;
    if (view.orthographic) {
      o = p + s * ext * aspect * r + t * ext * u;
      d = f;
    } else {
      o = p;
      d = f + s * ext * aspect * r + t * ext * u;
    }
    d /= norm(d);
    for (int k = 0; k < 3; ++k) dirs[lane][k] = static_cast<float>(d[k]);
    // Distances along the ray to the near and far planes, which are perpendicular to forward.
    const double cosF = d ^ f;
    rh.ray.org_x[lane] = static_cast<float>(o[0]);
    rh.ray.org_y[lane] = static_cast<float>(o[1]);
    rh.ray.org_z[lane] = static_cast<float>(o[2]);
    rh.ray.dir_x[lane] = dirs[lane][0];
    rh.ray.dir_y[lane] = dirs[lane][1];
    rh.ray.dir_z[lane] = dirs[lane][2];
    rh.ray.tnear[lane] = static_cast<float>(std::max(0.0, view.znear / cosF));
    rh.ray.tfar[lane] = view.zfar > 0.0 ? static_cast<float>(view.zfar / cosF) : inf;
    rh.ray.time[lane] = 0.0f;
    rh.ray.mask[lane] = 0xFFFFFFFFu;
    rh.ray.id[lane] = static_cast<unsigned>(lane);
    rh.ray.flags[lane] = 0;
    rh.hit.geomID[lane] = RTC_INVALID_GEOMETRY_ID;
    rh.hit.primID[lane] = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0][lane] = RTC_INVALID_GEOMETRY_ID;
  }
}

// Pixel i of `g` holds the surface `sp` (V is written by the caller).
void storeSurface(GBuffer& g, std::size_t i, const SurfacePoint& sp) {
  for (int k = 0; k < 3; ++k) {
    g.P[3 * i + k] = sp.P[k];
    g.N[3 * i + k] = sp.N[k];
    g.T[3 * i + k] = sp.T[k];
    g.baseColor[3 * i + k] = sp.baseColor[k];
    g.emissive[3 * i + k] = sp.emissive[k];
    g.sheenColor[3 * i + k] = sp.sheenColor[k];
    g.clearcoatN[3 * i + k] = sp.clearcoatN[k];
  }
  g.mask[i] = 1.0f;
  g.metallic[i] = sp.metallic;
  g.roughness[i] = sp.roughness;
  g.sheenRoughness[i] = sp.sheenRoughness;
  g.clearcoat[i] = sp.clearcoat;
  g.clearcoatRoughness[i] = sp.clearcoatRoughness;
  g.anisotropyStrength[i] = sp.anisotropyStrength;
  g.anisotropyRotation[i] = sp.anisotropyRotation;
  g.occlusion[i] = sp.occlusion;
}
}  // namespace

void Raycaster::trace(const View& view, int width, int height, float jx, float jy, GBuffer& g) const {
  if (width <= 0 || height <= 0)
    throw Error("image size " + std::to_string(width) + "x" + std::to_string(height) + ": expected positive sizes");
  g.width = width;
  g.height = height;
  g.camera = gbufferCamera(view);
  zeroChannels(g, g.pixelCount());
  const State& st = *s_;

  // One packet of 4x4 neighbouring pixels: coherent primary rays traverse the BVH together.
  auto traceBlock = [&](RayContext& rc, int x0, int y0) {
    alignas(64) RTCRayHit16 rh;
    alignas(64) int valid[16];
    float dirs[16][3];
    primaryRays(view, width, height, jx, jy, x0, y0, rh, valid, dirs);
    rtcIntersect16(valid, st.scene, &rc.embree, &rh);

    for (int lane = 0; lane < 16; ++lane) {
      if (!valid[lane]) continue;
      const int x = x0 + lane % 4, y = y0 + lane / 4;
      const std::size_t i = static_cast<std::size_t>(y) * width + x;
      float V[3] = {-dirs[lane][0], -dirs[lane][1], -dirs[lane][2]};
      if (rh.hit.geomID[lane] != RTC_INVALID_GEOMETRY_ID) {
        Hit h;
        h.prim = static_cast<int>(rh.hit.geomID[lane]);
        h.tri = rh.hit.primID[lane];
        h.u = rh.hit.u[lane];
        h.v = rh.hit.v[lane];
        h.dir = {dirs[lane][0], dirs[lane][1], dirs[lane][2]};
        h.coneWidth = rc.orthographic ? rc.coneWidth : rh.ray.tfar[lane] * rc.coneSpread;
        const SurfacePoint sp = st.surfaces->evaluate(h);
        if (!view.orthographic) {
          const Imath::V3d e = toVec3(view.position) - Imath::V3d(toVec3(sp.P));
          const double el = norm(e);
          if (el > 0.0 && std::isfinite(el))
            for (int k = 0; k < 3; ++k) V[k] = static_cast<float>(e[k] / el);
        }
        storeSurface(g, i, sp);
      }
      for (int k = 0; k < 3; ++k) g.V[3 * i + k] = V[k];
    }
  };

  // Tiles rather than rows: neighbouring rows on one core reuse the texels the previous row
  // brought into its cache.
  constexpr int kTileW = 32, kTileH = 8;
  const int tilesX = (width + kTileW - 1) / kTileW, tiles = tilesX * ((height + kTileH - 1) / kTileH);
  // Each thread keeps one ray context and takes tiles as it frees up. An exception must not leave
  // the OpenMP region: each tile's is kept, and the first in the tiles' order rethrown after it.
  std::vector<std::exception_ptr> failures(std::size_t(std::max(tiles, 0)));
#pragma omp parallel
  {
    RayContext rc;
    rtcInitIntersectContext(&rc.embree);
    rc.embree.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    rc.surfaces = st.surfaces.get();
    rc.orthographic = view.orthographic;
    rc.coneSpread = static_cast<float>(2.0 * view.tanHalfFovY / height);
    rc.coneWidth = static_cast<float>(2.0 * view.halfHeight / height);
#pragma omp for schedule(dynamic, 1)
    for (int tile = 0; tile < tiles; ++tile) {
      try {
        const int x0 = (tile % tilesX) * kTileW, y0 = (tile / tilesX) * kTileH;
        for (int y = y0; y < std::min(height, y0 + kTileH); y += 4)
          for (int x = x0; x < std::min(width, x0 + kTileW); x += 4) traceBlock(rc, x, y);
      } catch (...) {
        failures[std::size_t(tile)] = std::current_exception();
      }
    }
  }
  for (const std::exception_ptr& e : failures)
    if (e) std::rethrow_exception(e);
}

}  // namespace brdfcl::gltf
