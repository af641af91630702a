// Row-parallel helpers shared by the samples reader and the results writer (see rows.hpp).
#include "io/rows.hpp"

#include <algorithm>
#include <cctype>
#include <exception>
#include <system_error>
#include <thread>
#include <vector>

namespace brdfcl::detail {

bool hasNpyExtension(const std::string& path) {
  if (path.size() < 4) return false;
  std::string ext = path.substr(path.size() - 4);
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext == ".npy";
}

std::size_t workerCount(std::size_t bytes) {
  const std::size_t cores = std::max(1u, std::thread::hardware_concurrency());
  return std::min<std::size_t>({cores, 64, bytes / (1u << 20) + 1});
}

void parallelFor(std::size_t n, const std::function<void(std::size_t)>& body) {
  std::vector<std::exception_ptr> errors(n);
  const auto run = [&](std::size_t i) {
    try {
      body(i);
    } catch (...) {
      errors[i] = std::current_exception();
    }
  };
  std::vector<std::thread> threads;
  std::size_t next = 1;
  for (; next < n; ++next) {
    try {
      threads.emplace_back(run, next);
    } catch (const std::system_error&) {
      break;  // no more threads available: the rest runs here
    }
  }
  if (n > 0) run(0);
  for (; next < n; ++next) run(next);
  for (auto& t : threads) t.join();
  for (auto& e : errors)
    if (e) std::rethrow_exception(e);
}

}  // namespace brdfcl::detail
