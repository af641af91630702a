// brdfcl._core's Device: made on a device by index or name, it evaluates the caller's direction
// rows in place (per sample or as a materials x samples grid), directional albedo and LUT bakes.
#include <nanobind/stl/map.h>
#include <nanobind/stl/string.h>
#include <nanobind/stl/vector.h>

#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "bindings.hpp"
#include "brdfcl/albedo.hpp"
#include "brdfcl/arrays.hpp"
#include "brdfcl/device_array.hpp"
#include "brdfcl/error.hpp"
#include "brdfcl/lut.hpp"
#include "host/src/model/pack.hpp"

using namespace nanobind::literals;

namespace brdfcl_python {
namespace {

using brdfcl::Error;

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

}  // namespace

void bindEval(nb::class_<Device>& device) {
  device
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
           "kind"_a, "size"_a, "sheen_visibility"_a, "sheen_distribution"_a);
}

}  // namespace brdfcl_python
