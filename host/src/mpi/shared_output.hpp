// One output file written by every rank of an mpirun job through MPI-IO: rank 0's header, then
// each rank's part at the offset the exclusive prefix sum of the parts' sizes gives, into a
// temporary beside the output that rank 0 renames into place once every rank has succeeded.
#pragma once
#include <cstdint>
#include <string>

namespace brdfcl::mpi {

// Collective: every rank calls it. `header` counts on rank 0 only; `partPath` is this rank's
// part (a local file of `partBytes` bytes; "" with 0 bytes for a rank with nothing to write).
// `userPath` must be a regular file's path (or a new one): checkSharedOutput. On any failure,
// every rank throws the same Error (Session::together) and no file appears at `userPath`.
void writeShared(const std::string& userPath, const std::string& header, const std::string& partPath,
                 std::uint64_t partBytes);

// Refuses, before any work, an output that ranks cannot write together: "-" and FIFOs or
// devices, which one process must write ("--out '-': under mpirun, outputs must be files...").
void checkSharedOutput(const std::string& option, const std::string& userPath);

}  // namespace brdfcl::mpi
