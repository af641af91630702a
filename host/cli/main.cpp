// brdfcl command-line entry point: subcommand dispatch and the one-line error contract
// (message on stderr; exit status 2 for bad input or environment, 3 for internal faults).
#include <csignal>
#include <cstdio>
#include <exception>
#include <memory>
#include <new>

#include <fmt/format.h>

#include "arguments.hpp"
#include "host/src/io/cache.hpp"
#include "host/src/io/cleanup.hpp"
#include "brdfcl/error.hpp"
#include "brdfcl/runtime.hpp"
#include "commands.hpp"
#include "host/src/mpi/session.hpp"

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

namespace {
// Parses and runs the subcommand; returns its exit status. `speak`: print errors and help (under
// mpirun only rank 0 does, so that a failure is one line, whatever the number of ranks).
int run(CLI::App& app, int argc, char** argv, bool speak) {
  std::string subcommand;
  try {
    subcommand = brdfcl::cli::checkArguments(app, argc, argv);
    if (subcommand.empty() && std::string(argv[1]) == "--version") {
      if (speak) brdfcl::cli::printVersion();
      return 0;
    }
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return speak ? app.exit(e) : 0;
  } catch (const CLI::CallForAllHelp& e) {
    return speak ? app.exit(e) : 0;
  } catch (const CLI::ParseError& e) {
    const std::string help = subcommand.empty() ? "brdfcl --help" : "brdfcl " + subcommand + " --help";
    if (speak) std::fprintf(stderr, "brdfcl: %s; see '%s'\n", e.what(), help.c_str());
    return 2;
  } catch (const brdfcl::Error& e) {
    if (speak) std::fprintf(stderr, "brdfcl: %s\n", e.what());
    return e.exitCode();
  } catch (const std::bad_alloc&) {
    if (speak) std::fprintf(stderr, "brdfcl: %s\n", brdfcl::outOfMemoryMessage().c_str());
    return 2;
  } catch (const std::exception& e) {
    if (speak) std::fprintf(stderr, "brdfcl: internal error: %s\n", e.what());
    return 3;
  }
  return 0;
}

// The subcommands whose work is split between the ranks of an mpirun job; the others run on
// rank 0 alone while the rest wait for its exit status.
bool splitsAcrossRanks(const char* subcommand) {
  const std::string s = subcommand;
  return s == "eval" || s == "render" || s == "shade";
}
}  // namespace

int main(int argc, char** argv) {
  brdfcl::installSignalCleanup();
  brdfcl::setCacheWarningHandler(brdfcl::cli::printWarning);
  // A file size limit (ulimit -f) then fails the write with EFBIG, which every writer reports
  // and cleans up after, instead of killing the process with its temporary left behind.
  std::signal(SIGXFSZ, SIG_IGN);
  std::unique_ptr<brdfcl::mpi::Scope> mpiScope;
  try {
    mpiScope = std::make_unique<brdfcl::mpi::Scope>(&argc, &argv);
  } catch (const brdfcl::Error& e) {
    std::fprintf(stderr, "brdfcl: %s\n", e.what());
    return e.exitCode();
  }
  CLI::App app{"brdfcl: exact glTF BRDF evaluation (sheen, clearcoat, anisotropy, cloth) on OpenCL"};
  app.name("brdfcl");
  app.require_subcommand(1);
  app.add_flag("--version", "print the version, the git commit and the OpenCL devices found");
  brdfcl::cli::addDevicesCommand(app);
  brdfcl::cli::addEvalCommand(app);
  brdfcl::cli::addSampleCommand(app);
  brdfcl::cli::addPdfCommand(app);
  brdfcl::cli::addAlbedoCommand(app);
  brdfcl::cli::addGbufferCommand(app);
  brdfcl::cli::addShadeCommand(app);
  brdfcl::cli::addRenderCommand(app);
  brdfcl::cli::addDemoCommand(app);
  brdfcl::cli::addBenchCommand(app);
  brdfcl::cli::addLutCommand(app);
  brdfcl::cli::addDiffCommand(app);
  brdfcl::cli::addCompareCommand(app);
  brdfcl::cli::addCacheCommand(app);
  const auto& session = brdfcl::mpi::Session::get();
  if (argc < 2) {
    if (session.rank() == 0) std::fputs(app.help().c_str(), stdout);
    return 0;
  }
  if (!session.parallel()) return run(app, argc, argv, true);
  if (splitsAcrossRanks(argv[1])) return run(app, argc, argv, session.rank() == 0);
  const int code = session.rank() == 0 ? run(app, argc, argv, true) : 0;
  return session.broadcastExitCode(code);
}
