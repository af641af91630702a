// The peers as a loadable module (build/bin/brdfcl-peers.so): `brdfcl bench` opens it at run time
// and calls through the table of host/src/eval/peer_input.hpp, so the CLI itself links no
// benchmark code. An unknown workload comes back as false rather than as an exception.
#include <stdexcept>

#include "peers.hpp"

namespace {

bool runPeer(bool simd, const char* workload, const brdfcl::peers::Input* in) {
  try {
    brdfcl::peers::run(simd ? brdfcl::peers::Flavor::OpenMPSimd : brdfcl::peers::Flavor::Scalar, workload, *in);
    return true;
  } catch (const std::invalid_argument&) {
    return false;
  }
}

const brdfcl::peers::ModuleTable kTable = {brdfcl::peers::kPeersModuleVersion, runPeer,
                                           brdfcl::peers::streamTriadBytesPerSecond, brdfcl::peers::threads};

}  // namespace

extern "C" __attribute__((visibility("default"))) const brdfcl::peers::ModuleTable* brdfcl_peers_module() {
  return &kTable;
}
