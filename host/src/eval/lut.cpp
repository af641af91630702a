// LUT baking on the device (kernels/lut.cl) on the uniform (N.V, roughness) grid engines sample,
// and the LUT writers: OpenEXR FLOAT channels, CSV, a C header and float32 NPY, written through
// the output layer (atomic for files, "-" is stdout).
#include "brdfcl/lut.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <exception>

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfStringAttribute.h>
#include <fmt/format.h>

#include "brdfcl/error.hpp"
#include "brdfcl/evaluator.hpp"
#include "brdfcl/io.hpp"
#include "eval/quadrature.hpp"
#include "io/files.hpp"
#include "io/messages.hpp"
#include "io/output.hpp"
#include "eval/sheen_albedo_bake.hpp"
#include "io/option_style.hpp"
#include "model/pack.hpp"
#include "runtime/opencl.hpp"

namespace brdfcl {

namespace {

// theta_h panel breaks at atan(alpha c): the GGX lobe's width in tan(theta_h) is alpha, and its
// tail falls as 1/tan^3, so geometric steps out to 64 alpha leave a smooth remainder.
const std::vector<float> kThetaGrade = {0.25f, 0.5f, 1.0f, 2.0f, 4.0f, 8.0f, 16.0f, 64.0f};
// Azimuth t = phi / phi_max: graded towards t = 1, where N.L -> 0 and, at grazing N.V, the
// visibility term turns sharply.
const std::vector<double> kPhiBreaks = {0.0, 0.5, 0.75, 0.9, 0.97, 0.99, 0.999, 0.9999, 1.0};

std::vector<float> toFloat(const std::vector<double>& v) { return std::vector<float>(v.begin(), v.end()); }

std::vector<float> bakeGgxDfg(Runtime& rt, std::size_t size, int nodesPerPanel) {
  const auto theta = gaussLegendre(nodesPerPanel, 0.0, 1.0);
  const auto phi = compositeGaussLegendre(kPhiBreaks, nodesPerPanel);
  auto pt = toFloat(phi.nodes), pw = toFloat(phi.weights);
  // The kernel reads azimuth nodes 16 lanes at a time: pad with zero-weight nodes.
  while (pt.size() % 16 != 0) {
    pt.push_back(0.0f);
    pw.push_back(0.0f);
  }
  const auto tn = toFloat(theta.nodes), tw = toFloat(theta.weights);
  std::vector<float> out(size * size * 2);
  EvalOptions o;
  FeatureSet f;
  f.sheen = true;
  try {
    // 16 lanes on every device, whatever laneShape() says: the lanes sum the phi nodes, so the
    // width sets the order of the sum and with it the last bits of the table (and its cache key).
    auto program = rt.opencl().program("lut.cl", materialDefines(o, f) + " -DBRDFCL_W=16");
    const auto& ctx = rt.opencl().context();
    auto ro = CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR;
    auto grade = kThetaGrade;
    cl::Buffer bg(ctx, ro, grade.size() * 4, grade.data());
    cl::Buffer btn(ctx, ro, tn.size() * 4, const_cast<float*>(tn.data()));
    cl::Buffer btw(ctx, ro, tw.size() * 4, const_cast<float*>(tw.data()));
    cl::Buffer bpt(ctx, ro, pt.size() * 4, pt.data()), bpw(ctx, ro, pw.size() * 4, pw.data());
    cl::Buffer bout(ctx, CL_MEM_WRITE_ONLY, out.size() * 4);
    cl::KernelFunctor<int, cl::Buffer, int, cl::Buffer, cl::Buffer, int, cl::Buffer, cl::Buffer, int, cl::Buffer> bake(
        program, "bake_ggx_dfg");
    bake(cl::EnqueueArgs(rt.opencl().queue(), cl::NDRange(size, size)), int(size), bg, int(grade.size()), btn, btw,
         int(tn.size()), bpt, bpw, int(pt.size()), bout);
    rt.opencl().queue().enqueueReadBuffer(bout, CL_TRUE, 0, out.size() * 4, out.data());
  } catch (const cl::Error&) {
    rethrowOpenCL("baking the ggx-dfg LUT");
  }
  return out;
}

// The format's extension: "-" and extensionless FIFOs or devices get CSV (io/output.hpp).
std::string lutExtension(const std::string& path) {
  return detail::outputExtension(path, detail::resolveOutput(path));
}

std::string identifier(LutKind k) {
  std::string s = toString(k);
  std::replace(s.begin(), s.end(), '-', '_');
  return s;
}

std::string upper(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return char(std::toupper(c)); });
  return s;
}

// One line per fact the consumer needs; shared by the EXR attribute and the header comment.
std::string describe(const Lut& lut) {
  std::string what;
  switch (lut.kind) {
    case LutKind::SheenE:
      what = fmt::format("E(N.V, r) = directional albedo of the white sheen lobe ({} D, {} V), alpha_s = r^2",
                         toString(lut.distribution), toString(lut.visibility));
      break;
    case LutKind::GgxDfg:
      what = "split-sum GGX: A = int (1 - w) D V N.L dw_L, B = int w D V N.L dw_L, w = (1 - V.H)^5, "
             "alpha = r^2; specular albedo = F0 A + B (f90 = 1)";
      break;
    case LutKind::CharlieDfg:
      what = "Charlie sheen DFG = int D_Charlie V_Charlie N.L dw_L (directional albedo of the white lobe), "
             "alpha_s = r^2";
      break;
  }
  return fmt::format(
      "brdfcl {} LUT, {}x{}, {} channel(s).\n{}.\nTexel (i, j): x = N.V = i/(size-1) (baked at max(x, 1e-4)), "
      "y = r = perceptual roughness j/(size-1); alpha floored at 1e-3.\nLayout: row j (roughness) major, i (N.V) "
      "fastest, channels interleaved: value[(j*size + i)*channels + c].",
      toString(lut.kind), lut.size, lut.size, lut.channels, what);
}

// Messages name the user's path (`shown`), never the temporary beside it.
void writeExr(const Lut& lut, const std::string& tmp, const std::string& path, const std::string& shown) {
  try {
    const int n = int(lut.size);
    Imf::Header header(n, n);
    header.compression() = Imf::ZIP_COMPRESSION;
    header.insert("brdfclLut", Imf::StringAttribute(describe(lut)));
    const auto names = lutChannelNames(lut.kind);
    // EXR channel names are R, G: viewers and engines' loaders read those without configuration.
    const char* exrNames[] = {"R", "G"};
    Imf::FrameBuffer fb;
    auto* base = const_cast<char*>(reinterpret_cast<const char*>(lut.values.data()));
    for (int c = 0; c < lut.channels; ++c) {
      header.channels().insert(exrNames[c], Imf::Channel(Imf::FLOAT));
      fb.insert(exrNames[c], Imf::Slice(Imf::FLOAT, base + c * sizeof(float), sizeof(float) * lut.channels,
                                         sizeof(float) * lut.channels * lut.size));
    }
    Imf::OutputFile file(tmp.c_str(), header);
    file.setFrameBuffer(fb);
    file.writePixels(n);
  } catch (const Error&) {
    throw;
  } catch (const std::exception& e) {
    throw Error(fmt::format("cannot write '{}': {}", shown,
                            detail::printable(detail::withUserPath(e.what(), tmp, path), 200, ' ')));
  }
}

// float32 NPY in the texel layout (row j = roughness major, i = N.V, channels innermost), so
// numpy's lut[j, i] (or lut[j, i, c]) is the texel at x = N.V = i/(size-1), y = r = j/(size-1):
// the EXR's pixel (i, j) and the CSV's row j*size + i.
std::string npyBytes(const Lut& lut) {
  const std::string shape = lut.channels == 1 ? fmt::format("({}, {})", lut.size, lut.size)
                                              : fmt::format("({}, {}, {})", lut.size, lut.size, lut.channels);
  std::string s = detail::npyHeader(shape);
  s.append(reinterpret_cast<const char*>(lut.values.data()), lut.values.size() * sizeof(float));
  return s;
}

std::string csvText(const Lut& lut) {
  std::string s = "nv,roughness";
  for (const auto& name : lutChannelNames(lut.kind)) s += "," + name;
  s += '\n';
  const double step = 1.0 / double(lut.size - 1);
  for (std::size_t j = 0; j < lut.size; ++j)
    for (std::size_t i = 0; i < lut.size; ++i) {
      s += fmt::format("{:.9g},{:.9g}", float(i * step), float(j * step));
      for (int c = 0; c < lut.channels; ++c) s += fmt::format(",{:.9g}", lut.at(i, j, c));
      s += '\n';
    }
  return s;
}

std::string headerText(const Lut& lut) {
  const std::string id = identifier(lut.kind), macro = "BRDFCL_" + upper(id) + "_LUT";
  std::string desc = describe(lut), comment;
  for (std::size_t p = 0, q; p < desc.size(); p = q + 1) {
    q = desc.find('\n', p);
    if (q == std::string::npos) q = desc.size();
    comment += " * " + desc.substr(p, q - p) + "\n";
  }
  std::string s = "/* Generated by brdfcl lut; do not edit.\n" + comment + " * Channels: ";
  const auto names = lutChannelNames(lut.kind);
  for (std::size_t c = 0; c < names.size(); ++c) s += (c ? ", " : "") + names[c];
  s += fmt::format(
      ".\n * Index: {0}[({1}_SIZE * j + i) * {1}_CHANNELS + c]; interpolate bilinearly in (i, j) = "
      "(N.V, roughness) * ({1}_SIZE - 1). */\n#ifndef {1}_H\n#define {1}_H\n#define {1}_SIZE {2}\n#define "
      "{1}_CHANNELS {3}\nstatic const float {0}[{1}_SIZE * {1}_SIZE * {1}_CHANNELS] = {{\n",
      "brdfcl_" + id + "_lut", macro, lut.size, lut.channels);
  const std::size_t perLine = 8;
  for (std::size_t k = 0; k < lut.values.size(); ++k) {
    // %.9g can print an integer ("1", "0"); suffix f needs a float literal, so keep plain doubles.
    s += fmt::format("{}{:.9g}{}", k % perLine == 0 ? "  " : " ", lut.values[k],
                     k + 1 == lut.values.size() ? "\n" : (k % perLine == perLine - 1 ? ",\n" : ","));
  }
  s += "};\n#endif\n";
  return s;
}

}  // namespace

LutKind parseLutKind(const std::string& s) {
  if (s == "sheen-e") return LutKind::SheenE;
  if (s == "ggx-dfg") return LutKind::GgxDfg;
  if (s == "charlie-dfg") return LutKind::CharlieDfg;
  throw Error("unknown " + optionName("--kind") + " value '" + detail::printable(s) + "'; use sheen-e, ggx-dfg or charlie-dfg");
}

const char* toString(LutKind k) {
  switch (k) {
    case LutKind::SheenE: return "sheen-e";
    case LutKind::GgxDfg: return "ggx-dfg";
    case LutKind::CharlieDfg: return "charlie-dfg";
  }
  return "?";
}

std::vector<std::string> lutChannelNames(LutKind k) {
  if (k == LutKind::GgxDfg) return {"A", "B"};
  return {"E"};
}

Lut bakeLut(Runtime& rt, LutKind kind, std::size_t size, const EvalOptions& o, int nodesPerPanel) {
  if (size < kMinLutSize || size > kMaxLutSize)
    throw Error(fmt::format("LUT size {} is out of range; use {} to {}", size, kMinLutSize, kMaxLutSize));
  Lut lut{kind, size, kind == LutKind::GgxDfg ? 2 : 1, SheenDistribution::Charlie, SheenVisibility::Charlie, {}};
  switch (kind) {
    case LutKind::GgxDfg:
      lut.values = bakeGgxDfg(rt, size, nodesPerPanel);
      break;
    case LutKind::SheenE:
      lut.distribution = o.sheenDistribution;
      lut.visibility = o.sheenVisibility;
      [[fallthrough]];
    case LutKind::CharlieDfg:
      lut.values = bakeSheenAlbedoFrom(rt, "lut.cl", lut.distribution, lut.visibility, size, nodesPerPanel).values;
      break;
  }
  return lut;
}

void checkLutPath(const std::string& path) {
  const auto ext = lutExtension(path);
  if (ext != ".exr" && ext != ".csv" && ext != ".h" && ext != ".npy")
    throw Error("cannot write LUT '" + detail::printable(path, 300) +
                "': unknown extension; use .exr, .csv, .h or .npy (- writes CSV to stdout)");
}

void writeLut(const Lut& lut, const std::string& path) {
  checkLutPath(path);
  const auto ext = lutExtension(path);
  const std::string shown = detail::printable(path, 300);
  if (ext == ".exr") {
    writeAtomically(path, [&](const std::string& tmp) { writeExr(lut, tmp, path, shown); });
    return;
  }
  const std::string bytes = ext == ".csv" ? csvText(lut) : ext == ".h" ? headerText(lut) : npyBytes(lut);
  writeOutput(path, bytes.data(), bytes.size());
}

}  // namespace brdfcl
