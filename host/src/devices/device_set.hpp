// Several OpenCL devices of one machine working on one batch: `--device all` or a list such as
// `--device 0,2`. Each batch is split into contiguous ranges in proportion to each device's
// measured speed, run concurrently (one host thread a device) and written into one output.
#pragma once
#include <cstddef>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "brdfcl/evaluator.hpp"
#include "brdfcl/runtime.hpp"

namespace brdfcl {

// True for "all" and for lists ("0,2"): selectors that name several devices.
bool isDeviceList(const std::string& selector);

// The device indexes a list names, in the order given ("all": every device). Throws (exit 2),
// naming `source` (e.g. "--device") and the valid indexes:
//   "--device 0,9: device index 9 out of range; valid indexes: 0-1 (see 'brdfcl devices')"
//   "--device 0,0: device 0 is listed twice; valid indexes: 0-1 (see 'brdfcl devices')"
//   "--device 0,x: 'x' is not a device index; use all or a list such as 0,1; valid indexes: 0-1 ..."
std::vector<std::size_t> parseDeviceList(const std::string& selector, std::size_t deviceCount,
                                         const std::string& source = "--device");

// One Runtime per device and a running estimate of each one's speed.
// Byte-identity: every sample is evaluated whole on one device, with the program that device
// compiles from the same source and options, so on devices of one kind (same platform and
// type, e.g. several PoCL pthread devices) the output equals a single-device run byte for byte,
// whatever the split. Across kinds (PoCL and Intel, CPU and GPU) each sample carries its
// device's rounding: within 1e-5 relative of each other, not byte-identical.
class DeviceSet {
 public:
  // selector: "all", a list of indexes, or anything Runtime accepts (one device).
  explicit DeviceSet(const std::string& selector);
  ~DeviceSet();

  std::size_t size() const { return runtimes_.size(); }
  Runtime& runtime(std::size_t k) { return *runtimes_[k]; }

  // [first, count) for each device: n items split in proportion to the speeds, each boundary a
  // multiple of `grain` (the last device takes the remainder).
  struct Range {
    std::size_t first = 0, count = 0;
  };
  std::vector<Range> split(std::size_t n, std::size_t grain) const;

  // Runs work(k, first, count) for every device k with a non-empty range, concurrently (one
  // thread a device; one device runs on the calling thread), times each, and updates the speeds.
  // Rethrows the first device's error after every thread has finished.
  void run(std::size_t n, std::size_t grain, const std::function<void(std::size_t, std::size_t, std::size_t)>& work);

  // Items a second each device managed on its last range (the compute units until measured).
  std::vector<double> speeds() const;

 private:
  std::vector<std::unique_ptr<Runtime>> runtimes_;
  mutable std::mutex mutex_;
  std::vector<double> speed_;
};

// Evaluator's evaluate() and evaluateGrid() over a DeviceSet: one Evaluator per device, with
// the results of a single-device run (see DeviceSet for what is byte-identical).
class MultiEvaluator {
 public:
  MultiEvaluator(DeviceSet& devices, EvalOptions options);
  ~MultiEvaluator();

  const EvalOptions& options() const { return options_; }
  DeviceSet& devices() { return devices_; }
  Evaluator& evaluator(std::size_t k) { return *evaluators_[k]; }

  std::vector<float> evaluate(const std::vector<MaterialParams>& materials, const Samples& samples);
  std::vector<float> evaluateGrid(const std::vector<MaterialParams>& materials, const Samples& samples);
  // Rows [firstMaterial, firstMaterial + materialCount) of the grid, as Evaluator's overload.
  std::vector<float> evaluateGrid(const std::vector<MaterialParams>& materials, const Samples& samples,
                                  std::size_t firstMaterial, std::size_t materialCount);

  // Repeated evaluate() calls on one material list (the stream): the materials are checked and
  // every device's program built once, here; each call splits its samples across the devices,
  // each range read and written in place by the row kernel.
  class Batches {
   public:
    Batches(MultiEvaluator& multi, const std::vector<MaterialParams>& materials);
    ~Batches();
    void evaluate(const Samples& samples, float* rgb);

   private:
    MultiEvaluator& multi_;
    std::vector<MaterialParams> materials_;
  };

 private:
  DeviceSet& devices_;
  EvalOptions options_;
  std::vector<std::unique_ptr<Evaluator>> evaluators_;
};

}  // namespace brdfcl
