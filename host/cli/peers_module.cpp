// Finding and opening brdfcl-peers.so: beside the running executable (/proc/self/exe), never on
// the library search path, so that `brdfcl bench` runs the peers built with it.
#include "peers_module.hpp"

#include <dlfcn.h>

#include <filesystem>
#include <system_error>

#include <fmt/format.h>

#include "brdfcl/error.hpp"

namespace brdfcl::cli {

namespace {
const peers::ModuleTable& load() {
  std::error_code ec;
  const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  const std::string path = (ec ? std::filesystem::path(".") : exe.parent_path()) / "brdfcl-peers.so";
  if (!std::filesystem::exists(path, ec))
    throw Error(fmt::format("brdfcl bench compares the kernel with C++ peers from '{}', which is not built; build the "
                            "CMake target brdfcl-peers ('make build' does), or time the kernel alone with --pairs or "
                            "--profile",
                            path));
  void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
  const char* why = handle == nullptr ? dlerror() : nullptr;
  using Entry = const peers::ModuleTable* (*)();
  const auto entry = handle == nullptr ? nullptr : reinterpret_cast<Entry>(dlsym(handle, peers::kPeersModuleEntry));
  const peers::ModuleTable* table = entry == nullptr ? nullptr : entry();
  if (table == nullptr || table->version != peers::kPeersModuleVersion)
    throw Error(fmt::format("cannot load the C++ peers '{}': {}; rebuild the CMake target brdfcl-peers",
                            path, why != nullptr ? why : "not a brdfcl peers module of this version"));
  return *table;  // the module stays loaded for the process's life
}
}  // namespace

const peers::ModuleTable& peersModule() {
  static const peers::ModuleTable& table = load();
  return table;
}

}  // namespace brdfcl::cli
