// Row-parallel helpers shared by the samples reader and the results writer: both convert
// numbers row by row, which dominates their time, and rows are independent.
#pragma once
#include <cstddef>
#include <functional>
#include <string>

namespace brdfcl::detail {

// True if `path` ends in .npy (any case): the samples and results formats are chosen by it.
bool hasNpyExtension(const std::string& path);

// The threads an OpenMP loop gets: OMP_NUM_THREADS when set, else the cores; 1 in a build
// without OpenMP.
std::size_t parallelThreads();

// Threads worth starting for `bytes` of text or data: at least 1 MiB each, at most parallelThreads().
std::size_t workerCount(std::size_t bytes);

// Runs body(0..n-1) concurrently in an OpenMP team of up to n threads, the calling thread taking
// part; rethrows the exception of the lowest index that threw.
void parallelFor(std::size_t n, const std::function<void(std::size_t)>& body);

}  // namespace brdfcl::detail
