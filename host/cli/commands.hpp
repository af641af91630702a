// The CLI's subcommands. Each registers its options on a CLI11 app and runs from a callback;
// errors travel as brdfcl::Error up to main(), which prints one line and exits with its code.
#pragma once
#include <CLI/CLI.hpp>

#include <functional>
#include <string>
#include <vector>

#include "brdfcl/material.hpp"

namespace brdfcl::cli {

void addDevicesCommand(CLI::App& app);
void addEvalCommand(CLI::App& app);
void addAlbedoCommand(CLI::App& app);
void addGbufferCommand(CLI::App& app);
void addShadeCommand(CLI::App& app);
void addRenderCommand(CLI::App& app);
void addDemoCommand(CLI::App& app);
void addBenchCommand(CLI::App& app);
void addLutCommand(CLI::App& app);
void addDiffCommand(CLI::App& app);
void addCompareCommand(CLI::App& app);
void addCacheCommand(CLI::App& app);
void addSampleCommand(CLI::App& app);
void addPdfCommand(CLI::App& app);

// "brdfcl: warning: <text>" on stderr: the one form every command warns in.
void printWarning(const std::string& text);
// The user's materials file read as eval and albedo read it: --strict honoured, warnings printed
// (or handed to `warn`, for a command that checks more before it speaks).
std::vector<MaterialParams> readUserMaterials(const std::string& path, bool strict,
                                              const std::function<void(const std::string&)>& warn = {});

}  // namespace brdfcl::cli
