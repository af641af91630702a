// The MPI session of one brdfcl process: started only when mpirun launched it (MPI_Init is never
// called otherwise), its rank, size and node-local rank, and how ranks agree on one error.
// Without MPI at build time (BRDFCL_HAVE_MPI unset) every process is rank 0 of 1.
#pragma once
#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace brdfcl::mpi {

struct Share;

// Whether the environment says mpirun (Open MPI, MPICH/Hydra, PMIx) started this process.
bool launchedByMpirun();

// Process-wide: start() once at the top of main, finish() (or the destructor of Scope) at exit.
class Session {
 public:
  static Session& get();

  // MPI_Init when built with MPI and launchedByMpirun(); otherwise nothing.
  void start(int* argc, char*** argv);
  // MPI_Finalize when start() initialized MPI.
  void finish();

  bool active() const { return active_; }  // MPI initialized, any size
  bool parallel() const { return active_ && size_ > 1; }
  int rank() const { return rank_; }
  int size() const { return size_; }
  int localRank() const { return localRank_; }  // rank among the ranks of this node

  // Runs `step` on every rank, then all agree: when any rank threw, every rank throws the error
  // of the lowest failing rank (the first in file order, since ranks own rows in order), as a
  // brdfcl::Error with its message and exit code; bad_alloc and other exceptions become the
  // messages main prints for them. Every rank must call it the same number of times.
  void together(const std::function<void()>& step);

  // The sum over ranks below this one of `value` (0 on rank 0), and the total over all ranks.
  std::uint64_t exclusivePrefixSum(std::uint64_t value, std::uint64_t* total = nullptr) const;
  // Rank 0's string on every rank.
  std::string broadcast(const std::string& fromRank0) const;
  // Rank 0's exit code on every rank (for the commands that run on rank 0 alone).
  int broadcastExitCode(int code) const;
  void barrier() const;
  // Rank 0 receives into `data` the range [share(r).begin, share(r).end) * stride floats of every
  // other rank r, sent from the same place of that rank's `data`: the rows each rank rendered.
  // `shares` is indexed by rank (rank 0 needs them all).
  void gatherShares(std::vector<float>& data, const std::vector<Share>& shares, std::size_t stride) const;

 private:
  Session() = default;
  bool active_ = false;
  int rank_ = 0, size_ = 1, localRank_ = 0;
};

// finish() at scope exit, so every return path of main finalizes MPI.
struct Scope {
  Scope(int* argc, char*** argv) { Session::get().start(argc, argv); }
  ~Scope() { Session::get().finish(); }
  Scope(const Scope&) = delete;
  Scope& operator=(const Scope&) = delete;
};

// The contiguous share [begin, end) of `total` items that `rank` of `size` owns: sizes differ by
// at most one, lower ranks take the larger ones, and the shares cover [0, total) in rank order.
struct Share {
  std::uint64_t begin = 0, end = 0;
  std::uint64_t count() const { return end - begin; }
};
Share shareOf(std::uint64_t total, int rank, int size);

// The device selector of this rank: `given` (--device) when set, then $BRDFCL_DEVICE, then under
// mpirun the node-local rank modulo the node's device count (so the ranks of a node spread over
// its devices); "" leaves the choice to Runtime (device 0).
std::string deviceSelector(const std::string& given);

}  // namespace brdfcl::mpi
