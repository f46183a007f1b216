#pragma once
// The `bounce` command line. Each subcommand lives in its own file (XCommand.cpp) and registers
// itself through one of the functions below; runCli() wires them into CLI11.
#include <CLI/CLI.hpp>

#include <functional>

namespace bounce {

// Runs after parsing succeeded; returns the process exit code. Errors are printed as one line,
// "bounce <command>: <message>", on stderr, and leave no output file behind.
using CommandAction = std::function<int()>;

void registerListCommand(CLI::App& root, CommandAction& action);
void registerInfoCommand(CLI::App& root, CommandAction& action);
void registerRenderCommand(CLI::App& root, CommandAction& action);
void registerViewCommand(CLI::App& root, CommandAction& action);
void registerReferenceCommand(CLI::App& root, CommandAction& action);
void registerCompareCommand(CLI::App& root, CommandAction& action);
void registerPhotonMapCommand(CLI::App& root, CommandAction& action);
void registerSweepCommand(CLI::App& root, CommandAction& action);
void registerReportCommand(CLI::App& root, CommandAction& action);

int runCli(int argc, char** argv);

// Prints "bounce <command>: <message>" to stderr and returns exit code 1.
int failCommand(const std::string& command, const std::string& message);
// The message as one line: line breaks of multi-line messages (shader logs, library exceptions)
// become " | " (what failCommand prints and `import bounce`'s exceptions carry).
std::string oneLine(const std::string& message);

}  // namespace bounce
