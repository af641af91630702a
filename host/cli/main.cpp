// brdfcl command-line entry point: subcommand dispatch and the one-line error contract
// (message on stderr; exit status 2 for bad input or environment, 3 for internal faults).
#include <cstdio>
#include <exception>
#include <new>

#include <fmt/format.h>

#include "arguments.hpp"
#include "brdfcl/cleanup.hpp"
#include "brdfcl/error.hpp"
#include "brdfcl/runtime.hpp"
#include "commands.hpp"

namespace brdfcl::cli {
extern const char* const kGitCommit;

namespace {
// The version, the commit and what OpenCL offers: the three facts a bug report needs.
void printVersion() {
  fmt::print("brdfcl {} (commit {})\n", BRDFCL_VERSION, kGitCommit);
  try {
    for (const auto& d : listDevices())
      fmt::print("OpenCL device [{}]: {} ({}, {}, {})\n", d.index, d.name, d.platform, d.type, d.openclC);
  } catch (const Error& e) {
    fmt::print("OpenCL: {}\n", e.what());
  }
}
}  // namespace
}  // namespace brdfcl::cli

int main(int argc, char** argv) {
  brdfcl::installSignalCleanup();
  CLI::App app{"brdfcl: exact glTF BRDF evaluation (sheen, clearcoat, anisotropy, cloth) on OpenCL"};
  app.name("brdfcl");
  app.require_subcommand(1);
  app.add_flag("--version", "print the version, the git commit and the OpenCL devices found");
  brdfcl::cli::addDevicesCommand(app);
  brdfcl::cli::addEvalCommand(app);
  brdfcl::cli::addAlbedoCommand(app);
  brdfcl::cli::addRenderCommands(app);
  brdfcl::cli::addBenchCommand(app);
  brdfcl::cli::addLutCommand(app);
  brdfcl::cli::addDiffCommand(app);
  brdfcl::cli::addCompareCommand(app);
  if (argc < 2) {
    std::fputs(app.help().c_str(), stdout);
    return 0;
  }
  std::string subcommand;
  try {
    subcommand = brdfcl::cli::checkArguments(app, argc, argv);
    if (subcommand.empty() && std::string(argv[1]) == "--version") {
      brdfcl::cli::printVersion();
      return 0;
    }
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    const std::string help = subcommand.empty() ? "brdfcl --help" : "brdfcl " + subcommand + " --help";
    std::fprintf(stderr, "brdfcl: %s; see '%s'\n", e.what(), help.c_str());
    return 2;
  } catch (const brdfcl::Error& e) {
    std::fprintf(stderr, "brdfcl: %s\n", e.what());
    return e.exitCode();
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "brdfcl: out of memory; try a smaller --size or --chunk, or free memory\n");
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "brdfcl: internal error: %s\n", e.what());
    return 3;
  }
  return 0;
}
