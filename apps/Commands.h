#pragma once
// The nao-soccer subcommands. Each takes its arguments after the subcommand name and returns
// the process exit code (0 success, 1 failed run); bad usage or input throws nao::Error (exit 2).
#include <string>
#include <vector>

namespace nao::cli {

using Argv = std::vector<std::string>;

int renderCommand(const Argv& args);
int runCommand(const Argv& args);
int benchCommand(const Argv& args);
int perceiveCommand(const Argv& args);
int evalCommand(const Argv& args);
int calibrateCommand(const Argv& args);
int walkCommand(const Argv& args);
int kickCommand(const Argv& args);
int trainCommand(const Argv& args);

}  // namespace nao::cli
