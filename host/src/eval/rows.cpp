// Evaluator::evaluateRows / evaluateTableRows / evaluateGridRows: the caller's rows handed to the
// row kernels (eval_rows, eval_table_rows, eval_grid_rows in kernels/eval.cl) where they lie, a
// launch at a time. The device normalizes and checks the rows; only the lowest bad row comes back.
// The launches are eval/row_driver.hpp's: CPU devices read and write the caller's pages in place;
// other devices get the rows through pinned staging, double buffered (eval/staging.hpp).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "brdfcl/error.hpp"
#include "brdfcl/evaluator.hpp"
#include "eval/batch.hpp"
#include "eval/device_array.hpp"
#include "eval/material_range.hpp"
#include "eval/row_driver.hpp"
#include "runtime/opencl.hpp"

namespace brdfcl {

namespace {

cl_uint count32(std::size_t n) { return cl_uint(std::min<std::size_t>(n, UINT32_MAX)); }

// A device array's check against what evaluate() takes for it.
void checkArray(const Runtime& rt, const DeviceArray& a, const char* name, DeviceArray::Type type, std::size_t size,
                std::size_t rows) {
  if (!a.belongsTo(rt))
    throw Error(fmt::format("device array {} belongs to another Runtime; create it on the evaluator's Runtime", name));
  if (a.type() != type)
    throw Error(fmt::format("device array {} must be {}", name, type == DeviceArray::Type::Float32 ? "float32" : "uint32"));
  if (a.size() != size)
    throw Error(fmt::format("device array {} holds {} elements; {} rows need {}", name, a.size(), rows, size));
}

// The message for bad row `i` of device-resident rows, worded as evaluate() words it.
[[noreturn]] void throwDeviceRowError(const DeviceArray& L, const DeviceArray& V, const DeviceArray* material,
                                      std::size_t materialCount, std::size_t i) {
  std::uint32_t index = 0;
  if (material) material->download(&index, 1, i);
  if (index >= materialCount)
    throw Error(fmt::format("sample {}: material index {} out of range ({} materials)", i, index, materialCount));
  float d[6];
  L.download(d, 3, 3 * i);
  V.download(d + 3, 3, 3 * i);
  static const char* const kNames[6] = {"Lx", "Ly", "Lz", "Vx", "Vy", "Vz"};
  for (int k = 0; k < 6; ++k)
    if (!std::isfinite(d[k]))
      throw Error(fmt::format("sample {}: {} is not finite: {}", i, kNames[k], std::isnan(d[k]) ? "nan" : d[k] > 0 ? "inf" : "-inf"));
  throw Error(fmt::format("sample {}: {} is zero", i, d[0] == 0 && d[1] == 0 && d[2] == 0 ? "L" : "V"));
}

}  // namespace

std::size_t Evaluator::evaluateRows(const std::vector<MaterialParams>& materials, const Rows& rows, float* rgb,
                                    bool normalize) {
  if (rows.count == 0) return 0;
  if (!rows.L || !rows.V || !rgb) throw Error("internal: rows without data", 3);
  if (rows.index && rows.index32) throw Error("internal: rows with two kinds of index", 3);
  Batch b = prepare(materials, Kernels::Rows);
  try {
    RowDriver run(rt_, b.program, "eval_rows", b.shape);
    const Column index = rows.index ? Column{rows.index, 8, 8} : Column{rows.index32, 4, 4};
    run.run(rows.count, run.rowsPerLaunch(launchLimit(), rows.launch, 12, 16), {{rows.L, 12}, {rows.V, 12}, index},
            rgb, 12, [&](std::size_t first, std::size_t n, const std::vector<Wrapped>& in, const Wrapped& out) {
              run.args(in[0].buffer, in[0].at, in[1].buffer, in[1].at, in[2].buffer, in[2].at,
                       cl_int(rows.index != nullptr), count32(materials.size()), cl_uint(n), cl_int(normalize),
                       b.materials, b.tableBuffer, b.tableSize, out.buffer, out.at, run.badRowSlot(first));
            });
    return run.lowestBadRow(rows.count);
  } catch (const cl::Error&) {
    rethrowOpenCL("evaluating rows");
  }
}

void Evaluator::evaluate(const std::vector<MaterialParams>& materials, const DeviceArray& L, const DeviceArray& V,
                         const DeviceArray* material, DeviceArray& rgb, bool normalize) {
  using T = DeviceArray::Type;
  if (L.size() % 3)
    throw Error(fmt::format("device array L holds {} elements; give 3 floats a row", L.size()));
  const std::size_t n = L.size() / 3;
  if (n > UINT32_MAX / 3) throw Error(fmt::format("device arrays of {} rows are too long; use at most {} rows a call", n, UINT32_MAX / 3));
  checkArray(rt_, L, "L", T::Float32, 3 * n, n);
  checkArray(rt_, V, "V", T::Float32, 3 * n, n);
  if (material) checkArray(rt_, *material, "material", T::UInt32, n, n);
  checkArray(rt_, rgb, "rgb", T::Float32, 3 * n, n);
  if (&rgb.impl() == &L.impl() || &rgb.impl() == &V.impl())
    throw Error("device array rgb must not be L or V; give the results their own array");
  Batch b = prepare(materials, Kernels::Rows);
  if (n == 0) return;
  std::size_t bad = n;
  try {
    RowDriver run(rt_, b.program, "eval_rows", b.shape, RowDriver::Rows::Device);
    const std::size_t chunk = run.rowsPerLaunch(launchLimit(), 0, 12, 16);
    const cl::Buffer none;
    for (std::size_t first = 0; first < n; first += chunk) {
      const std::size_t count = std::min(chunk, n - first);
      run.begin();
      run.args(L.impl().buffer, cl_uint(3 * first), V.impl().buffer, cl_uint(3 * first),
               material ? material->impl().buffer : none, cl_uint(material ? first : 0), cl_int(0),
               count32(materials.size()), cl_uint(count), cl_int(normalize), b.materials, b.tableBuffer, b.tableSize,
               rgb.impl().buffer, cl_uint(3 * first), run.badRowSlot(first));
      run.launch(count, 0);
    }
    bad = run.lowestBadRow(n);
  } catch (const cl::Error&) {
    rethrowOpenCL("evaluating device rows");
  }
  if (bad < n) throwDeviceRowError(L, V, material, materials.size(), bad);
}

std::size_t Evaluator::evaluateTableRows(const std::vector<MaterialParams>& materials, const float* rows,
                                         std::size_t count, float* rgb, std::size_t launch) {
  if (count == 0) return 0;
  if (!rows || !rgb) throw Error("internal: table rows without data", 3);
  Batch b = prepare(materials, Kernels::Table);
  try {
    RowDriver run(rt_, b.program, "eval_table_rows", b.shape);
    run.run(count, run.rowsPerLaunch(launchLimit(), launch, 28, 16), {{rows, 28}}, rgb, 12,
            [&](std::size_t first, std::size_t n, const std::vector<Wrapped>& in, const Wrapped& out) {
              run.args(in[0].buffer, in[0].at, count32(materials.size()), cl_uint(n), b.materials, b.tableBuffer,
                       b.tableSize, out.buffer, out.at, run.badRowSlot(first));
            });
    return run.lowestBadRow(count);
  } catch (const cl::Error&) {
    rethrowOpenCL("evaluating sample rows");
  }
}

std::size_t Evaluator::evaluateGridRows(const std::vector<MaterialParams>& materials, const Rows& rows, float* rgb,
                                        bool normalize, std::size_t firstMaterial, std::size_t materialCount) {
  checkMaterialRange(firstMaterial, materialCount, materials.size());
  const std::size_t n = rows.count, nm = materialCount;
  if (n == 0 || nm == 0) return n;
  if (!rows.L || !rows.V || !rgb) throw Error("internal: rows without data", 3);
  Batch b = prepare(materials, Kernels::Grid);
  try {
    RowDriver run(rt_, b.program, "eval_grid_rows", b.shape);
    const std::size_t chunk = run.rowsPerLaunch(launchLimit(), rows.launch, 12, 16);
    for (std::size_t first = 0; first < n; first += chunk) {
      const std::size_t count = std::min(chunk, n - first);
      // Materials in groups whose stretch of the output, (mc - 1) * n + count rows (mc * count
      // staged), fits a launch.
      const std::size_t perLaunch = run.staged() ? std::max<std::size_t>(1, chunk / count)
                                                 : std::max<std::size_t>(1, chunk > count ? (chunk - count) / n + 1 : 1);
      for (std::size_t m0 = 0; m0 < nm; m0 += perLaunch) {
        const std::size_t mc = std::min(perLaunch, nm - m0);
        // Staged, every launch takes its own copy of the directions (the slots alternate).
        run.begin();
        const Wrapped L = run.in(rows.L + 3 * first, 12 * count, 4), V = run.in(rows.V + 3 * first, 12 * count, 4);
        const auto [out, stride] = run.outGrid(rgb + 3 * (m0 * n + first), mc, count, n);
        run.args(L.buffer, L.at, V.buffer, V.at, cl_uint(count), cl_int(normalize), b.materials,
                cl_uint(firstMaterial + m0), b.tableBuffer, b.tableSize, out.buffer, out.at, cl_ulong(stride),
                run.badRowSlot(first));
        run.launch(count, mc);
      }
    }
    return run.lowestBadRow(n);
  } catch (const cl::Error&) {
    rethrowOpenCL("evaluating the material x direction grid");
  }
}

}  // namespace brdfcl
