#pragma once
// Ctrl-C (SIGINT), SIGTERM and SIGHUP end a run without leaving its partial outputs behind
// (docs/bad-input.md, "Output"). The signals are blocked in every thread and taken by one thread
// that waits for them (sigwait), so the cleanup runs as ordinary code, not in a signal handler: it
// removes every path registered with remove_on_interrupt (an OutputSet's staging folder, and its
// output folder when the run created it), says so on stderr, and ends the process by the same
// signal, so a shell or a sweep sees how it ended.
#include <cstdint>
#include <filesystem>
#include <functional>

namespace rtsim::app {

/// Blocks the signals and starts the waiting thread. Call once, first thing in main, before any
/// other thread starts (threads inherit the blocked signals). Child processes are started with the
/// signals unblocked (common/spawn_signals.hpp).
void install_interrupt_cleanup();

/// In a child forked to run one command in process (runs::RunQueueOptions::in_process):
/// forgets the parent's registered paths and starts the child's own waiting thread (fork copies
/// only the forking thread; the signals stay blocked).
void restart_interrupt_cleanup_after_fork();

/// A command that must finish its own way when interrupted (`rtsim sweep`: stop its runs, write
/// the partial table, say how to resume) sets a handler: the first signal calls it, from the
/// waiting thread, instead of the cleanup; the command then ends itself with end_by_signal. A
/// second signal does the cleanup and ends the process at once. An empty handler restores the
/// default.
void set_interrupt_handler(std::function<void(int sig)> handler);

/// Ends the process by `sig` (its default action), so a shell or a parent sees how it ended.
[[noreturn]] void end_by_signal(int sig);

/// `path` is removed (with everything in it) if the process is interrupted before forget_on_
/// interrupt(id). Paths are removed newest first.
std::uint64_t remove_on_interrupt(const std::filesystem::path& path);
/// Runs `make` (which creates `path`) and registers `path`, as one step the cleanup cannot come
/// between: an interrupt either finds nothing made and nothing registered, or both (made first and
/// registered after, a signal in between left the folder behind; registered first, the cleanup
/// could remove it and `make` create it again before the process ended).
std::uint64_t make_and_remove_on_interrupt(const std::filesystem::path& path,
                                           const std::function<void()>& make);
void forget_on_interrupt(std::uint64_t id);

}  // namespace rtsim::app
