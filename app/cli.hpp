#pragma once
// The `rtsim` command line: subcommands render, run, sweep, validate, list, describe.
// Exit status: 0 success, 1 internal failure, 2 bad input (scene, config, parameter, usage).

#include <string>
#include <vector>

namespace rtsim::app {

inline constexpr int kExitOk = 0;
inline constexpr int kExitFailure = 1;
inline constexpr int kExitBadInput = 2;

int run_cli(int argc, char** argv);

/// run_cli in a child forked by `rtsim sweep` or `rtsim validate` for one run
/// (runs::RunQueueOptions::in_process): `args` as a command line, argv[0] included.
int run_cli_in_forked_child(const std::vector<std::string>& args);

}  // namespace rtsim::app
