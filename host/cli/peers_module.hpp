// The C++ peers of `brdfcl bench`, loaded at run time from brdfcl-peers.so beside the executable
// (bench/peers/module.cpp, CMake target brdfcl-peers): the CLI links no benchmark code, and a
// build of the CLI alone (`make demo`) has no peers, only the kernel's own timings.
#pragma once
#include <string>

#include "host/src/eval/peer_input.hpp"

namespace brdfcl::cli {

// The module's table, loaded once; throws brdfcl::Error naming the file and how to build it.
const peers::ModuleTable& peersModule();

}  // namespace brdfcl::cli
