// `brdfcl gbuffer`, `brdfcl shade`, `brdfcl render` and `brdfcl demo`: G-buffers of the built-in
// spheres or of a glTF asset, deferred shading of any G-buffer under a scene's lights and
// environment, and both chained into linear EXR radiance and a tone-mapped PNG. Under mpirun,
// shade and render shade a band of rows per rank and rank 0 gathers them and writes the files.
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "host/src/gltf/demo_asset.hpp"
#include "brdfcl/frame_budget.hpp"
#include "host/src/devices/device_set.hpp"
#include "brdfcl/error.hpp"
#include "brdfcl/gbuffer.hpp"
#include "brdfcl/gltf.hpp"
#include "host/src/render/gltf_frame.hpp"
#include "brdfcl/image.hpp"
#include "host/src/parity/diff.hpp"
#include "brdfcl/io.hpp"
#include "host/src/model/profile_version.hpp"
#include "brdfcl/render.hpp"
#include "brdfcl/render_job.hpp"
#include "commands.hpp"
#include "host/src/io/output.hpp"
#include "host/src/mpi/session.hpp"
#include "render_options.hpp"

namespace brdfcl::cli {

void parseSize(const std::string& s, int& w, int& h) {
  int n = 0;
  if (std::sscanf(s.c_str(), "%dx%d%n", &w, &h, &n) != 2 || n != int(s.size()) || w < 1 || h < 1 || w > 16384 ||
      h > 16384)
    throw Error(fmt::format("--size '{}' is not WIDTHxHEIGHT with sides 1 to 16384, e.g. 768x768", s));
}

std::string lowerExtension(const std::string& path) {
  auto e = std::filesystem::path(path).extension().string();
  for (auto& c : e) c = char(std::tolower(static_cast<unsigned char>(c)));
  return e;
}

void requireExtension(const std::string& option, const std::string& path, const char* extension) {
  if (!path.empty() && !detail::isStreamTarget(path) && lowerExtension(path) != extension)
    throw Error(fmt::format("{} '{}' must end in {}", option, path, extension));
}

void checkExposure(float exposure) {
  if (!std::isfinite(exposure)) throw Error(fmt::format("--exposure {} is not a finite number of stops; use e.g. 0 or -1.5", exposure));
}

// Every output named on the command line, checked before any work: extension and writability.
void checkOutput(const std::string& option, const std::string& path, const char* extension) {
  if (path.empty()) return;
  requireExtension(option, path, extension);
  checkOutputPath(option, path);
}

// stdout holds one file: two outputs there would interleave into neither.
void checkOneStdout(std::initializer_list<std::pair<const char*, const std::string*>> outputs) {
  std::vector<std::string> dashes;
  for (const auto& [option, path] : outputs)
    if (*path == "-") dashes.push_back(option);
  if (dashes.size() > 1)
    throw Error(fmt::format("{} all write to stdout ('-'); give at most one of them '-'", fmt::join(dashes, " and ")));
}

void checkSpp(int spp) { checkRenderSpp(spp); }

void writeImages(const Image& img, const std::string& exr, const std::string& png, float exposure) {
  if (!exr.empty()) writeExrRgb(exr, img.width, img.height, img.rgb);
  if (!png.empty()) writePng(png, img.width, img.height, img.rgb, exposure);
}


RenderJob GltfArgs::job() const {
  RenderJob j;
  j.gltf = path;
  j.camera = camera;
  j.gltfScene = scene;
  j.variant = variant;
  j.strict = strict;
  j.allowOutsideUris = allowOutsideUris;
  if (!size.empty()) parseSize(size, j.width, j.height);
  j.warn = printWarning;
  return j;
}

// Progress on stderr only when a person is watching it: "<what>: <unit> 3/12, 0:41 left". A
// single step has nothing to report.
std::function<void(int, int)> progressLine(const char* what, const char* unit) {
  if (!isatty(STDERR_FILENO)) return {};
  const auto start = std::chrono::steady_clock::now();
  return [what, unit, start](int done, int total) {
    if (total < 2) return;
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const int left = int(std::lround(elapsed / done * (total - done)));
    std::fprintf(stderr, "\r%s: %s %d/%d, %d:%02d left ", what, unit, done, total, left / 60, left % 60);
    if (done == total) std::fputc('\n', stderr);
    std::fflush(stderr);
  };
}


// Shades under the chosen image-based light; exact mode reports its error estimate on stderr.
Image shadeWith(Shader& shader, const GBuffer& g, const ShadeOptions& o) {
  ShadeStats stats;
  Image img = shader.shade(g, o, &stats);
  if (o.ibl == IblMode::Exact) printExactSummary(stats);
  return img;
}

void printExactSummary(const ShadeStats& stats) { std::fprintf(stderr, "%s\n", exactIblSummary(stats).c_str()); }



// The rows of a frame `height` rows tall that each rank shades under mpirun, indexed by rank:
// contiguous bands in rank order, or every row on rank 0 for the exact image-based light, which
// integrates the whole frame at once.
std::vector<mpi::Share> rowShares(int height, IblMode ibl) {
  const mpi::Session& s = mpi::Session::get();
  std::vector<mpi::Share> shares(static_cast<std::size_t>(s.size()));
  for (int r = 0; r < s.size(); ++r)
    shares[std::size_t(r)] = ibl == IblMode::Exact ? (r == 0 ? mpi::Share{0, std::uint64_t(height)} : mpi::Share{})
                                                   : mpi::shareOf(std::uint64_t(height), r, s.size());
  return shares;
}

// This rank's share of the shading.
ShadeOptions forRank(ShadeOptions o, const std::vector<mpi::Share>& shares) {
  const mpi::Session& s = mpi::Session::get();
  if (s.parallel() && o.ibl != IblMode::Exact) {
    o.firstRow = int(shares[std::size_t(s.rank())].begin);
    o.rowCount = int(shares[std::size_t(s.rank())].count());
  }
  return o;
}

bool myShareIsEmpty(const std::vector<mpi::Share>& shares) {
  return shares[std::size_t(mpi::Session::get().rank())].count() == 0;
}

// Rank 0 collects every rank's rows of `img` (a no-op in one process).
void gatherRows(Image& img, const std::vector<mpi::Share>& shares) {
  mpi::Session::get().gatherShares(img.rgb, shares, 3 * std::size_t(img.width));
}

bool writesOutputs() { return mpi::Session::get().rank() == 0; }

// "pthread-... CPU", or the devices of a list joined by " + ".
std::string deviceNames(DeviceSet& devices) {
  std::string names;
  for (std::size_t k = 0; k < devices.size(); ++k) names += (k ? " + " : "") + devices.runtime(k).info().name;
  return names;
}

}  // namespace brdfcl::cli
