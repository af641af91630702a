// `brdfcl devices`: every OpenCL device with the facts that matter for choosing one.
#include <fmt/format.h>

#include "brdfcl/runtime.hpp"
#include "commands.hpp"

namespace brdfcl::cli {

void addDevicesCommand(CLI::App& app) {
  auto* cmd = app.add_subcommand("devices", "List OpenCL devices (select one with --device or BRDFCL_DEVICE)");
  cmd->callback([] {
    for (const auto& d : listDevices()) {
      fmt::print("[{}] {}\n    platform: {}\n    type: {}, compute units: {}, {}\n    max allocation: {} MiB, "
                 "global memory: {} MiB\n",
                 d.index, d.name, d.platform, d.type, d.computeUnits, d.openclC, d.maxAlloc >> 20, d.globalMem >> 20);
    }
  });
}

}  // namespace brdfcl::cli
