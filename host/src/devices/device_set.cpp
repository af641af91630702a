// Device lists (--device all, --device 0,2) and the DeviceSet that splits a batch across them
// in proportion to measured speed, one host thread a device.
#include "devices/device_set.hpp"

#include <algorithm>
#include <chrono>
#include <exception>
#include <thread>

#include <fmt/format.h>

#include "brdfcl/error.hpp"

namespace brdfcl {

namespace {
std::string validIndexes(std::size_t count) {
  const std::string range = count == 1 ? "0" : fmt::format("0-{}", count - 1);
  return fmt::format("valid indexes: {} (see 'brdfcl devices')", range);
}
}  // namespace

bool isDeviceList(const std::string& selector) {
  return selector == "all" || selector.find(',') != std::string::npos;
}

std::vector<std::size_t> parseDeviceList(const std::string& selector, std::size_t deviceCount,
                                         const std::string& source) {
  std::vector<std::size_t> out;
  if (selector == "all") {
    for (std::size_t i = 0; i < deviceCount; ++i) out.push_back(i);
    return out;
  }
  std::size_t pos = 0;
  while (true) {
    const std::size_t comma = selector.find(',', pos);
    const std::string item = selector.substr(pos, comma == std::string::npos ? std::string::npos : comma - pos);
    if (item.empty() || item.size() > 9 || item.find_first_not_of("0123456789") != std::string::npos)
      throw Error(fmt::format("{} {}: '{}' is not a device index; use all or a list such as 0,1; {}", source, selector,
                              item, validIndexes(deviceCount)));
    const std::size_t index = std::stoul(item);
    if (index >= deviceCount)
      throw Error(fmt::format("{} {}: device index {} out of range; {}", source, selector, index,
                              validIndexes(deviceCount)));
    if (std::find(out.begin(), out.end(), index) != out.end())
      throw Error(fmt::format("{} {}: device {} is listed twice; {}", source, selector, index,
                              validIndexes(deviceCount)));
    out.push_back(index);
    if (comma == std::string::npos) break;
    pos = comma + 1;
  }
  return out;
}

DeviceSet::DeviceSet(const std::string& selector) {
  if (isDeviceList(selector)) {
    for (std::size_t index : parseDeviceList(selector, listDevices().size()))
      runtimes_.push_back(std::make_unique<Runtime>(std::to_string(index)));
  } else {
    runtimes_.push_back(std::make_unique<Runtime>(selector));
  }
  // Until a device has been timed, compute units stand in for its speed.
  for (const auto& rt : runtimes_) speed_.push_back(double(std::max(1u, rt->info().computeUnits)));
}

DeviceSet::~DeviceSet() = default;

std::vector<double> DeviceSet::speeds() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return speed_;
}

std::vector<DeviceSet::Range> DeviceSet::split(std::size_t n, std::size_t grain) const {
  const std::vector<double> speed = speeds();
  double total = 0;
  for (double s : speed) total += s;
  std::vector<Range> out(speed.size());
  std::size_t first = 0;
  double share = 0;
  for (std::size_t k = 0; k < speed.size(); ++k) {
    share += speed[k] / total;
    // Boundaries from the running share, so the rounding never accumulates.
    std::size_t end = k + 1 == speed.size() ? n : std::min(n, std::size_t(share * double(n)) / grain * grain);
    end = std::max(end, first);
    out[k] = {first, end - first};
    first = end;
  }
  return out;
}

void DeviceSet::run(std::size_t n, std::size_t grain,
                    const std::function<void(std::size_t, std::size_t, std::size_t)>& work) {
  const auto ranges = split(n, std::max<std::size_t>(grain, 1));
  std::vector<std::exception_ptr> errors(ranges.size());
  std::vector<double> seconds(ranges.size(), 0.0);
  auto one = [&](std::size_t k) {
    const auto start = std::chrono::steady_clock::now();
    try {
      work(k, ranges[k].first, ranges[k].count);
    } catch (...) {
      errors[k] = std::current_exception();
    }
    seconds[k] = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  };
  std::vector<std::thread> threads;
  std::size_t local = ranges.size();  // the first busy device runs on this thread
  for (std::size_t k = 0; k < ranges.size(); ++k) {
    if (ranges[k].count == 0) continue;
    if (local == ranges.size()) {
      local = k;
      continue;
    }
    threads.emplace_back(one, k);
  }
  if (local < ranges.size()) one(local);
  for (auto& t : threads) t.join();
  for (auto& e : errors)
    if (e) std::rethrow_exception(e);
  // Ranges too small to time (a few ms) say little about throughput, and the speeds must all be
  // in one unit: update them together or keep the old estimate.
  for (std::size_t k = 0; k < ranges.size(); ++k)
    if (ranges[k].count < 4096 || seconds[k] < 1e-3) return;
  std::lock_guard<std::mutex> lock(mutex_);
  for (std::size_t k = 0; k < ranges.size(); ++k) speed_[k] = double(ranges[k].count) / seconds[k];
}

}  // namespace brdfcl
