// PoCL's own kernel cache: where PoCL 3.1 will put it, and a private temporary folder in its place
// when that is not usable, so that PoCL starts instead of reporting no device.
#pragma once
#include <string>

namespace brdfcl::detail {

// The folder PoCL 3.1 creates at its first OpenCL call: POCL_CACHE_DIR, else
// $XDG_CACHE_HOME/pocl/kcache, else $HOME/.cache/pocl/kcache, else /tmp/pocl/kcache ("uncached"
// for "kcache" when POCL_KERNEL_CACHE is 0).
std::string poclCacheFolder();

// Call before the first OpenCL call, once. An empty POCL_CACHE_DIR (which PoCL asserts on) is
// removed from the environment. When PoCL's folder cannot be created or written, or its disk has
// less than kPoclMinFreeBytes free, POCL_CACHE_DIR is pointed at a new private folder under
// $TMPDIR (or /tmp), with one warning; that folder is removed when the process exits.
constexpr unsigned long long kPoclMinFreeBytes = 64ull << 20;
void preparePoclCacheFolder();

}  // namespace brdfcl::detail
