// --ibl exact on the host: the environment CDFs (built in double, stored as float), the launches
// of kernels/ibl_exact.cl in chunks of samples (progress, and no launch long enough for a GPU
// watchdog), and the per-pixel standard errors reduced to one figure for the image.
#include "render/exact_ibl.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "brdfcl/error.hpp"
#include "io/luminance.hpp"
#include "io/option_style.hpp"
#include "runtime/opencl.hpp"

namespace brdfcl {

IblMode parseIblMode(const std::string& s) {
  if (s == "split-sum") return IblMode::SplitSum;
  if (s == "exact") return IblMode::Exact;
  throw Error(fmt::format("{} is not an image-based light mode; use split-sum or exact",
                          optionWithValue("--ibl", "'" + s + "'")));
}

const char* toString(IblMode m) { return m == IblMode::Exact ? "exact" : "split-sum"; }

void checkIblSamples(int samples) {
  if (samples < 1 || samples > kMaxIblSamples)
    throw Error(fmt::format("{} is out of range; use 1 to {}", optionWithValue("--ibl-samples", std::to_string(samples)),
                            kMaxIblSamples));
}

void checkIblSamplesApply(IblMode mode, bool samplesGiven) {
  if (mode != IblMode::Exact && samplesGiven)
    throw Error(fmt::format("{} applies to {}; add {}", optionName("--ibl-samples"), optionWithValue("--ibl", "exact", true),
                            optionWithValue("--ibl", "exact", true)));
}

std::string exactIblSummary(const ShadeStats& s) {
  return fmt::format("brdfcl: exact IBL, {} samples per pixel: relative standard error of the image {:.2f} % (mean "
                     "over {} covered pixels)",
                     s.iblSamples, 100.0 * s.relativeStandardError, s.coveredPixels);
}

namespace detail {

namespace {
// kernels/ibl_exact.cl: RGB sums of whole blocks and of the last block, then each replicate's
// luminance sums likewise.
constexpr int kReplicates = 4;
constexpr int kAccPlanes = 6 + 2 * kReplicates;
// c4(4) = sqrt(2 / 3) Gamma(2) / Gamma(3 / 2): E[s] = c4 sigma for 4 normal values.
constexpr double kC4 = 0.9213177319235613;
// About this many pixel-samples per launch: well under a second on a CPU, far under a GPU watchdog.
constexpr double kPixelSamplesPerLaunch = 4.0 * 1024 * 1024;
}  // namespace

EnvironmentCdf environmentCdf(const std::vector<float>& planes, int w, int h) {
  EnvironmentCdf c;
  const std::size_t n = std::size_t(w) * h;
  std::vector<double> weight(n);
  std::vector<double> rowSum(h, 0.0);
  for (int y = 0; y < h; ++y) {
    // sin(theta) at the row's centre: the solid angle a texel of that row covers.
    const double sinTheta = std::sin((y + 0.5) / h * M_PI);
    for (int x = 0; x < w; ++x) {
      const std::size_t i = std::size_t(y) * w + x;
      const double lum = luminance709(planes[i], planes[n + i], planes[2 * n + i]);
      weight[i] = std::max(lum, 0.0) * sinTheta;
      rowSum[y] += weight[i];
    }
  }
  double total = 0.0, solidAngle = 0.0, peak = 0.0;
  for (double r : rowSum) total += r;
  for (int y = 0; y < h; ++y) {
    const double sinTheta = std::sin((y + 0.5) / h * M_PI);
    solidAngle += sinTheta * w;
    if (sinTheta > 0.0)
      for (int x = 0; x < w; ++x) peak = std::max(peak, weight[std::size_t(y) * w + x] / sinTheta);
  }
  c.rows.assign(h + 1, 0.0f);
  c.cols.assign(std::size_t(h) * (w + 1), 0.0f);
  c.texelP.assign(n, 0.0f);
  if (!(total > 0.0 && std::isfinite(total))) {
    // Never sampled (the kernel's environment share is 0); keep the arrays well formed.
    for (int y = 0; y <= h; ++y) c.rows[y] = float(y) / h;
    for (int y = 0; y < h; ++y)
      for (int x = 0; x <= w; ++x) c.cols[std::size_t(y) * (w + 1) + x] = float(x) / w;
    return c;
  }
  double run = 0.0;
  for (int y = 0; y < h; ++y) {
    run += rowSum[y];
    c.rows[y + 1] = float(run / total);
    double r = 0.0;
    float* col = &c.cols[std::size_t(y) * (w + 1)];
    for (int x = 0; x < w; ++x) {
      const std::size_t i = std::size_t(y) * w + x;
      r += weight[i];
      col[x + 1] = rowSum[y] > 0.0 ? float(r / rowSum[y]) : float(x + 1) / w;
      c.texelP[i] = float(weight[i] / total);
    }
    col[w] = 1.0f;
  }
  c.rows[h] = 1.0f;
  // How peaked the light is: mean over max luminance is 1 for a uniform environment (sample the
  // BRDF only) and near 0 for a sun.
  const double meanOverPeak = total / solidAngle / peak;
  c.share = float(kMaxEnvironmentShare * std::clamp(1.0 - meanOverPeak, 0.0, 1.0));
  return c;
}

void integrateExactIbl(Runtime& rt, const ExactIblInputs& in, const std::vector<float>& planes,
                       const ShadeOptions& options, std::vector<float>& out, ShadeStats* stats) {
  const std::size_t np = std::size_t(in.width) * in.height;
  const int total = options.iblSamples;
  const int chunk = options.chunkSamples > 0
                        ? std::min(options.chunkSamples, total)
                        : std::clamp(int(kPixelSamplesPerLaunch / double(std::max<std::size_t>(np, 1))), 1, total);
  std::vector<float> acc(kAccPlanes * np);
  try {
    cl::Buffer bacc(rt.opencl().context(), CL_MEM_READ_WRITE, acc.size() * 4);
    cl::Kernel k(in.program, "ibl_exact");
    int a = 0;
    k.setArg(a++, *in.gbuffer);
    k.setArg(a++, in.width);
    k.setArg(a++, in.height);
    k.setArg(a++, in.camera);
    k.setArg(a++, *in.environment);
    k.setArg(a++, in.envW);
    k.setArg(a++, in.envH);
    k.setArg(a++, in.rotation);
    k.setArg(a++, *in.rows);
    k.setArg(a++, *in.cols);
    k.setArg(a++, *in.texelP);
    k.setArg(a++, in.envShare);
    k.setArg(a++, *in.sheenE);
    k.setArg(a++, in.sheenESize);
    k.setArg(a++, cl_uint(options.seed));
    const int beginArg = a++, endArg = a++;
    k.setArg(a++, bacc);
    for (int begin = 0; begin < total; begin += chunk) {
      const int end = std::min(total, begin + chunk);
      k.setArg(beginArg, begin);
      k.setArg(endArg, end);
      rt.opencl().queue().enqueueNDRangeKernel(k, cl::NullRange, cl::NDRange(std::size_t(in.width), std::size_t(in.height)));
      rt.opencl().queue().finish();
      if (options.progress) options.progress(end, total);
    }
    rt.opencl().queue().enqueueReadBuffer(bacc, CL_TRUE, 0, acc.size() * 4, acc.data());
  } catch (const cl::Error&) {
    rethrowOpenCL("integrating the exact image-based light");
  }
  double relSum = 0.0;
  std::size_t covered = 0, lit = 0;
  for (std::size_t i = 0; i < np; ++i) {
    if (planes[GB_MASK * np + i] < 0.5f) continue;
    ++covered;
    const float occlusion = std::clamp(planes[GB_OCCLUSION * np + i], 0.0f, 1.0f);
    for (int c = 0; c < 3; ++c) out[c * np + i] += (acc[c * np + i] + acc[(3 + c) * np + i]) / float(total) * occlusion;
    // The replicates' means (copy r holds the samples k = r mod kReplicates) and their spread:
    // the standard error of their average is s / sqrt(R), s unbiased by c4.
    if (total < kReplicates) continue;
    double means[kReplicates], sum = 0.0;
    for (int r = 0; r < kReplicates; ++r) {
      const int count = (total - r + kReplicates - 1) / kReplicates;
      means[r] = (double(acc[(6 + r) * np + i]) + acc[(6 + kReplicates + r) * np + i]) / count;
      sum += means[r];
    }
    const double mean = sum / kReplicates;
    double ss = 0.0;
    for (double m : means) ss += (m - mean) * (m - mean);
    if (mean > 0.0) {
      relSum += std::sqrt(ss / (kReplicates - 1) / kReplicates) / kC4 / mean;
      ++lit;
    }
  }
  if (stats) {
    stats->iblSamples = total;
    stats->coveredPixels = covered;
    stats->relativeStandardError = lit ? relSum / double(lit) : 0.0;
  }
}

}  // namespace detail
}  // namespace brdfcl
