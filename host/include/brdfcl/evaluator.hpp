// Batch BRDF evaluation on an OpenCL device: f(L, V) in 1/sr, no cosine, per sample or per
// material x direction grid. Owns the baked sheen albedo tables it needs.
#pragma once
#include <cstddef>
#include <cstdint>
#include <memory>
#include <mutex>
#include <vector>

#include "brdfcl/device_array.hpp"
#include "brdfcl/io.hpp"
#include "brdfcl/material.hpp"
#include "brdfcl/runtime.hpp"
#include "kernels/common/material_layout.h"

namespace brdfcl {

// Directional albedo E(mu, r) of the white sheen lobe, looked up with mu = N.V (or N.L) and
// r = sheenRoughness, both in [0, 1]. Nodes sit at mu = s^2, r = t^2 for s, t uniform in [0, 1]
// (x fastest): E is steepest at grazing angles and low roughness, so the grid is densest there.
struct SheenAlbedoTable {
  static constexpr std::size_t kSize = 320;
  SheenDistribution distribution;
  SheenVisibility visibility;
  std::size_t width = kSize, height = kSize;
  std::vector<float> values;  // height rows of width
  float lookup(float mu, float sheenRoughness) const;  // bilinear, as the kernels do it
  // E along mu for one sheenRoughness: the two rows lookup blends, blended once (width values).
  std::vector<float> rowAt(float sheenRoughness) const;
};

// Bakes E by numerical integration on the device (kernels/sheen_albedo.cl).
// nodesPerPanel sets the quadrature order (tests double it to prove convergence).
SheenAlbedoTable bakeSheenAlbedo(Runtime& rt, SheenDistribution d, SheenVisibility v,
                                 std::size_t size = SheenAlbedoTable::kSize, int nodesPerPanel = 12);

// The table for the default size from the on-disk cache ($XDG_CACHE_HOME or ~/.cache, then
// brdfcl/), baking and storing it on a miss. The key holds the device, the options and a hash of
// the kernel source, so a changed kernel never reads a stale table. An unwritable cache is skipped.
SheenAlbedoTable cachedSheenAlbedo(Runtime& rt, SheenDistribution d, SheenVisibility v);

class SoaBatch;

// Thread safety. One Runtime may be shared by any number of threads (see runtime.hpp), and so
// may one Evaluator: evaluate(), evaluateGrid() and sheenAlbedo() may run concurrently on the
// same Evaluator (the table is baked once, under a lock; options() never changes). Each call
// creates its own kernel object and wraps only its caller's memory (the row kernels), or takes its
// planes from the evaluator's pool (scratch SoaBatches, e.g. evaluateArrays on float64; under a
// lock, a set serves one call at a time), so concurrent calls never share kernel arguments or
// memory and give bit-for-bit the results of the same calls made one after another. The pool
// keeps up to four idle sets for the next calls (about 40 MiB each at the default chunk) until
// the Evaluator is destroyed. The simplest pattern
// is one Evaluator per thread on one shared Runtime. A SoaBatch is NOT thread-safe: use each
// batch from one thread at a time (different batches, even of one Evaluator, may run
// concurrently). The Evaluator and Runtime must outlive every call and every SoaBatch.
// Tests: tests/unit/test_threads.cpp.
class Evaluator {
 public:
  // Materials up to which a batch reads a row of the sheen albedo table a material, blended once
  // for its sheenRoughness (kernels/brdf/material.h, BRDFCL_E_ROW); a larger batch blends two
  // rows of the table at every lookup. 1.3 MB of rows at most.
  static constexpr std::size_t kMaxSheenRows = 1024;

  Evaluator(Runtime& rt, EvalOptions options);
  ~Evaluator();

  const EvalOptions& options() const { return options_; }

  // One result per sample; samples.material indexes `materials`. Returns rgb, 3 floats a sample.
  // L and V are expected as unit vectors (readSamples normalizes them); a direction at or below
  // the horizon gives f = 0. Throws brdfcl::Error (exit code 2), naming the material or sample:
  //   "material 3: roughness must be a number in [0, 1], got nan" -- any field outside the glTF
  //     domain readMaterials enforces ([0, 1]; >= 0 for draftIntensity and emissive; finite for
  //     anisotropyRotation), NaN and infinities included;
  //   "sample 7: Vz is not finite: inf" -- a NaN or infinite direction component;
  //   "sample 7: material index 5 out of range (2 materials)".
  std::vector<float> evaluate(const std::vector<MaterialParams>& materials, const Samples& samples);

  // Every material x every direction pair, material-major. samples.material is ignored.
  // Materials and directions are checked as in evaluate().
  std::vector<float> evaluateGrid(const std::vector<MaterialParams>& materials, const Samples& samples);
  // Only the rows of materials [firstMaterial, firstMaterial + materialCount), bit-identical to
  // those rows of the whole grid. (The kernel is specialized for the layers `materials` use, so
  // evaluating a sub-list instead may differ in the last bit.)
  std::vector<float> evaluateGrid(const std::vector<MaterialParams>& materials, const Samples& samples,
                                  std::size_t firstMaterial, std::size_t materialCount);

  // The same results written to caller memory (3 floats a sample; materials x samples x 3 for
  // the grid) instead of a fresh vector, whose pages a large call would fault in every time.
  void evaluate(const std::vector<MaterialParams>& materials, const Samples& samples, float* rgb);
  void evaluateGrid(const std::vector<MaterialParams>& materials, const Samples& samples, float* rgb);
  void evaluateGrid(const std::vector<MaterialParams>& materials, const Samples& samples, std::size_t firstMaterial,
                    std::size_t materialCount, float* rgb);

  // Rows where the caller holds them, evaluated in place: the kernels read `rows.count` rows of
  // L and V (3 floats each, contiguous) and the material indices, and write 3 floats a row
  // to rgb, all through CL_MEM_USE_HOST_PTR on this very memory (no copy on CPU devices). With
  // `normalize` each direction is normalized on the device by the samples readers' arithmetic
  // (the bits of normalizeDirection); without, L and V must be unit vectors. Returns the lowest
  // row that holds no direction (NaN, infinite or zero) or whose index is not in
  // [0, materials.size()), or rows.count when none does; rgb is then undefined for that row and
  // the caller words the problem (evaluateArrays, evaluate(), evaluateGrid() do). Materials are
  // checked as in evaluate().
  struct Rows {
    const float* L = nullptr;
    const float* V = nullptr;
    const std::int64_t* index = nullptr;  // one material index a row (numpy's int64), or nullptr
    std::size_t count = 0;
    std::size_t launch = 0;                  // rows a launch takes at most (0: as many as the device allows)
    const std::uint32_t* index32 = nullptr;  // instead of `index`: Samples::material; neither: material 0
  };
  std::size_t evaluateRows(const std::vector<MaterialParams>& materials, const Rows& rows, float* rgb,
                           bool normalize);
  // A samples file's rows as they lie in memory (the data of a float32 C-order NPY of shape
  // (count, 7)): the material index (a float holding an integer), then Lx Ly Lz Vx Vy Vz.
  // Evaluated in place as evaluateRows does, checked and normalized on the device as the samples
  // readers would: returns the lowest row whose directions are not finite and non-zero or whose
  // index is no integer in [0, materials.size()), or count. `launch` as in Rows.
  std::size_t evaluateTableRows(const std::vector<MaterialParams>& materials, const float* rows, std::size_t count,
                                float* rgb, std::size_t launch = 0);
  // Every material of [firstMaterial, firstMaterial + materialCount) x every row, material-major
  // (the indices are ignored): material k's row i at rgb + 3 * ((k - firstMaterial) * rows.count + i).
  std::size_t evaluateGridRows(const std::vector<MaterialParams>& materials, const Rows& rows, float* rgb,
                               bool normalize, std::size_t firstMaterial, std::size_t materialCount);

  // evaluate() on rows that stay in device memory (brdfcl/device_array.hpp), for chained work:
  // L and V float32, 3 a row (unit vectors, or normalized on the device with `normalize`);
  // `material` uint32, one index a row (nullptr: material 0); rgb float32, 3 a row, written on the
  // device and left there. Only a bad row crosses the bus, read back to word the error as
  // evaluate() does ("sample 7: Vz is not finite: inf", "sample 7: material index 5 out of range
  // (2 materials)", "sample 7: L is zero"). Every array must belong to this evaluator's Runtime
  // ("device array L belongs to another Runtime; create it on the evaluator's Runtime") and have
  // the type and size of its part.
  void evaluate(const std::vector<MaterialParams>& materials, const DeviceArray& L, const DeviceArray& V,
                const DeviceArray* material, DeviceArray& rgb, bool normalize = false);

  // The table this evaluator's sheen options use (baked on first use).
  const SheenAlbedoTable& sheenAlbedo();

  // Samples one kernel launch takes at most: a fixed bound, lowered to fit every plane in the
  // device's largest allocation. Larger batches are split into launches of this size.
  std::size_t launchLimit() const;

  // ---- Importance sampling (docs/sampling.md) ----
  // One direction L per row drawn from the material's lobes, as a path tracer's one-sample MIS
  // draws it: a lobe chosen by u3 with probabilities from each lobe's estimated albedo at V (the
  // options' lobe alone under --lobe), then L from that lobe's sampler with (u1, u2). Writes 7
  // floats a row, Lx Ly Lz pdf wr wg wb: pdf is the mixture's density of L (solid angle) and
  // w = f(L, V) N.L / pdf with f of the options' profile and lobe; all 0 where no direction
  // above the horizon came out (or V.z <= 0). `view` holds 3 floats a row (normalized here),
  // `material` one index a row (nullptr: material 0), `u` 3 floats a row in [0, 1).
  // Throws brdfcl::Error naming the row: "row 7: Vz is not finite: inf",
  // "row 7: material index 5 out of range (2 materials)", "row 7: u2 must be in [0, 1), got 1".
  void sample(const std::vector<MaterialParams>& materials, const std::uint32_t* material, const float* view,
              const float* u, std::size_t count, float* out);
  std::vector<float> sample(const std::vector<MaterialParams>& materials, const std::vector<std::uint32_t>& material,
                            const std::vector<float>& view, const std::vector<float>& u);
  // The density sample() draws L with, per sample (L and V as evaluate() takes them); 0 where
  // N.L <= 0 or N.V <= 0. Checks as evaluate().
  void pdf(const std::vector<MaterialParams>& materials, const Samples& samples, float* pdf);
  std::vector<float> pdf(const std::vector<MaterialParams>& materials, const Samples& samples);
  // The counter-based uniforms of `brdfcl sample --count --seed`: u_j of global row r is
  // SplitMix64's output number 3 r + j (from 0) of the stream seeded with `seed`, so any chunking
  // or device draws the same numbers. Fills 3 floats a row for rows [firstRow, firstRow + rows).
  static void drawUniforms(std::uint64_t seed, std::uint64_t firstRow, std::size_t rows, float* u);

 private:
  friend class SoaBatch;
  struct Batch;
  enum class Kernels : unsigned;  // which of eval.cl's entry points a batch's program holds (eval/batch.hpp)
  struct Planes;  // a batch's page-aligned host planes and the device buffers wrapping them
  Batch prepare(const std::vector<MaterialParams>& materials, Kernels kernels);
  // The pool of planes scratch batches reuse, so that repeated calls neither allocate nor fault
  // fresh pages: take returns idle planes of exactly `floats` per plane, or nullptr.
  std::unique_ptr<Planes> takePlanes(std::size_t floats);
  void givePlanes(std::unique_ptr<Planes> planes);

  Runtime& rt_;
  EvalOptions options_;
  std::mutex tableMutex_;                    // guards the lazy bake of table_
  std::unique_ptr<SheenAlbedoTable> table_;  // set once, never replaced
  std::mutex poolMutex_;                     // guards pool_
  std::vector<std::unique_ptr<Planes>> pool_;
};

// Samples as structure-of-arrays planes in page-aligned host memory that the device reads and
// writes in place (CL_MEM_USE_HOST_PTR: zero-copy on CPU devices). Fill the planes, run(), read
// the result planes; run() again after changing them. This is the throughput path: evaluate()
// uses it chunk by chunk, and the benchmarks and their C++ peers read the very same arrays.
class SoaBatch {
 public:
  // Planes are padded to a multiple of 16 samples: a multiple of every lane width a device may
  // use (laneShape in runtime.hpp: 1, 4, 8 or 16).
  static constexpr std::size_t kLanes = 16;

  // Room for `capacity` samples of `materials` (copied, checked as evaluate() checks them, and
  // packed now). Throws "no materials to evaluate" for an empty list and "out of host memory
  // allocating <n> MiB for a batch" when the planes cannot be allocated. The planes themselves
  // are not checked: this is the throughput path, so keep NaN and infinities out of them.
  SoaBatch(Evaluator& evaluator, const std::vector<MaterialParams>& materials, std::size_t capacity);
  // A batch for callers that write every input lane they run (the first count(), and zeros up
  // to capacity() before a shorter run), as evaluate(), evaluateArrays and evaluateStream do:
  // its planes come from the evaluator's pool and go back to it, holding whatever the last
  // user left. Thread-safe like the Evaluator; the pool keeps at most a few idle sets.
  struct Scratch {};
  SoaBatch(Evaluator& evaluator, const std::vector<MaterialParams>& materials, std::size_t capacity, Scratch);
  ~SoaBatch();
  SoaBatch(const SoaBatch&) = delete;
  SoaBatch& operator=(const SoaBatch&) = delete;

  std::size_t capacity() const { return capacity_; }  // requested capacity rounded up to kLanes
  // Samples the next run() evaluates (<= capacity). Lanes past `count` in the last group of 16
  // are evaluated too; keep them at L = V = 0 (as allocated), which gives f = 0.
  void setCount(std::size_t count);
  std::size_t count() const { return count_; }

  float* direction(int k);            // plane k of Lx Ly Lz Vx Vy Vz
  std::uint32_t* materialIndex();      // one per sample, < materials.size()
  const float* result(int c) const;    // plane c of r g b, valid after run()
  const float* directionPlane(int k) const { return planes_[k]; }
  const std::uint32_t* materialIndexPlane() const { return index_; }
  float* resultPlane(int c) { return planes_[6 + c]; }  // for peers writing where the kernel does

  // What the kernel reads besides the samples, for peers that compute the same thing.
  const std::vector<brdfcl_material>& packedMaterials() const { return packed_; }
  const std::vector<float>& sheenAlbedoValues() const { return tableValues_; }
  int sheenAlbedoSize() const { return tableSize_; }

  void run();  // start() then finish()
  // run() in two halves: start() enqueues the launch and returns at once; finish() waits for
  // it. Between the two, leave this batch's planes alone (fill another batch meanwhile).
  void start();
  void finish();
  // Device time of the last run's kernel alone (its profiling event), without the copies a
  // device that caches host memory (a GPU) makes; 0 before the first run.
  double lastKernelSeconds() const;


 private:
  SoaBatch(Evaluator& evaluator, const std::vector<MaterialParams>& materials, std::size_t capacity, bool pooled);
  void release();  // frees (or pools) the device buffers and the host planes they wrap

  Evaluator& ev_;
  bool pooled_ = false;
  std::unique_ptr<Evaluator::Planes> set_;
  std::size_t capacity_ = 0, count_ = 0;
  std::size_t allocated_ = 0;  // floats a plane holds: capacity padded to whole work-groups
  float* planes_[9] = {};  // Lx Ly Lz Vx Vy Vz r g b, each page-aligned
  std::uint32_t* index_ = nullptr;
  bool inputsChanged_ = true;
  bool running_ = false;
  std::vector<brdfcl_material> packed_;
  std::vector<float> tableValues_;
  int tableSize_ = 2;
  struct Device;
  std::unique_ptr<Device> device_;
};

}  // namespace brdfcl
