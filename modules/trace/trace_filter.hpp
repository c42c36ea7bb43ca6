#pragma once
// What a trace keeps when the user narrows it (`rtsim run --trace-window T0,T1`,
// `--trace-modules GLOB`): a window of simulated time and shell-style patterns on the module
// names (the names of stats.json's `modules`). Everything passes by default, so a trace is
// complete unless asked otherwise; events left out this way were not asked for, so they are not
// counted as dropped.
// Used by every machine (MachineTrace).
#include <fnmatch.h>

#include <cstdint>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

namespace rtsim::modules {

/// A trace file larger than this is said to be too large to open comfortably (200 MB): Perfetto's
/// web UI holds the whole trace in the browser's memory and gives up on JSON traces of a few
/// hundred MB; GTKWave loads a VCD whole.
inline constexpr std::uint64_t kTraceWarnBytes = 200'000'000;

struct TraceFilter {
  /// [from, to] in sc_time ticks; the default is all of time.
  std::uint64_t from = 0;
  std::uint64_t to = std::numeric_limits<std::uint64_t>::max();
  /// fnmatch(3) patterns without flags ('*' also matches dots: "pert0*" is pert0 and all in
  /// it); a module is kept if any matches. Empty: every module.
  std::vector<std::string> modules;

  bool windowed() const { return from != 0 || to != std::numeric_limits<std::uint64_t>::max(); }

  bool keeps_module(std::string_view name) const {
    if (modules.empty()) return true;
    const std::string n(name);
    for (const std::string& p : modules)
      if (::fnmatch(p.c_str(), n.c_str(), 0) == 0) return true;
    return false;
  }

  /// An event over [start, start + duration] touches the window.
  bool keeps_time(std::uint64_t start, std::uint64_t duration) const {
    return start <= to && start + duration >= from;
  }
};

}  // namespace rtsim::modules
