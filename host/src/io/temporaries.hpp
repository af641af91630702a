// The registry of this process's output temporaries, read by the signal handler, their names,
// and the removal of temporaries that dead brdfcl processes of this host left behind.
#pragma once
#include <cstdint>
#include <string>

namespace brdfcl::detail {

// Records `path` (made absolute here, so a later chdir cannot misdirect the handler) before the
// file is created; returns false when the path does not fit or the registry is full, in which
// case the file is still written but an interrupt would leave it behind.
bool registerTemporary(const std::string& path);
// Forgets `path` once it has been renamed into place or unlinked.
void deregisterTemporary(const std::string& path);

// What a temporary's name records about the process that made it. A name is
// ".brdfcl.tmp.<host>.<pidns>.<pid>.<random>": the host name with every byte outside
// [A-Za-z0-9-] written as _XX (hex), the inode of the PID namespace (0 where unknown), the process
// id, and 16 random hex digits. No user file is expected to look like that, and the host and
// namespace say where the process id means something. At most 255 bytes (NAME_MAX).
struct TemporaryOwner {
  std::string host;         // encoded as in the name
  std::uint64_t pidNamespace = 0;
  long pid = 0;
};

// A host name as temporaries' names hold it: bytes outside [A-Za-z0-9-] as _XX, so that dots,
// slashes and odd bytes cannot split or escape the name; beyond 160 characters, the head and a
// hash of the whole after '~'.
std::string encodeHostName(const std::string& host);
// This process: the host name (encoded) and PID namespace of the temporaries it makes.
TemporaryOwner thisProcess();
// A fresh temporary name of `owner` (random part from getrandom).
std::string temporaryName(const TemporaryOwner& owner);
// Whether `name` is exactly a temporary's name; sets `owner`.
bool parseTemporaryName(const std::string& name, TemporaryOwner& owner);

// Temporaries younger than this are never swept, whoever made them: a process in another PID
// namespace with the same host name, or a clock that disagrees, gets this much grace.
inline constexpr long kStaleTemporarySeconds = 3600;

// Whether the entry `name` of the directory `dirFd` is a temporary that may be swept: exactly a
// temporary's name, of `self`'s host and PID namespace, of a process that no longer exists, a
// regular file last modified more than kStaleTemporarySeconds ago.
bool isStaleTemporary(int dirFd, const char* name, const TemporaryOwner& self);

// Unlinks the entries of `dir` that are exactly temporaries' names, of this host and PID
// namespace, of a process that no longer exists, regular files last modified more than
// kStaleTemporarySeconds ago. Anything else is kept; failures are ignored (a stale file costs
// space, not correctness).
void removeStaleTemporaries(const std::string& dir);

}  // namespace brdfcl::detail
