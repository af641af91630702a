// What a C++ peer of the batch kernel (bench/peers) reads and writes, and the table its module
// exports: the peers are benchmark code that the library and the CLI never link; this header is
// the whole of what they share.
#pragma once
#include <cstddef>
#include <cstdint>

#include "kernels/common/material_layout.h"

namespace brdfcl::peers {

struct Input {
  const float* dir[6];  // Lx Ly Lz Vx Vy Vz
  const std::uint32_t* material;
  const brdfcl_material* materials;
  const float* sheenE;
  int sheenESize;
  float* out[3];
  std::size_t count;
};

}  // namespace brdfcl::peers

// The peers are a module of their own (bench/peers/module.cpp, build/bin/brdfcl-peers.so) that
// `brdfcl bench` loads at run time: its one exported C function, kPeersModuleEntry, returns this
// table. Module and CLI are built together from one tree, so the version only guards stale files.
namespace brdfcl::peers {

constexpr int kPeersModuleVersion = 1;
constexpr const char* kPeersModuleEntry = "brdfcl_peers_module";

struct ModuleTable {
  int version;
  // simd: the OpenMP-SIMD loop, else the scalar one. False for a workload the peers do not know.
  bool (*run)(bool simd, const char* workload, const Input* in);
  // STREAM triad over `floats` floats per array: bytes/s, best of `repeats`.
  double (*streamTriadBytesPerSecond)(std::size_t floats, int repeats);
  // Threads the OpenMP peer and the triad run on.
  int (*threads)();
};

}  // namespace brdfcl::peers
