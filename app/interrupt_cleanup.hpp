#pragma once
// Ctrl-C (SIGINT), SIGTERM and SIGHUP end a run without leaving its partial outputs behind
// (docs/bad-input.md, "Output"). The signals are blocked in every thread and taken by one thread
// that waits for them (sigwait), so the cleanup runs as ordinary code, not in a signal handler: it
// removes every path registered with remove_on_interrupt (an OutputSet's staging folder, and its
// output folder when the run created it), says so on stderr, and ends the process by the same
// signal, so a shell or a sweep sees how it ended.
#include <cstdint>
#include <filesystem>

namespace rtsim::app {

/// Blocks the signals and starts the waiting thread. Call once, first thing in main, before any
/// other thread starts (threads inherit the blocked signals). Child processes are started with the
/// signals unblocked (common/spawn_signals.hpp).
void install_interrupt_cleanup();

/// In a child forked to run one command in process (validation::RunQueueOptions::in_process):
/// forgets the parent's registered paths and starts the child's own waiting thread (fork copies
/// only the forking thread; the signals stay blocked).
void restart_interrupt_cleanup_after_fork();

/// `path` is removed (with everything in it) if the process is interrupted before forget_on_
/// interrupt(id). Paths are removed newest first.
std::uint64_t remove_on_interrupt(const std::filesystem::path& path);
void forget_on_interrupt(std::uint64_t id);

}  // namespace rtsim::app
