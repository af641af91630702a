// brdfcl._core's importance sampling (docs/sampling.md): sample and pdf of the caller's rows, and
// the counter-based uniforms that `brdfcl sample --seed` draws.
#include <cstdint>
#include <string>
#include <vector>

#include "bindings.hpp"
#include "brdfcl/error.hpp"
#include "brdfcl/io.hpp"

using namespace nanobind::literals;

namespace brdfcl_python {
namespace {

using brdfcl::Error;

// Float rows normalized by the library's reader arithmetic (brdfcl::normalizeDirection), for the
// calls whose CLI counterparts read their directions from files.
std::vector<float> unitRows(const float* rows, std::size_t n, const char* name) {
  std::vector<float> out(3 * n);
  for (std::size_t i = 0; i < n; ++i) {
    const double d[3] = {rows[3 * i], rows[3 * i + 1], rows[3 * i + 2]};
    if (!brdfcl::normalizeDirection(d, &out[3 * i]))
      throw Error(std::string(name) + " row " + std::to_string(i) + " is not a finite non-zero direction");
  }
  return out;
}

}  // namespace

void bindSample(nb::module_& m) {
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

}  // namespace brdfcl_python
