// Row-parallel helpers shared by the samples reader and the results writer (see rows.hpp).
#include "io/rows.hpp"

#include <algorithm>
#include <cctype>
#include <exception>
#include <vector>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace brdfcl::detail {

bool hasNpyExtension(const std::string& path) {
  if (path.size() < 4) return false;
  std::string ext = path.substr(path.size() - 4);
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext == ".npy";
}

std::size_t parallelThreads() {
#ifdef _OPENMP
  return std::size_t(std::max(1, omp_get_max_threads()));
#else
  return 1;
#endif
}

std::size_t workerCount(std::size_t bytes) {
  return std::min<std::size_t>({parallelThreads(), 64, bytes / (1u << 20) + 1});
}

void parallelFor(std::size_t n, const std::function<void(std::size_t)>& body) {
  // An exception must not leave an OpenMP region: each is kept, and the first rethrown after it.
  std::vector<std::exception_ptr> errors(n);
  const long count = long(n);
#pragma omp parallel for num_threads(int(std::max<std::size_t>(n, 1))) schedule(static, 1) if (n > 1)
  for (long i = 0; i < count; ++i) {
    try {
      body(std::size_t(i));
    } catch (...) {
      errors[std::size_t(i)] = std::current_exception();
    }
  }
  for (auto& e : errors)
    if (e) std::rethrow_exception(e);
}

}  // namespace brdfcl::detail
