// The registry of this process's output temporaries, read by the signal handler, and the removal
// of temporaries that dead brdfcl processes left behind.
#pragma once
#include <string>

namespace brdfcl::detail {

// Records `path` (made absolute here, so a later chdir cannot misdirect the handler) before the
// file is created; returns false when the path does not fit or the registry is full, in which
// case the file is still written but an interrupt would leave it behind.
bool registerTemporary(const std::string& path);
// Forgets `path` once it has been renamed into place or unlinked.
void deregisterTemporary(const std::string& path);

// Unlinks the entries of `dir` named like brdfcl's temporaries (".<name>.tmp.<pid>.<n>") whose
// process no longer exists. Entries of live processes, ours included, are kept; failures are
// ignored (a stale file costs space, not correctness).
void removeStaleTemporaries(const std::string& dir);

// Whether `name` is ".<name>.tmp.<pid>.<n>"; sets `pid`.
bool parseTemporaryName(const std::string& name, long& pid);

}  // namespace brdfcl::detail
