#pragma once
// Who sets the frame, from a run's stats.json: the busiest module and, when it is saturated
// (kSaturated), who waits for it; when nothing is, the frame is set by latency and dependencies,
// and the answer is where the work spent its time instead, by module class: queued in a class of
// queues (their mean occupancy over the frame, Little's law: message-seconds), busy in a class
// of processors, units or links (busy_s: message-seconds in service or on the wire), or waiting
// for something a module names (its `waited_s`, `X_waited_s`). `rtsim run` prints it and the
// report shows it (run_summary.cpp, run_report.cpp).
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace rtsim::app {

/// Modules busier than this are saturated: the bottleneck line names the busiest.
inline constexpr double kSaturated = 0.95;

struct BusyModule {
  std::string name;
  double utilization;
};
/// Modules that were busy, busiest first (ties by name).
std::vector<BusyModule> busy_modules(const nlohmann::json& modules);

/// A class of modules ("node*.in_*": instances differing in numbers or in a one-letter
/// direction suffix) and the time spent there one way.
struct TimeShare {
  std::string where;  ///< "node*.in_* queued", "node* busy", "node*.link_* waited"
  double seconds;
  double share;  ///< of all the time counted
};

struct Bottleneck {
  bool any = false;  ///< some module was busy
  std::string busiest;
  double utilization = 0;
  bool saturated = false;
  std::string waiter;  ///< saturated: who waits longest for it, and the share of the frame
  double wait_share = 0;
  std::string next;  ///< saturated: the next busiest
  double next_utilization = 0;
  std::vector<TimeShare> time;  ///< not saturated: where the time went, largest first
};
Bottleneck find_bottleneck(const nlohmann::json& stats);
/// The line after "bottleneck  ".
std::string bottleneck_text(const Bottleneck& b);

}  // namespace rtsim::app
