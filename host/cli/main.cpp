// brdfcl command-line entry point: subcommand dispatch and the one-line error contract
// (message on stderr, exit status 2 for bad input or environment, 1 for internal faults).
#include <cstdio>
#include <exception>

#include "brdfcl/cleanup.hpp"
#include "brdfcl/error.hpp"
#include "commands.hpp"

int main(int argc, char** argv) {
  brdfcl::installSignalCleanup();
  CLI::App app{"brdfcl: exact glTF BRDF evaluation (sheen, clearcoat, anisotropy, cloth) on OpenCL"};
  app.require_subcommand(1);
  brdfcl::cli::addDevicesCommand(app);
  brdfcl::cli::addEvalCommand(app);
  brdfcl::cli::addAlbedoCommand(app);
  brdfcl::cli::addRenderCommands(app);
  brdfcl::cli::addBenchCommand(app);
  brdfcl::cli::addLutCommand(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::fprintf(stderr, "brdfcl: %s; see 'brdfcl --help'\n", e.what());
    return 2;
  } catch (const brdfcl::Error& e) {
    std::fprintf(stderr, "brdfcl: %s\n", e.what());
    return e.exitCode();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "brdfcl: internal error: %s\n", e.what());
    return 1;
  }
  return 0;
}
