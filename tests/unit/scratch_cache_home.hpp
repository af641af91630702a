// brdfcl's disk cache ($XDG_CACHE_HOME/brdfcl) moved under a scratch directory for one test and put
// back after it. The shared runtime is opened first: PoCL reads its own cache folder once, at the
// first OpenCL call, so only brdfcl's entries start cold, not PoCL's compiled kernels.
#pragma once

#include <cstdlib>
#include <string>

#include "process.hpp"
#include "support.hpp"

namespace brdfcl::test {

class ScratchCacheHome {
 public:
  explicit ScratchCacheHome(const ScratchDir& dir) : had_(std::getenv("XDG_CACHE_HOME") != nullptr) {
    runtime();
    if (had_) saved_ = std::getenv("XDG_CACHE_HOME");
    ::setenv("XDG_CACHE_HOME", dir.dir().c_str(), 1);
  }
  ~ScratchCacheHome() {
    if (had_) ::setenv("XDG_CACHE_HOME", saved_.c_str(), 1);
    else ::unsetenv("XDG_CACHE_HOME");
  }
  ScratchCacheHome(const ScratchCacheHome&) = delete;
  ScratchCacheHome& operator=(const ScratchCacheHome&) = delete;

 private:
  bool had_;
  std::string saved_;
};

}  // namespace brdfcl::test
