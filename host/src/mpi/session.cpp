// The MPI session (see session.hpp): launch detection, MPI_Init only under mpirun, the node-local
// rank, and the agreement on one error that makes every rank exit alike and rank 0 speak.
#include "mpi/session.hpp"

#include <cstdlib>
#include <new>
#include <stdexcept>
#include <vector>

#include "brdfcl/error.hpp"
#include "brdfcl/runtime.hpp"

#ifdef BRDFCL_HAVE_MPI
#include <mpi.h>
#endif

namespace brdfcl::mpi {

bool launchedByMpirun() {
  // Open MPI sets OMPI_COMM_WORLD_SIZE, MPICH's Hydra PMI_SIZE, any PMIx launcher PMIX_RANK.
  for (const char* v : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK"})
    if (std::getenv(v) != nullptr) return true;
  return false;
}

Session& Session::get() {
  static Session s;
  return s;
}

Share shareOf(std::uint64_t total, int rank, int size) {
  const std::uint64_t n = static_cast<std::uint64_t>(size), r = static_cast<std::uint64_t>(rank);
  const std::uint64_t base = total / n, extra = total % n;
  Share s;
  s.begin = r * base + (r < extra ? r : extra);
  s.end = s.begin + base + (r < extra ? 1 : 0);
  return s;
}

std::string deviceSelector(const std::string& given) {
  if (!given.empty()) return given;
  if (const char* env = std::getenv("BRDFCL_DEVICE"); env != nullptr && *env != '\0') return env;
  const Session& s = Session::get();
  if (!s.active()) return "";
  std::size_t count = 0;
  try {
    count = listDevices().size();
  } catch (const Error&) {
    return "";  // Runtime reports the missing OpenCL platform in its own words
  }
  return count == 0 ? "" : std::to_string(static_cast<std::size_t>(s.localRank()) % count);
}

#ifdef BRDFCL_HAVE_MPI

void Session::start(int* argc, char*** argv) {
  if (active_ || !launchedByMpirun()) return;
  int provided = 0;
  // Worker threads (readers, writers) never call MPI; only the main thread does.
  if (MPI_Init_thread(argc, argv, MPI_THREAD_FUNNELED, &provided) != MPI_SUCCESS)
    throw Error("mpirun started brdfcl but MPI_Init failed; check the MPI installation");
  active_ = true;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
  MPI_Comm node;
  MPI_Comm_split_type(MPI_COMM_WORLD, MPI_COMM_TYPE_SHARED, rank_, MPI_INFO_NULL, &node);
  MPI_Comm_rank(node, &localRank_);
  MPI_Comm_free(&node);
}

void Session::finish() {
  if (!active_) return;
  active_ = false;
  MPI_Finalize();
}

void Session::together(const std::function<void()>& step) {
  if (!active_) {
    step();
    return;
  }
  int code = 0;
  std::string message;
  try {
    step();
  } catch (const Error& e) {
    code = e.exitCode();
    message = e.what();
  } catch (const std::bad_alloc&) {
    code = 2;
    message = outOfMemoryMessage();
  } catch (const std::exception& e) {
    code = 3;
    message = std::string("internal error: ") + e.what();
  }
  int failing = code != 0 ? rank_ : size_, first = size_;
  MPI_Allreduce(&failing, &first, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
  if (first == size_) return;
  // The lowest failing rank's words, so that rank 0 prints what one process would have printed.
  unsigned long long length = message.size();
  MPI_Bcast(&code, 1, MPI_INT, first, MPI_COMM_WORLD);
  MPI_Bcast(&length, 1, MPI_UNSIGNED_LONG_LONG, first, MPI_COMM_WORLD);
  message.resize(length);
  MPI_Bcast(message.data(), static_cast<int>(length), MPI_CHAR, first, MPI_COMM_WORLD);
  throw Error(message, code);
}

std::uint64_t Session::exclusivePrefixSum(std::uint64_t value, std::uint64_t* total) const {
  if (!active_) {
    if (total) *total = value;
    return 0;
  }
  unsigned long long v = value, before = 0, all = 0;
  MPI_Exscan(&v, &before, 1, MPI_UNSIGNED_LONG_LONG, MPI_SUM, MPI_COMM_WORLD);
  if (rank_ == 0) before = 0;  // MPI leaves rank 0's result undefined
  MPI_Allreduce(&v, &all, 1, MPI_UNSIGNED_LONG_LONG, MPI_SUM, MPI_COMM_WORLD);
  if (total) *total = all;
  return before;
}

std::string Session::broadcast(const std::string& fromRank0) const {
  if (!active_) return fromRank0;
  unsigned long long length = fromRank0.size();
  MPI_Bcast(&length, 1, MPI_UNSIGNED_LONG_LONG, 0, MPI_COMM_WORLD);
  std::string s = rank_ == 0 ? fromRank0 : std::string(length, '\0');
  MPI_Bcast(s.data(), static_cast<int>(length), MPI_CHAR, 0, MPI_COMM_WORLD);
  return s;
}

int Session::broadcastExitCode(int code) const {
  if (!active_) return code;
  MPI_Bcast(&code, 1, MPI_INT, 0, MPI_COMM_WORLD);
  return code;
}

void Session::barrier() const {
  if (active_) MPI_Barrier(MPI_COMM_WORLD);
}

void Session::gatherShares(std::vector<float>& data, const std::vector<Share>& shares, std::size_t stride) const {
  if (!active_) return;
  const Share& mine = shares[static_cast<std::size_t>(rank_)];
  const int count = static_cast<int>(mine.count() * stride);
  float* base = data.empty() ? nullptr : data.data();
  if (rank_ != 0) {
    MPI_Gatherv(count ? base + mine.begin * stride : nullptr, count, MPI_FLOAT, nullptr, nullptr, nullptr, MPI_FLOAT, 0,
                MPI_COMM_WORLD);
    return;
  }
  // Counts and displacements are ints: a 16384^2 RGB frame is 805M floats, below 2^31.
  std::vector<int> counts(static_cast<std::size_t>(size_)), displacements(counts.size());
  for (std::size_t r = 0; r < counts.size(); ++r) {
    counts[r] = static_cast<int>(shares[r].count() * stride);
    displacements[r] = static_cast<int>(shares[r].begin * stride);
  }
  MPI_Gatherv(MPI_IN_PLACE, 0, MPI_FLOAT, base, counts.data(), displacements.data(), MPI_FLOAT, 0, MPI_COMM_WORLD);
}

#else  // one process: every collective is the identity

void Session::start(int*, char***) {}
void Session::finish() {}
void Session::together(const std::function<void()>& step) { step(); }
std::uint64_t Session::exclusivePrefixSum(std::uint64_t value, std::uint64_t* total) const {
  if (total) *total = value;
  return 0;
}
std::string Session::broadcast(const std::string& fromRank0) const { return fromRank0; }
int Session::broadcastExitCode(int code) const { return code; }
void Session::barrier() const {}
void Session::gatherShares(std::vector<float>&, const std::vector<Share>&, std::size_t) const {}

#endif

}  // namespace brdfcl::mpi
