#pragma once
// Signal traces for GTKWave: a Value Change Dump (IEEE 1364 §18) of level signals (busy flags,
// queue depths) named by dotted hierarchical names, which become nested scopes
// ("peripheral.ray_queue.depth" is signal "depth" in scope peripheral/ray_queue).
//
// Written by hand rather than by SystemC's sc_trace: SystemC samples signals at delta cycles, so
// with temporal decoupling an edge is written when the writing thread synchronises (late) and
// two edges between synchronisations are lost. Here a signal is given whole, as the time-sorted
// value changes the statistics were computed from, and close() merges all signals into one
// time-ordered dump. Memory: the changes of every signal until close().
//
// - Time unit: SystemC's time resolution (1 ps by default), so every simulated time is exact;
//   times are sc_time ticks.
// - A level (busy) whose values are only 0 and 1 is a 1-bit wire, any other signal (a count,
//   such as a queue depth, or a level that reached 2) a 32-bit integer.
// - close(from, to, max_changes): the dump covers [from, to]: the values at `from` as $dumpvars,
//   the changes after it up to `to`, and a last time stamp `to` so a viewer draws the values up
//   to there. At most max_changes value changes are written (0: no limit); the rest are counted
//   in dropped() (the dump then ends at the last change written).
// - The file is written as PATH.partial and renamed to PATH; abandon() (and the destructor of an
//   unclosed trace) deletes it instead, so a failed run leaves no half-written trace.
// - Deterministic: the same signals give the same bytes (no date, no wall clock).
// Used by every machine (MachineTrace).
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include "modules/level_steps.hpp"

namespace rtsim::modules {

class VcdTrace {
 public:
  /// The file to write at close(); nothing is written before.
  explicit VcdTrace(std::filesystem::path path);
  ~VcdTrace();
  VcdTrace(const VcdTrace&) = delete;
  VcdTrace& operator=(const VcdTrace&) = delete;

  /// kLevel: a flag, drawn as a wire while it is only 0 or 1; kCount: always a number.
  enum class Kind { kLevel, kCount };

  /// A signal: its dotted hierarchical name and its value changes in time order (the value is 0
  /// before the first). An empty name, an empty scope segment, a repeated name or changes out of
  /// time order are std::invalid_argument (programming errors).
  void signal(const std::string& hierarchical_name, std::vector<LevelChange> changes,
              Kind kind = Kind::kLevel);

  /// Writes the file (see above) and renames it into place. Throws std::runtime_error naming the
  /// path if it cannot be written. Idempotent.
  void close(std::uint64_t from, std::uint64_t to, std::size_t max_changes = 0);
  /// Deletes the partial file instead. Idempotent; no-op after close().
  void abandon();

  const std::filesystem::path& path() const { return path_; }
  std::size_t changes_written() const { return written_; }  ///< excluding the initial values
  std::size_t changes_dropped() const { return dropped_; }
  /// The time of the first change the cap dropped (the dump holds every change before it), in
  /// SystemC ticks; the maximum when none was.
  std::uint64_t first_dropped() const { return first_dropped_; }
  std::size_t signal_count() const { return signals_.size(); }

 private:
  struct Signal {
    std::string name;  ///< dotted
    std::vector<LevelChange> changes;
    Kind kind;
  };
  void write(std::ostream& out, std::uint64_t from, std::uint64_t to, std::size_t max_changes);

  std::filesystem::path path_;
  std::vector<Signal> signals_;
  bool done_ = false;
  std::size_t written_ = 0;
  std::size_t dropped_ = 0;
  std::uint64_t first_dropped_ = std::numeric_limits<std::uint64_t>::max();
};

/// The short identifier VCD gives signal number `index` (printable ASCII, base 94), for tests.
std::string vcd_identifier(std::size_t index);
/// The $timescale of SystemC's time resolution ("1 ps", "100 fs", ...).
std::string vcd_timescale();

}  // namespace rtsim::modules
