// brdfcl._core: the nanobind bindings of the C++ host library (brdfcl_core) that the pure-Python
// front (python/brdfcl/__init__.py) calls. No BRDF maths here: every call goes to the same library
// functions the CLI uses, with the GIL released while the device works.
#include <nanobind/nanobind.h>
#include <nanobind/ndarray.h>
#include <nanobind/stl/function.h>
#include <nanobind/stl/map.h>
#include <nanobind/stl/pair.h>
#include <nanobind/stl/string.h>
#include <nanobind/stl/tuple.h>
#include <nanobind/stl/vector.h>

#include <cmath>
#include <cstring>
#include <iterator>
#include <new>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <tuple>
#include <vector>

#include "brdfcl/albedo.hpp"
#include "brdfcl/arrays.hpp"
#include "brdfcl/device_array.hpp"
#include "brdfcl/error.hpp"
#include "brdfcl/evaluator.hpp"
#include "brdfcl/gbuffer.hpp"
#include "brdfcl/image.hpp"
#include "host/src/parity/diff.hpp"
#include "brdfcl/io.hpp"
#include "brdfcl/lut.hpp"
#include "brdfcl/material.hpp"
#include "brdfcl/render.hpp"
#include "brdfcl/render_job.hpp"
#include "brdfcl/runtime.hpp"
#include "brdfcl/scene.hpp"
#include "host/src/io/option_style.hpp"
#include "host/src/model/pack.hpp"

namespace nb = nanobind;
using namespace nb::literals;

namespace {

using brdfcl::Error;
using InArray = nb::ndarray<nb::ro, nb::c_contig, nb::device::cpu>;
using OutArray = nb::ndarray<float, nb::c_contig, nb::device::cpu>;

// A float32 numpy array that owns `values` (moved, never copied).
nb::ndarray<nb::numpy, float> toNumpy(std::vector<float>&& values, std::initializer_list<std::size_t> shape) {
  auto* held = new std::vector<float>(std::move(values));
  nb::capsule owner(held, [](void* p) noexcept { delete static_cast<std::vector<float>*>(p); });
  return nb::ndarray<nb::numpy, float>(held->data(), shape, owner);
}

// Materials parsed once on the Python side and passed to every call that evaluates them.
struct Materials {
  std::vector<brdfcl::MaterialParams> list;
  std::vector<std::string> warnings;
};

Materials readMaterials(const std::string& path, bool strict) {
  Materials m;
  brdfcl::MaterialReadOptions o;
  o.strict = strict;
  o.warn = [&m](const std::string& w) { m.warnings.push_back(w); };
  m.list = brdfcl::readMaterials(path, o);
  return m;
}

Materials parseMaterials(const std::string& json, const std::string& name, bool strict) {
  Materials m;
  brdfcl::MaterialReadOptions o;
  o.strict = strict;
  o.warn = [&m](const std::string& w) { m.warnings.push_back(w); };
  m.list = brdfcl::parseMaterials(json, name, o);
  return m;
}

brdfcl::EvalOptions evalOptions(const std::string& lobe, const std::string& visibility, const std::string& distribution,
                                const std::string& scaling, const std::string& profile) {
  brdfcl::EvalOptions o;
  o.profile = brdfcl::parseProfile(profile);
  o.sheenVisibility = brdfcl::parseSheenVisibility(visibility);
  o.sheenDistribution = brdfcl::parseSheenDistribution(distribution);
  o.sheenScaling = brdfcl::parseSheenScaling(scaling);
  o.lobe = brdfcl::parseLobe(lobe);
  brdfcl::checkProfileOptions(o);
  return o;
}

// An (N, 3) float32/float64 direction array as the library reads it (no copy).
brdfcl::DirectionArray directions(const InArray& a, const char* name, std::size_t& n) {
  if (a.ndim() != 2 || a.shape(1) != 3)
    throw Error(std::string(name) + " must have shape (N, 3), got " + std::to_string(a.ndim()) + " dimensions");
  brdfcl::DirectionArray d;
  d.data = a.data();
  if (a.dtype() == nb::dtype<float>())
    d.type = brdfcl::DirectionArray::Type::Float32;
  else if (a.dtype() == nb::dtype<double>())
    d.type = brdfcl::DirectionArray::Type::Float64;
  else
    throw Error(std::string(name) + " must be float32 or float64");
  n = a.shape(0);
  return d;
}

// One device and the evaluators of every option set used on it, made on first use. Evaluators
// are thread-safe (evaluator.hpp), so one per option set serves every thread.
class Device {
 public:
  explicit Device(const std::string& selector) : rt_(selector) {}

  brdfcl::Runtime& runtime() { return rt_; }

  brdfcl::Evaluator& evaluator(const brdfcl::EvalOptions& o) {
    const auto key = std::make_tuple(int(o.sheenVisibility), int(o.sheenDistribution), int(o.sheenScaling), int(o.lobe),
                                     int(o.profile));
    std::lock_guard<std::mutex> lock(mutex_);
    auto& slot = evaluators_[key];
    if (!slot) slot = std::make_unique<brdfcl::Evaluator>(rt_, o);
    return *slot;
  }

  nb::dict info() const {
    nb::dict d;
    const auto& i = rt_.info();
    d["index"] = i.index;
    d["name"] = i.name;
    d["platform"] = i.platform;
    d["type"] = i.type;
    d["compute_units"] = i.computeUnits;
    d["opencl_c"] = i.openclC;
    d["max_alloc"] = i.maxAlloc;
    d["global_mem"] = i.globalMem;
    return d;
  }

 private:
  brdfcl::Runtime rt_;
  std::mutex mutex_;
  std::map<std::tuple<int, int, int, int, int>, std::unique_ptr<brdfcl::Evaluator>> evaluators_;
};

void evaluate(Device& dev, const Materials& m, const InArray& L, const InArray& V, nb::object index, OutArray out,
              bool grid, const brdfcl::EvalOptions& o) {
  std::size_t nl = 0, nv = 0;
  brdfcl::ArraySamples s;
  s.L = directions(L, "L", nl);
  s.V = directions(V, "V", nv);
  if (nl != nv) throw Error("L and V must have the same number of rows, got " + std::to_string(nl) + " and " + std::to_string(nv));
  s.count = nl;
  const std::size_t rows = grid ? m.list.size() * nl : nl;
  if (out.size() != 3 * rows) throw Error("internal: output array of the wrong size", 3);
  std::unique_ptr<nb::ndarray<const std::int64_t, nb::ndim<1>, nb::c_contig, nb::device::cpu>> idx;
  if (!index.is_none()) {
    idx = std::make_unique<nb::ndarray<const std::int64_t, nb::ndim<1>, nb::c_contig, nb::device::cpu>>(
        nb::cast<nb::ndarray<const std::int64_t, nb::ndim<1>, nb::c_contig, nb::device::cpu>>(index, false));
    if (idx->shape(0) != nl)
      throw Error("material_index must have one entry per sample: " + std::to_string(idx->shape(0)) + " for " +
                  std::to_string(nl) + " samples");
    s.material = idx->data();
  }
  nb::gil_scoped_release release;
  brdfcl::Evaluator& ev = dev.evaluator(o);
  if (grid)
    brdfcl::evaluateGridArrays(ev, m.list, s, out.data());
  else
    brdfcl::evaluateArrays(ev, m.list, s, out.data());
}

// G-buffer channels as numpy arrays: (H, W, 3) vectors, (H, W) scalars, canonical names.
struct Channel {
  const char* name;
  std::vector<float> brdfcl::GBuffer::*field;
  int components;
  bool required;
};
const Channel kChannels[] = {
    {"P", &brdfcl::GBuffer::P, 3, true},
    {"N", &brdfcl::GBuffer::N, 3, true},
    {"baseColor", &brdfcl::GBuffer::baseColor, 3, true},
    {"metallic", &brdfcl::GBuffer::metallic, 1, true},
    {"roughness", &brdfcl::GBuffer::roughness, 1, true},
    {"mask", &brdfcl::GBuffer::mask, 1, true},
    {"T", &brdfcl::GBuffer::T, 3, false},
    {"emissive", &brdfcl::GBuffer::emissive, 3, false},
    {"sheenColor", &brdfcl::GBuffer::sheenColor, 3, false},
    {"sheenRoughness", &brdfcl::GBuffer::sheenRoughness, 1, false},
    {"clearcoat", &brdfcl::GBuffer::clearcoat, 1, false},
    {"clearcoatRoughness", &brdfcl::GBuffer::clearcoatRoughness, 1, false},
    {"clearcoatN", &brdfcl::GBuffer::clearcoatN, 3, false},
    {"anisotropyStrength", &brdfcl::GBuffer::anisotropyStrength, 1, false},
    {"anisotropyRotation", &brdfcl::GBuffer::anisotropyRotation, 1, false},
    {"occlusion", &brdfcl::GBuffer::occlusion, 1, false},
    {"V", &brdfcl::GBuffer::V, 3, false},
};

nb::dict gbufferToDict(brdfcl::GBuffer&& g) {
  nb::dict d;
  const auto h = std::size_t(g.height), w = std::size_t(g.width);
  for (const auto& c : kChannels) {
    auto& v = g.*c.field;
    if (v.empty()) continue;
    d[c.name] = c.components == 3 ? toNumpy(std::move(v), {h, w, 3}) : toNumpy(std::move(v), {h, w});
  }
  if (g.camera) {
    const auto& c = *g.camera;
    nb::dict cam;
    cam["orthographic"] = c.orthographic;
    cam["position"] = std::vector<float>(c.position.begin(), c.position.end());
    cam["right"] = std::vector<float>(c.right.begin(), c.right.end());
    cam["up"] = std::vector<float>(c.up.begin(), c.up.end());
    cam["forward"] = std::vector<float>(c.forward.begin(), c.forward.end());
    cam["fov"] = c.fovDegrees;
    cam["xmag"] = c.xmag;
    cam["ymag"] = c.ymag;
    cam["znear"] = c.znear;
    cam["zfar"] = c.zfar;
    d["camera"] = cam;
  }
  return d;
}

std::array<float, 3> vec3(const nb::dict& d, const char* key, std::array<float, 3> fallback) {
  if (!d.contains(key)) return fallback;
  const auto v = nb::cast<std::vector<float>>(d[key]);
  if (v.size() != 3) throw Error(std::string("gbuffer camera: ") + key + " must have 3 numbers");
  return {v[0], v[1], v[2]};
}

// A G-buffer from a dict of channel arrays (float32, C-contiguous: the Python front converts).
brdfcl::GBuffer gbufferFromDict(const nb::dict& d) {
  brdfcl::GBuffer g;
  for (auto [key, value] : d) {
    const std::string name = nb::cast<std::string>(key);
    if (name == "camera") continue;
    bool known = false;
    for (const auto& c : kChannels) known = known || name == c.name;
    if (!known) throw Error("gbuffer: unknown channel '" + name + "'; the channels are docs/gbuffer.md's (P, N, baseColor, ...)");
  }
  for (const auto& c : kChannels) {
    if (!d.contains(c.name)) {
      if (c.required) throw Error(std::string("gbuffer: missing required channel '") + c.name + "'");
      continue;
    }
    auto a = nb::cast<nb::ndarray<const float, nb::c_contig, nb::device::cpu>>(d[c.name], false);
    const bool shapeOk = c.components == 3 ? a.ndim() == 3 && a.shape(2) == 3 : a.ndim() == 2;
    if (!shapeOk)
      throw Error(std::string("gbuffer: channel '") + c.name + "' must have shape " +
                  (c.components == 3 ? "(H, W, 3)" : "(H, W)"));
    const int h = int(a.shape(0)), w = int(a.shape(1));
    if (g.width == 0 && g.height == 0) {
      g.width = w;
      g.height = h;
    } else if (w != g.width || h != g.height) {
      throw Error(std::string("gbuffer: channel '") + c.name + "' is " + std::to_string(h) + "x" + std::to_string(w) +
                  " (HxW), the others " + std::to_string(g.height) + "x" + std::to_string(g.width));
    }
    auto& v = g.*c.field;
    v.assign(a.data(), a.data() + a.size());
    for (std::size_t i = 0; i < v.size(); ++i)
      if (!std::isfinite(v[i]))
        throw Error(std::string("gbuffer: channel '") + c.name + "' holds a NaN or an infinity at element " + std::to_string(i));
  }
  if (g.width == 0 || g.height == 0) throw Error("gbuffer: the channels are empty");
  if (d.contains("camera")) {
    const nb::dict c = nb::cast<nb::dict>(d["camera"]);
    brdfcl::GBufferCamera cam;
    if (c.contains("orthographic")) cam.orthographic = nb::cast<bool>(c["orthographic"]);
    cam.position = vec3(c, "position", cam.position);
    cam.right = vec3(c, "right", cam.right);
    cam.up = vec3(c, "up", cam.up);
    cam.forward = vec3(c, "forward", cam.forward);
    if (c.contains("fov")) cam.fovDegrees = nb::cast<float>(c["fov"]);
    if (c.contains("xmag")) cam.xmag = nb::cast<float>(c["xmag"]);
    if (c.contains("ymag")) cam.ymag = nb::cast<float>(c["ymag"]);
    if (c.contains("znear")) cam.znear = nb::cast<float>(c["znear"]);
    if (c.contains("zfar")) cam.zfar = nb::cast<float>(c["zfar"]);
    g.camera = cam;
  }
  return g;
}

nb::ndarray<nb::numpy, float> imageToNumpy(brdfcl::Image&& img) {
  const auto h = std::size_t(img.height), w = std::size_t(img.width);
  return toNumpy(std::move(img.rgb), {h, w, 3});
}

}  // namespace

// Float rows normalized by the library's reader arithmetic (brdfcl::normalizeDirection), for the
// calls whose CLI counterparts read their directions from files.
static std::vector<float> unitRows(const float* rows, std::size_t n, const char* name) {
  std::vector<float> out(3 * n);
  for (std::size_t i = 0; i < n; ++i) {
    const double d[3] = {rows[3 * i], rows[3 * i + 1], rows[3 * i + 2]};
    if (!brdfcl::normalizeDirection(d, &out[3 * i]))
      throw Error(std::string(name) + " row " + std::to_string(i) + " is not a finite non-zero direction");
  }
  return out;
}

NB_MODULE(_core, m) {
  m.doc() = "brdfcl's C++ host library (brdfcl_core); use the brdfcl package, not this module.";
  // Every message names options as this process's callers write them: lobe=, not --lobe.
  brdfcl::setOptionStyle(brdfcl::OptionStyle::Python);
  // brdfcl.Error is the base of one class per brdfcl::ErrorKind, each also deriving the built-in
  // class a Python caller expects of that kind, so `except brdfcl.Error` and `except ValueError`
  // (or OSError, RuntimeError, MemoryError) both catch it.
  static PyObject* errorBase = PyErr_NewExceptionWithDoc(
      "brdfcl._core.Error", "Every error brdfcl raises; its .kind says who can fix it.", PyExc_Exception, nullptr);
  struct KindClass {
    brdfcl::ErrorKind kind;
    const char* name;
    PyObject* builtin;
    const char* doc;
  };
  static const KindClass kinds[] = {
      {brdfcl::ErrorKind::Input, "InputError", PyExc_ValueError, "A bad argument, file or value (a ValueError)."},
      {brdfcl::ErrorKind::Environment, "EnvironmentError", PyExc_OSError,
       "No OpenCL platform or device, or an unusable cache folder (an OSError)."},
      {brdfcl::ErrorKind::Device, "DeviceError", PyExc_RuntimeError,
       "An OpenCL call or kernel build failed on the device (a RuntimeError)."},
      {brdfcl::ErrorKind::Memory, "OutOfMemoryError", PyExc_MemoryError, "Host or device memory ran out (a MemoryError)."},
      {brdfcl::ErrorKind::Internal, "InternalError", PyExc_RuntimeError, "A fault in brdfcl itself (a RuntimeError)."},
  };
  static PyObject* kindClass[std::size(kinds)];
  PyObject_SetAttrString(errorBase, "kind", nb::str("").ptr());
  m.attr("Error") = nb::handle(errorBase);
  for (std::size_t i = 0; i < std::size(kinds); ++i) {
    const nb::object bases = nb::make_tuple(nb::handle(errorBase), nb::handle(kinds[i].builtin));
    kindClass[i] = PyErr_NewExceptionWithDoc((std::string("brdfcl._core.") + kinds[i].name).c_str(), kinds[i].doc,
                                             bases.ptr(), nullptr);
    if (kindClass[i] == nullptr) throw nb::python_error();
    PyObject_SetAttrString(kindClass[i], "kind", nb::str(brdfcl::toString(kinds[i].kind)).ptr());
    m.attr(kinds[i].name) = nb::handle(kindClass[i]);
  }
  nb::register_exception_translator([](const std::exception_ptr& p, void*) {
    try {
      std::rethrow_exception(p);
    } catch (const Error& e) {
      for (std::size_t i = 0; i < std::size(kinds); ++i)
        if (kinds[i].kind == e.kind()) PyErr_SetString(kindClass[i], e.what());
    } catch (const std::bad_alloc&) {
      PyErr_SetString(kindClass[3] /* Memory */, brdfcl::outOfMemoryMessage().c_str());
    }
  });

  // `python -m brdfcl` is a command line: its messages name its --options, as the CLI's do.
  m.def("set_cli_option_style", [] { brdfcl::setOptionStyle(brdfcl::OptionStyle::Cli); });

  m.def("devices", [] {
    std::vector<nb::dict> out;
    for (const auto& i : brdfcl::listDevices()) {
      nb::dict d;
      d["index"] = i.index;
      d["name"] = i.name;
      d["platform"] = i.platform;
      d["type"] = i.type;
      d["compute_units"] = i.computeUnits;
      d["opencl_c"] = i.openclC;
      d["max_alloc"] = i.maxAlloc;
      d["global_mem"] = i.globalMem;
      out.push_back(d);
    }
    return out;
  });

  nb::class_<Materials>(m, "Materials")
      .def("__len__", [](const Materials& x) { return x.list.size(); })
      .def_prop_ro("warnings", [](const Materials& x) { return x.warnings; })
      .def_prop_ro("names", [](const Materials& x) {
        std::vector<std::string> n;
        for (const auto& p : x.list) n.push_back(p.name);
        return n;
      });
  m.def("read_materials", &readMaterials, "path"_a, "strict"_a);
  m.def("parse_materials", &parseMaterials, "json"_a, "name"_a, "strict"_a);
  m.def("select_material", [](const Materials& x, std::size_t i) {
    if (i >= x.list.size()) throw Error("internal: material index out of range", 3);
    Materials one;
    one.list = {x.list[i]};
    return one;
  });

  nb::class_<brdfcl::EvalOptions>(m, "EvalOptions");
  m.def("eval_options", &evalOptions, "lobe"_a, "sheen_visibility"_a, "sheen_distribution"_a, "sheen_scaling"_a,
        "profile"_a);

  nb::class_<Device>(m, "Device")
      .def("__init__",
           [](Device* self, const std::string& selector) {
             nb::gil_scoped_release release;
             new (self) Device(selector);
           },
           "selector"_a)
      .def_prop_ro("info", &Device::info)
      .def("evaluate",
           [](Device& d, const Materials& m, const InArray& L, const InArray& V, nb::object index, OutArray out,
              const brdfcl::EvalOptions& o) { evaluate(d, m, L, V, index, out, false, o); },
           "materials"_a, "L"_a.noconvert(), "V"_a.noconvert(), "index"_a.none(), "out"_a.noconvert(), "options"_a)
      .def("evaluate_device",
           [](Device& d, const Materials& m, const brdfcl::DeviceArray& L, const brdfcl::DeviceArray& V,
              const brdfcl::DeviceArray* index, brdfcl::DeviceArray& out, bool normalize, const brdfcl::EvalOptions& o) {
             nb::gil_scoped_release release;
             d.evaluator(o).evaluate(m.list, L, V, index, out, normalize);
           },
           "materials"_a, "L"_a, "V"_a, "index"_a.none(), "out"_a, "normalize"_a, "options"_a)
      .def("evaluate_grid",
           [](Device& d, const Materials& m, const InArray& L, const InArray& V, OutArray out,
              const brdfcl::EvalOptions& o) { evaluate(d, m, L, V, nb::none(), out, true, o); },
           "materials"_a, "L"_a.noconvert(), "V"_a.noconvert(), "out"_a.noconvert(), "options"_a)
      .def("albedo",
           [](Device& d, const Materials& m, const std::vector<float>& mus, const brdfcl::EvalOptions& base) {
             std::map<std::string, nb::ndarray<nb::numpy, float>> out;
             const std::vector<brdfcl::Lobe> lobes = {brdfcl::Lobe::Diffuse, brdfcl::Lobe::Specular, brdfcl::Lobe::Sheen,
                                                      brdfcl::Lobe::Clearcoat, brdfcl::Lobe::All};
             for (brdfcl::Lobe l : lobes) {
               brdfcl::EvalOptions o = base;
               o.lobe = l;
               std::vector<float> a;
               {
                 nb::gil_scoped_release release;
                 a = brdfcl::directionalAlbedo(d.evaluator(o), m.list, mus);
               }
               out[brdfcl::toString(l)] = toNumpy(std::move(a), {m.list.size(), mus.size(), 3});
             }
             return out;
           },
           "materials"_a, "cos_theta_v"_a, "options"_a)
      .def("lut",
           [](Device& d, const std::string& kind, long long size, const std::string& visibility,
              const std::string& distribution) {
             const brdfcl::LutKind k = brdfcl::parseLutKind(kind);
             if (size < static_cast<long long>(brdfcl::kMinLutSize) || size > static_cast<long long>(brdfcl::kMaxLutSize))
               throw Error("size " + std::to_string(size) + " is out of range; use 2 to 4096");
             brdfcl::EvalOptions o;
             o.sheenVisibility = brdfcl::parseSheenVisibility(visibility);
             o.sheenDistribution = brdfcl::parseSheenDistribution(distribution);
             brdfcl::Lut lut;
             {
               nb::gil_scoped_release release;
               lut = brdfcl::bakeLut(d.runtime(), k, std::size_t(size), o);
             }
             const auto n = std::size_t(size);
             return lut.channels == 1 ? toNumpy(std::move(lut.values), {n, n})
                                      : toNumpy(std::move(lut.values), {n, n, std::size_t(lut.channels)});
           },
           "kind"_a, "size"_a, "sheen_visibility"_a, "sheen_distribution"_a)
      .def("render",
           [](Device& d, brdfcl::RenderJob job, const std::string& ibl, int iblSamples, bool iblSamplesGiven) {
             job.shade.ibl = brdfcl::parseIblMode(ibl);
             brdfcl::checkIblSamples(iblSamples);
             brdfcl::checkIblSamplesApply(job.shade.ibl, iblSamplesGiven);
             job.shade.iblSamples = iblSamples;
             std::vector<std::string> warnings;
             job.warn = [&warnings](const std::string& w) { warnings.push_back(w); };
             brdfcl::Image img;
             {
               nb::gil_scoped_release release;
               img = brdfcl::renderJob(d.runtime(), job);
             }
             return std::make_pair(imageToNumpy(std::move(img)), warnings);
           },
           "job"_a, "ibl"_a, "ibl_samples"_a, "ibl_samples_given"_a)
      .def("shade",
           [](Device& d, const brdfcl::GBuffer& g, const brdfcl::Scene& scene, const std::string& profile,
              const std::string& ibl, int iblSamples) {
             brdfcl::EvalOptions o;
             o.profile = brdfcl::parseProfile(profile);
             brdfcl::ShadeOptions so;
             so.ibl = brdfcl::parseIblMode(ibl);
             brdfcl::checkIblSamples(iblSamples);
             so.iblSamples = iblSamples;
             brdfcl::Image img;
             {
               nb::gil_scoped_release release;
               brdfcl::Shader shader(d.runtime(), scene, o);
               img = shader.shade(g, so);
             }
             return imageToNumpy(std::move(img));
           },
           "gbuffer"_a, "scene"_a, "profile"_a, "ibl"_a, "ibl_samples"_a);

  // Arrays in the device's memory (brdfcl/device_array.hpp): the Python front keeps their shape
  // and dtype; the array keeps its Device alive.
  nb::class_<brdfcl::DeviceArray>(m, "DeviceArray")
      .def("__init__",
           [](brdfcl::DeviceArray* self, Device& d, bool uint32, std::size_t size) {
             new (self) brdfcl::DeviceArray(d.runtime(), uint32 ? brdfcl::DeviceArray::Type::UInt32
                                                                : brdfcl::DeviceArray::Type::Float32, size);
           },
           "device"_a, "uint32"_a, "size"_a, nb::keep_alive<1, 2>())
      .def_prop_ro("size", &brdfcl::DeviceArray::size)
      .def("upload",
           [](brdfcl::DeviceArray& a, InArray host) {
             if (host.itemsize() != 4) throw Error("internal: device arrays hold 4-byte elements", 3);
             const std::size_t n = host.size();
             const void* p = host.data();
             nb::gil_scoped_release release;
             a.upload(p, n);
           },
           "host"_a.noconvert())
      .def("download",
           [](const brdfcl::DeviceArray& a, nb::ndarray<nb::c_contig, nb::device::cpu> host) {
             if (host.itemsize() != 4 || host.size() != a.size()) throw Error("internal: download into the wrong array", 3);
             void* p = host.data();
             nb::gil_scoped_release release;
             a.download(p, a.size());
           },
           "host"_a.noconvert());

  nb::class_<brdfcl::RenderJob>(m, "RenderJob")
      .def(nb::init<>())
      .def_rw("gltf", &brdfcl::RenderJob::gltf)
      .def_rw("scene", &brdfcl::RenderJob::scene)
      .def_rw("width", &brdfcl::RenderJob::width)
      .def_rw("height", &brdfcl::RenderJob::height)
      .def_rw("camera", &brdfcl::RenderJob::camera)
      .def_rw("gltf_scene", &brdfcl::RenderJob::gltfScene)
      .def_rw("variant", &brdfcl::RenderJob::variant)
      .def_rw("strict", &brdfcl::RenderJob::strict)
      .def_rw("allow_outside_uris", &brdfcl::RenderJob::allowOutsideUris)
      .def_rw("spp", &brdfcl::RenderJob::spp)
      .def_rw("spp_given", &brdfcl::RenderJob::sppGiven)
      .def_rw("environment", &brdfcl::RenderJob::environment)
      .def_rw("env_intensity", &brdfcl::RenderJob::envIntensity)
      .def_rw("env_rotation", &brdfcl::RenderJob::envRotation)
      .def_rw("environment_given", &brdfcl::RenderJob::environmentGiven)
      .def_rw("lights", &brdfcl::RenderJob::lights)
      .def("set_profile", [](brdfcl::RenderJob& j, const std::string& p) { j.model.profile = brdfcl::parseProfile(p); });

  nb::class_<brdfcl::GBuffer>(m, "GBuffer")
      .def_ro("width", &brdfcl::GBuffer::width)
      .def_ro("height", &brdfcl::GBuffer::height);
  m.def("read_gbuffer", [](const std::string& path, bool check) {
    brdfcl::GBufferReadOptions o;
    o.check = check;
    nb::gil_scoped_release release;
    return brdfcl::readGBuffer(path, o);
  }, "path"_a, "check"_a);
  m.def("gbuffer_from_dict", &gbufferFromDict, "channels"_a);
  m.def("check_gbuffer", [](const brdfcl::GBuffer& g, const std::string& shown) {
    nb::gil_scoped_release release;
    brdfcl::checkGBufferValues(g, shown, "check=False");
  }, "gbuffer"_a, "shown"_a);
  m.def("shade_camera_warning", &brdfcl::shadeCameraWarning, "scene_name"_a, "scene"_a, "gbuffer_name"_a, "gbuffer"_a);
  m.def("gbuffer_to_dict", [](brdfcl::GBuffer g) { return gbufferToDict(std::move(g)); }, "gbuffer"_a);
  m.def("write_gbuffer", [](const std::string& path, const brdfcl::GBuffer& g, bool half) {
    nb::gil_scoped_release release;
    brdfcl::writeGBuffer(path, g, half);
  }, "path"_a, "gbuffer"_a, "half"_a);

  m.def("read_exr", [](const std::string& path) {
    brdfcl::Image img;
    {
      nb::gil_scoped_release release;
      img.rgb = brdfcl::readExrRgb(path, img.width, img.height);
    }
    return imageToNumpy(std::move(img));
  }, "path"_a);

  // `brdfcl render`'s PNG pixels (exposure, PBR Neutral, sRGB, 8 bits) of a C-contiguous float32 (H, W, 3) array.
  m.def("tone_map", [](const nb::ndarray<const float, nb::ndim<3>, nb::c_contig, nb::device::cpu>& rgb, float exposure) {
    if (rgb.shape(2) != 3) throw Error("the image must have shape (H, W, 3), got " + std::to_string(rgb.shape(2)) + " channels");
    const std::size_t h = rgb.shape(0), w = rgb.shape(1);
    std::vector<std::uint8_t> bytes;
    {
      nb::gil_scoped_release release;
      bytes = brdfcl::displayRgb8(rgb.data(), h * w, exposure);
    }
    auto* held = new std::vector<std::uint8_t>(std::move(bytes));
    nb::capsule owner(held, [](void* p) noexcept { delete static_cast<std::vector<std::uint8_t>*>(p); });
    return nb::ndarray<nb::numpy, std::uint8_t>(held->data(), {h, w, 3}, owner);
  }, "rgb"_a, "exposure"_a);
  // `brdfcl diff`'s numbers: d per pixel (H, W), the report as JSON text, and the default colour
  // range; of two EXR files (the CLI's reader and checks) or two arrays of one shape.
  const auto diffResult = [](brdfcl::ImageDiff&& d, const std::string& nameA, const std::string& nameB) {
    const double range = brdfcl::defaultDiffRange(d.stats);
    const std::string json = brdfcl::imageDiffJson(d.stats, nameA, nameB, range, "");
    const auto h = std::size_t(d.stats.height), w = std::size_t(d.stats.width);
    return std::make_tuple(toNumpy(std::move(d.relative), {h, w}), json, range);
  };
  m.def("image_diff_files", [diffResult](const std::string& a, const std::string& b, double threshold, double floor) {
    brdfcl::ImageDiffOptions o;
    o.threshold = threshold;
    o.floor = floor;
    brdfcl::ImageDiff d;
    {
      nb::gil_scoped_release release;
      d = brdfcl::diffExrFiles(a, b, o);
    }
    return diffResult(std::move(d), a, b);
  }, "a"_a, "b"_a, "threshold"_a, "floor"_a);
  m.def("image_diff_arrays", [diffResult](const nb::ndarray<const float, nb::ndim<3>, nb::c_contig, nb::device::cpu>& a,
                                          const nb::ndarray<const float, nb::ndim<3>, nb::c_contig, nb::device::cpu>& b,
                                          double threshold, double floor, const std::string& nameA, const std::string& nameB) {
    if (a.shape(2) != 3 || b.shape(2) != 3 || a.shape(0) != b.shape(0) || a.shape(1) != b.shape(1))
      throw Error("internal: image_diff_arrays takes two (H, W, 3) arrays of one shape", 3);
    const int h = int(a.shape(0)), w = int(a.shape(1));
    brdfcl::ImageDiffOptions o;
    o.threshold = threshold;
    o.floor = floor;
    brdfcl::ImageDiff d;
    {
      nb::gil_scoped_release release;
      d = brdfcl::diffImages(std::vector<float>(a.data(), a.data() + a.size()),
                             std::vector<float>(b.data(), b.data() + b.size()), w, h, o);
    }
    return diffResult(std::move(d), nameA, nameB);
  }, "a"_a, "b"_a, "threshold"_a, "floor"_a, "name_a"_a, "name_b"_a);

  nb::class_<brdfcl::Scene>(m, "Scene");
  m.def("read_scene", &brdfcl::readScene, "path"_a, "allow_outside"_a = false);
  m.def("parse_scene", &brdfcl::parseScene, "json"_a, "name"_a, "base_dir"_a, "allow_outside"_a = false);
  m.def("spheres_scene", &brdfcl::spheresScene);

  // Importance sampling (docs/sampling.md): rows of V (and u) in, (rows, 7) Lx Ly Lz pdf wr wg wb
  // out; and the mixture's pdf of (L, V) rows. The Python side checks shapes and draws nothing.
  using Rows3 = nb::ndarray<const float, nb::ndim<2>, nb::c_contig, nb::device::cpu>;
  using Indices = nb::ndarray<const std::uint32_t, nb::ndim<1>, nb::c_contig, nb::device::cpu>;
  m.def("sample",
        [](Device& d, const Materials& mats, Rows3 V, nb::object index, Rows3 u, OutArray out,
           const brdfcl::EvalOptions& o) {
          const std::size_t n = V.shape(0);
          if (V.shape(1) != 3 || u.shape(0) != n || u.shape(1) != 3 || out.size() != 7 * n)
            throw Error("internal: sample arrays of the wrong shape", 3);
          const std::uint32_t* idx = nullptr;
          Indices held;
          if (!index.is_none()) {
            held = nb::cast<Indices>(index, false);
            if (held.shape(0) != n) throw Error("internal: sample indices of the wrong length", 3);
            idx = held.data();
          }
          // Rows normalized as the CLI's readers normalize them, so that the same numbers give the
          // same bits as `brdfcl sample`.
          const std::vector<float> unitV = unitRows(V.data(), n, "V");
          nb::gil_scoped_release release;
          d.evaluator(o).sample(mats.list, idx, unitV.data(), u.data(), n, out.data());
        },
        "device"_a, "materials"_a, "V"_a.noconvert(), "index"_a.none(), "u"_a.noconvert(), "out"_a.noconvert(),
        "options"_a);
  m.def("pdf",
        [](Device& d, const Materials& mats, Rows3 L, Rows3 V, nb::object index, OutArray out,
           const brdfcl::EvalOptions& o) {
          const std::size_t n = V.shape(0);
          if (L.shape(0) != n || L.shape(1) != 3 || V.shape(1) != 3 || out.size() != n)
            throw Error("internal: pdf arrays of the wrong shape", 3);
          brdfcl::Samples s;
          s.L = unitRows(L.data(), n, "L");
          s.V = unitRows(V.data(), n, "V");
          if (!index.is_none()) {
            const Indices held = nb::cast<Indices>(index, false);
            if (held.shape(0) != n) throw Error("internal: pdf indices of the wrong length", 3);
            s.material.assign(held.data(), held.data() + n);
          }
          nb::gil_scoped_release release;
          d.evaluator(o).pdf(mats.list, s, out.data());
        },
        "device"_a, "materials"_a, "L"_a.noconvert(), "V"_a.noconvert(), "index"_a.none(), "out"_a.noconvert(),
        "options"_a);
  m.def("draw_uniforms", [](std::uint64_t seed, std::size_t rows) {
    std::vector<float> u(3 * rows);
    brdfcl::Evaluator::drawUniforms(seed, 0, rows, u.data());
    return toNumpy(std::move(u), {rows, 3});
  }, "seed"_a, "rows"_a);
}
