// The one driver of the row paths (evaluate's rows, table rows, grid rows and device arrays in
// rows.cpp; sample and pdf in sampling.cpp): rows a launch takes, staged or not, the upload of the
// input columns, the whole-and-tail launches of a row kernel and the read-back of its results.
#pragma once
#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "eval/staging.hpp"
#include "runtime/opencl.hpp"

namespace brdfcl {

// A buffer holding a launch's rows and the element offset of its first row in it: nonzero only
// where a CPU device reads the caller's page-aligned memory in place.
struct Wrapped {
  cl::Buffer buffer;
  cl_uint at = 0;
};

// One column of host rows: `rowBytes` bytes a row from `data` on, in elements of `element` bytes
// (what the kernels' offsets count). A null `data` is no column: the kernel gets a null buffer.
struct Column {
  const void* data = nullptr;
  std::size_t rowBytes = 0, element = 4;
};

// The whole groups of `lanes` rows (a work-item each) on `whole`, then the partial group on
// `tail`; `materials` > 0 adds a second dimension. `local` > 0: the work-group size of a launch
// of at least 8 groups of it (0: the runtime chooses). The events, when given, get the launches.
void launchWholeAndTail(cl::CommandQueue& q, cl::Kernel& whole, cl::Kernel& tail, std::size_t rows, std::size_t lanes,
                        std::size_t local = 0, std::size_t materials = 0, cl::Event* wholeDone = nullptr,
                        cl::Event* tailDone = nullptr);

// A read-only device copy of `bytes` at p (4 zero bytes for none).
cl::Buffer deviceCopy(const cl::Context& ctx, const void* p, std::size_t bytes);

// One evaluation's launches of a row kernel: the caller's memory wrapped (or copied) and kept
// alive until the device is done with it, one bad-row slot a launch, and a drain that waits for
// the device on every way out (an error included) before that memory may be reused or freed.
class RowDriver {
 public:
  // Where the rows are: host memory, which unstaged launches read in place (the kernel takes
  // element offsets) or from copies (it takes none); or device buffers, never staged.
  enum class Rows { InPlace, Copied, Device };

  // The kernel `name` (whole groups of shape.lanes) and `name`_tail (the partial group at the
  // end); shape.groupSize 0 leaves the work-group size to the runtime.
  RowDriver(Runtime& rt, const cl::Program& program, const std::string& name, const LaneShape& shape,
            Rows rows = Rows::InPlace);
  ~RowDriver();
  RowDriver(const RowDriver&) = delete;
  RowDriver& operator=(const RowDriver&) = delete;

  bool staged() const { return stage_ != nullptr; }

  // Rows a launch takes: every `rowBytes` row buffer within the device's largest allocation, the
  // kernel's 32-bit row numbers within `launchLimit`, a multiple of `granule` (at least one),
  // within the staging slots when staged, and at most `asked` (0: no limit asked).
  std::size_t rowsPerLaunch(std::size_t launchLimit, std::size_t asked, std::size_t rowBytes,
                            std::size_t granule) const;

  // Runs the kernel over `count` rows, `chunk` a launch: each launch uploads its rows of
  // `inputs`, gives `output` (`outBytes` a row) its rows, and calls
  // setArgs(first row, rows, the inputs' buffers in order, the output's buffer).
  template <class SetArgs>
  void run(std::size_t count, std::size_t chunk, std::initializer_list<Column> inputs, void* output,
           std::size_t outBytes, SetArgs&& setArgs) {
    std::vector<Wrapped> in;
    for (std::size_t first = 0; first < count; first += chunk) {
      const std::size_t n = std::min(chunk, count - first);
      begin();
      in.clear();
      for (const Column& c : inputs)
        in.push_back(c.data ? this->in(static_cast<const char*>(c.data) + c.rowBytes * first, c.rowBytes * n, c.element)
                            : Wrapped{});
      const Wrapped result = out(static_cast<char*>(output) + outBytes * first, outBytes * n);
      setArgs(first, n, in, result);
      launch(n, 0);
    }
  }

  // The steps of one launch, for callers whose launches are not one run of rows (the grid).
  // begin() starts a launch: with staging, on the next slot once its last results are delivered.
  void begin();
  // The launch's next input: the caller's memory, a copy of it, or its staged copy.
  Wrapped in(const void* p, std::size_t bytes, std::size_t element);
  // Where the launch writes `bytes` of 4-byte elements that belong at p.
  Wrapped out(void* p, std::size_t bytes);
  // Where a grid launch writes `materials` stretches of `rows` rows of 3 floats that belong
  // `stride` rows apart from p on, and the stride the launch writes them with (a staged launch
  // packs them).
  std::pair<Wrapped, std::size_t> outGrid(float* p, std::size_t materials, std::size_t rows, std::size_t stride);
  // The arguments of the next launch, for both entry points.
  template <class... A>
  void args(const A&... a) {
    setArgs(kernel_, a...);
    setArgs(tail_, a...);
  }
  // A slot the launch lowers to its first bad row (relative to `firstRow`).
  cl::Buffer badRowSlot(std::size_t firstRow);
  // Runs the kernel (arguments set) over `rows` rows, for `materials` materials (0: a 1-D
  // launch), and brings its output (if any) to the host: at once when copied, free on CPU devices
  // in place, when its slot comes round again or at finish() when staged.
  // The events, when given, get the launches (for their profiling times).
  void launch(std::size_t rows, std::size_t materials, cl::Event* wholeDone = nullptr, cl::Event* tailDone = nullptr);
  // Waits for every launch and delivers every result.
  void finish();
  // The lowest bad row of every launch, or `none`; waits for the launches.
  std::size_t lowestBadRow(std::size_t none);

 private:
  template <class... A>
  static void setArgs(cl::Kernel& kernel, const A&... args) {
    cl_uint i = 0;
    (kernel.setArg(i++, args), ...);
  }
  Wrapped wrap(void* p, std::size_t bytes, std::size_t element, cl_mem_flags flags);

  const cl::Context& ctx_;
  cl::CommandQueue& q_;
  const DeviceInfo& info_;
  Rows rows_;
  cl::Kernel kernel_, tail_;
  std::size_t lanes_, local_;
  std::vector<cl::Buffer> keep_;
  std::vector<std::pair<std::size_t, cl::Buffer>> bad_;  // (first row of the launch, its slot)
  Wrapped result_;                                       // the unstaged launch's output
  void* resultHost_ = nullptr;                           // where a copied output goes
  std::size_t resultBytes_ = 0;                          // what of result_ the host reads back
  std::unique_ptr<Staging> stage_;  // declared last: it waits for its queues before the kernels go
  int input_ = 0;
};

}  // namespace brdfcl
