// Collective output through MPI-IO (see shared_output.hpp). Each rank copies its part from its
// local file in blocks with MPI_File_write_at_all; ranks with fewer blocks join with empty writes,
// and a rank that fails to read or write keeps joining, so no rank waits forever on another.
// Every write's count, the sync and the close are checked on every rank, and agreed on, before
// rank 0 renames the temporary into place.
#include "mpi/shared_output.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <vector>

#include "brdfcl/error.hpp"
#include "io/messages.hpp"
#include "io/output.hpp"
#include "mpi/session.hpp"

#ifdef BRDFCL_HAVE_MPI
#include <mpi.h>
#endif

namespace brdfcl::mpi {

void checkSharedOutput(const std::string& option, const std::string& userPath) {
  if (!Session::get().parallel()) return;
  if (detail::isStreamTarget(userPath))
    throw Error(option + " '" + detail::printable(userPath, 300) +
                "': under mpirun, outputs must be files (the ranks write their parts into one file); "
                "run one process to write to stdout or a FIFO");
}

#ifdef BRDFCL_HAVE_MPI

namespace {
// The bytes a completed MPI-IO write of MPI_BYTEs reports in its status.
std::size_t bytesWritten(const MPI_Status& st) {
  int count = 0;
  MPI_Status copy = st;
  if (MPI_Get_count(&copy, MPI_BYTE, &count) != MPI_SUCCESS || count == MPI_UNDEFINED || count < 0) return 0;
  return static_cast<std::size_t>(count);
}

std::string mpiMessage(int code) {
  char text[MPI_MAX_ERROR_STRING] = {};
  int length = 0;
  MPI_Error_string(code, text, &length);
  return std::string(text, static_cast<std::size_t>(length));
}
}  // namespace

void writeShared(const std::string& userPath, const std::string& header, const std::string& partPath,
                 std::uint64_t partBytes) {
  Session& s = Session::get();
  const std::string shown = detail::printable(userPath, 300);
  const std::uint64_t headerBytes = std::stoull(s.broadcast(std::to_string(header.size())));
  std::uint64_t partsBytes = 0;
  const std::uint64_t offset = headerBytes + s.exclusivePrefixSum(partBytes, &partsBytes);
  // MPI-IO may report success for a write the file system took only part of (a full disk, a
  // file size limit): every count is checked, and the file's size once it is closed.
  const std::string shortWrite =
      "cannot write '" + shown + "': the file system took only part of the data (a full disk or a file size limit)";

  // Rank 0 makes the temporary in the output's directory, which every rank must see.
  std::string tmp, finalPath;
  s.together([&] {
    if (s.rank() != 0) return;
    const detail::OutputTarget target = detail::resolveOutput(userPath);
    finalPath = target.path;
    tmp = detail::createTemporary(target.path, userPath);
  });
  tmp = s.broadcast(tmp);
  // Removes rank 0's temporary unless it was committed.
  struct Cleanup {
    std::string path;
    ~Cleanup() {
      if (!path.empty()) detail::removeTemporary(path);
    }
  } cleanup{s.rank() == 0 ? tmp : std::string()};

  MPI_File file = MPI_FILE_NULL;
  const int opened = MPI_File_open(MPI_COMM_WORLD, tmp.c_str(), MPI_MODE_WRONLY, MPI_INFO_NULL, &file);
  s.together([&] {
    if (opened != MPI_SUCCESS) throw Error("cannot write '" + shown + "': MPI-IO: " + mpiMessage(opened));
  });

  std::string failure;
  if (s.rank() == 0 && !header.empty()) {
    MPI_Status st;
    const int rc = MPI_File_write_at(file, 0, header.data(), static_cast<int>(header.size()), MPI_BYTE, &st);
    if (rc != MPI_SUCCESS) failure = "cannot write '" + shown + "': MPI-IO: " + mpiMessage(rc);
    else if (bytesWritten(st) != header.size()) failure = shortWrite;
  }
  constexpr std::uint64_t kBlock = std::uint64_t(4) << 20;
  unsigned long long rounds = (partBytes + kBlock - 1) / kBlock, maxRounds = 0;
  MPI_Allreduce(&rounds, &maxRounds, 1, MPI_UNSIGNED_LONG_LONG, MPI_MAX, MPI_COMM_WORLD);
  int fd = -1;
  if (partBytes > 0) {
    fd = ::open(partPath.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) failure = "cannot read this rank's part of '" + shown + "': " + std::strerror(errno);
  }
  std::vector<char> block(static_cast<std::size_t>(std::min(partBytes, kBlock)));
  for (unsigned long long r = 0; r < maxRounds; ++r) {
    const std::uint64_t at = r * kBlock;
    std::size_t n = failure.empty() && at < partBytes ? static_cast<std::size_t>(std::min(kBlock, partBytes - at)) : 0;
    for (std::size_t done = 0; done < n;) {
      const ssize_t got = ::pread(fd, block.data() + done, n - done, static_cast<off_t>(at + done));
      if (got < 0 && errno == EINTR) continue;
      if (got <= 0) {
        failure = "cannot read this rank's part of '" + shown + "': " + (got < 0 ? std::strerror(errno) : "truncated");
        n = 0;
        break;
      }
      done += static_cast<std::size_t>(got);
    }
    MPI_Status st;
    const int rc = MPI_File_write_at_all(file, static_cast<MPI_Offset>(offset + at), block.data(), static_cast<int>(n),
                                         MPI_BYTE, &st);
    if (rc != MPI_SUCCESS && failure.empty()) failure = "cannot write '" + shown + "': MPI-IO: " + mpiMessage(rc);
    if (rc == MPI_SUCCESS && failure.empty() && bytesWritten(st) != n) failure = shortWrite;
  }
  if (fd >= 0) ::close(fd);
  // Collective, like the close: the data on the disk (or its error, on NFS) before the rename.
  const int synced = MPI_File_sync(file);
  if (synced != MPI_SUCCESS && failure.empty()) failure = "cannot write '" + shown + "': MPI-IO: " + mpiMessage(synced);
  const int closed = MPI_File_close(&file);
  if (closed != MPI_SUCCESS && failure.empty()) failure = "cannot write '" + shown + "': MPI-IO: " + mpiMessage(closed);
  s.together([&] {
    if (!failure.empty()) throw Error(failure);
  });
  s.together([&] {
    if (s.rank() != 0) return;
    struct stat st {};
    if (::stat(tmp.c_str(), &st) != 0) throw Error("cannot write '" + shown + "': " + std::strerror(errno));
    if (static_cast<std::uint64_t>(st.st_size) != headerBytes + partsBytes) throw Error(shortWrite);
    detail::commitTemporary(tmp, finalPath, userPath);
    cleanup.path.clear();
  });
}

#else

void writeShared(const std::string&, const std::string&, const std::string&, std::uint64_t) {
  throw Error("internal: writeShared without MPI", 3);
}

#endif

}  // namespace brdfcl::mpi
