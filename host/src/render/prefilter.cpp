// Image-based light for the shader: the environment prefiltered on the device (kernels/
// ibl_prefilter.cl) into GGX and Charlie chains and an irradiance map, cached on disk, and the
// tables the shade kernel reads beside them; shared by every Shader of the process.
#include "render/prefilter.hpp"

#include <map>
#include <mutex>
#include <string>

#include <fmt/format.h>

#include "brdfcl/error.hpp"
#include "brdfcl/lut.hpp"
#include "io/disk_cache.hpp"
#include "model/engine_tables.hpp"
#include "model/pack.hpp"
#include "runtime/opencl.hpp"

namespace brdfcl::detail {
namespace {
// Part of the disk cache key of prefiltered environments: bump when the chain layout, the sample
// counts or the levels change (the kernel source is in the key already).
constexpr const char* kPrefilterVersion = "chains6 ggx1/128 cap512x256 charlie256 at128x64 irr512 v2";

// kernels/common/environment.h's chain layout (env_level_w/h), which the kernels index by.
int levelW(int w0, int capW, int k) { return k == 0 ? std::max(w0, 8) : std::max(std::min(w0, capW) >> k, 8); }
int levelH(int h0, int capH, int k) { return k == 0 ? std::max(h0, 4) : std::max(std::min(h0, capH) >> k, 4); }

// Floats of a prefiltered chain of kPrefilterLevels levels.
std::size_t chainFloatsOf(int w0, int h0, int capW, int capH) {
  std::size_t n = 0;
  for (int k = 0; k < kPrefilterLevels; ++k) n += 3 * std::size_t(levelW(w0, capW, k)) * levelH(h0, capH, k);
  return n;
}

// GGX and Charlie prefiltered chains (kPrefilterLevels levels each, roughness k / (levels - 1))
// and the irradiance map, concatenated in that order: the part of the light worth caching.
std::vector<float> prefilterEnvironment(Runtime& rt, const std::vector<float>& env, int envW, int envH) {
  const auto& ctx = rt.opencl().context();
  auto& q = rt.opencl().queue();
  // Source chain: the environment and its 2x2 box mips down to 8x4.
  std::vector<int> ws{envW}, hs{envH};
  while (ws.back() > 8 && hs.back() > 4) ws.push_back(std::max(ws.back() / 2, 8)), hs.push_back(std::max(hs.back() / 2, 4));
  std::size_t chainFloats = 0;
  for (std::size_t k = 0; k < ws.size(); ++k) chainFloats += 3 * std::size_t(ws[k]) * hs[k];
  cl::Buffer chain(ctx, CL_MEM_READ_WRITE, chainFloats * 4);
  q.enqueueWriteBuffer(chain, CL_TRUE, 0, env.size() * 4, env.data());
  auto prefilterProgram = rt.opencl().program("ibl_prefilter.cl");
  cl::Kernel down(prefilterProgram, "env_downsample");
  std::size_t offset = 0;
  for (std::size_t k = 0; k + 1 < ws.size(); ++k) {
    const std::size_t size = 3 * std::size_t(ws[k]) * hs[k], next = 3 * std::size_t(ws[k + 1]) * hs[k + 1];
    // Sub-buffer offsets need the device's base alignment; copy through temporaries instead.
    cl::Buffer a(ctx, CL_MEM_READ_WRITE, size * 4), b(ctx, CL_MEM_READ_WRITE, next * 4);
    q.enqueueCopyBuffer(chain, a, offset * 4, 0, size * 4);
    down.setArg(0, a);
    down.setArg(1, ws[k]);
    down.setArg(2, hs[k]);
    down.setArg(3, b);
    down.setArg(4, ws[k + 1]);
    down.setArg(5, hs[k + 1]);
    q.enqueueNDRangeKernel(down, cl::NullRange, cl::NDRange(std::size_t(ws[k + 1]), std::size_t(hs[k + 1])));
    q.enqueueCopyBuffer(b, chain, 0, (offset + size) * 4, next * 4);
    offset += size;
  }

  // Prefiltered chains: level k of kPrefilterLevels at roughness k / (levels - 1).
  cl::Kernel pre(prefilterProgram, "env_prefilter");
  // GGX level 0 is the mirror at the map's size; its blurred levels and the whole Charlie chain
  // are no larger than their lobes need, which keeps a 1k or 4k map's first use short.
  auto prefilterChain = [&](int kind) {
    std::vector<float> all;
    const int w0 = kind == 0 ? envW : charlieW(envW), h0 = kind == 0 ? envH : charlieH(envH);
    const int capW = kind == 0 ? BRDFCL_PREFILTER_CAP_W : w0, capH = kind == 0 ? BRDFCL_PREFILTER_CAP_H : h0;
    for (int k = 0; k < kPrefilterLevels; ++k) {
      const int w = levelW(w0, capW, k), h = levelH(h0, capH, k);
      cl::Buffer out(ctx, CL_MEM_WRITE_ONLY, 3 * std::size_t(w) * h * 4);
      pre.setArg(0, chain);
      pre.setArg(1, envW);
      pre.setArg(2, envH);
      pre.setArg(3, int(ws.size()));
      pre.setArg(4, kind);
      pre.setArg(5, float(k) / float(kPrefilterLevels - 1));
      pre.setArg(6, cl_uint(kind == 0 ? (k == 0 ? 1 : 128) : 256));
      pre.setArg(7, out);
      pre.setArg(8, w);
      pre.setArg(9, h);
      q.enqueueNDRangeKernel(pre, cl::NullRange, cl::NDRange(std::size_t(w), std::size_t(h)));
      std::vector<float> level(3 * std::size_t(w) * h);
      q.enqueueReadBuffer(out, CL_TRUE, 0, level.size() * 4, level.data());
      all.insert(all.end(), level.begin(), level.end());
    }
    return all;
  };
  std::vector<float> arrays = prefilterChain(0);
  const std::vector<float> charlie = prefilterChain(1);
  arrays.insert(arrays.end(), charlie.begin(), charlie.end());
  {
    cl::Buffer out(ctx, CL_MEM_WRITE_ONLY, 3 * kIrradianceW * kIrradianceH * 4);
    pre.setArg(0, chain);
    pre.setArg(1, envW);
    pre.setArg(2, envH);
    pre.setArg(3, int(ws.size()));
    pre.setArg(4, 2);
    pre.setArg(5, 1.0f);
    pre.setArg(6, cl_uint(512));
    pre.setArg(7, out);
    pre.setArg(8, kIrradianceW);
    pre.setArg(9, kIrradianceH);
    q.enqueueNDRangeKernel(pre, cl::NullRange, cl::NDRange(kIrradianceW, kIrradianceH));
    std::vector<float> irr(3 * kIrradianceW * kIrradianceH);
    q.enqueueReadBuffer(out, CL_TRUE, 0, irr.size() * 4, irr.data());
    arrays.insert(arrays.end(), irr.begin(), irr.end());
  }

  return arrays;
}
}  // namespace

std::shared_ptr<const PreparedLight> prepareLight(Runtime& rt, const Environment& environment, const EvalOptions& options) {
  static std::mutex mutex;
  static std::map<std::string, std::shared_ptr<const PreparedLight>> cache;
  const EvalOptions table = sheenTableOptions(options);
  const std::string key = fmt::format("{}|{}|{}|{}|{}|{}|{}|{}", static_cast<const void*>(&rt), environment.builtin,
                                      environment.builtinKind, environment.path, environment.intensity,
                                      toString(table.sheenDistribution), toString(table.sheenVisibility),
                                      toString(options.profile));
  std::lock_guard<std::mutex> lock(mutex);
  if (auto it = cache.find(key); it != cache.end()) return it->second;
  auto prepared = std::make_shared<PreparedLight>();
  auto& s = *prepared;
  const auto env = environmentPlanes(environment, s.envW, s.envH);
  const auto& ctx = rt.opencl().context();
  try {
    s.background = readOnly(ctx, env);
    // The prefiltered chains and irradiance depend only on the environment's texels and the
    // prefilter kernel: keyed by both, they come from the disk cache on every run but the first.
    const std::string device = rt.info().name + "|" + rt.info().platform + "|" + rt.info().openclC;
    const std::uint64_t prefilterKey = detail::contentHash(
        env, detail::contentHash(fmt::format("{}|{}|{}x{}|{}|{}x{}", kernelSource("ibl_prefilter.cl"), kPrefilterVersion,
                                             s.envW, s.envH, device, kIrradianceW, kIrradianceH)));
    const std::size_t ggxFloats = chainFloatsOf(s.envW, s.envH, BRDFCL_PREFILTER_CAP_W, BRDFCL_PREFILTER_CAP_H);
    const std::size_t charlieFloats =
        chainFloatsOf(charlieW(s.envW), charlieH(s.envH), charlieW(s.envW), charlieH(s.envH));
    std::vector<float> arrays(ggxFloats + charlieFloats + 3 * kIrradianceW * kIrradianceH);
    const std::string prefilterName = fmt::format("env_{}x{}_{:016x}.f32", s.envW, s.envH, prefilterKey);
    if (!detail::loadCachedFloats(prefilterName, arrays)) {
      arrays = prefilterEnvironment(rt, env, s.envW, s.envH);
      detail::storeCachedFloats(prefilterName, arrays);
    }
    auto part = [&](std::size_t begin, std::size_t count) {
      return readOnly(ctx, std::vector<float>(arrays.begin() + std::ptrdiff_t(begin),
                                              arrays.begin() + std::ptrdiff_t(begin + count)));
    };
    s.ggx = part(0, ggxFloats);
    s.charlie = part(ggxFloats, charlieFloats);
    s.irradiance = part(ggxFloats + charlieFloats, 3 * kIrradianceW * kIrradianceH);

    std::vector<float> dfg(2 * kDfgSize * kDfgSize);
    const std::string dfgName =
        fmt::format("ggx_dfg_{}_{:016x}.f32", kDfgSize, detail::contentHash(kernelSource("lut.cl") + "|" + device));
    if (!detail::loadCachedFloats(dfgName, dfg)) {
      dfg = bakeLut(rt, LutKind::GgxDfg, kDfgSize).values;
      detail::storeCachedFloats(dfgName, dfg);
    }
    s.dfg = readOnly(ctx, dfg);
    const auto e = cachedSheenAlbedo(rt, table.sheenDistribution, table.sheenVisibility);
    std::vector<float> tables = e.values;
    // Engine profiles read three.js's DFG table right after the E table, khronos the Sample
    // Renderer's sheen albedo texture after that, babylon its BRDF texture (docs/profiles.md "Tables").
    if (options.profile != Profile::Spec) tables.insert(tables.end(), threejsDfgTable().begin(), threejsDfgTable().end());
    if (options.profile == Profile::Khronos)
      tables.insert(tables.end(), khronosSheenETable().begin(), khronosSheenETable().end());
    if (options.profile == Profile::Babylon)
      tables.insert(tables.end(), babylonBrdfTable().begin(), babylonBrdfTable().end());
    s.sheenE = readOnly(ctx, tables);
    s.sheenESize = int(e.width);
    std::vector<float> fl(kFresnelLambertSize);
    for (int i = 0; i < kFresnelLambertSize; ++i) fl[i] = float(fresnelWeightedLambert(double(i) / (kFresnelLambertSize - 1)));
    s.fresnelLambert = readOnly(ctx, fl);
  } catch (const cl::Error&) {
    rethrowOpenCL("preparing image-based light");
  }
  cache.emplace(key, prepared);
  return prepared;
}

}  // namespace brdfcl::detail
