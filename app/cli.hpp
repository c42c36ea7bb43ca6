#pragma once
// The `rtsim` command line: subcommands render, run, sweep, validate, list, describe.
// Exit status: 0 success, 1 internal failure, 2 bad input (scene, config, parameter, usage).

namespace rtsim::app {

inline constexpr int kExitOk = 0;
inline constexpr int kExitFailure = 1;
inline constexpr int kExitBadInput = 2;

int run_cli(int argc, char** argv);

}  // namespace rtsim::app
