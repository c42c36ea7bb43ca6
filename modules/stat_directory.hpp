#pragma once
// Every statistics group alive (modules/statistics.hpp), by hierarchical name: what stats.json's
// `modules` tree and the traces' busy and depth signals are written from. A group enters when
// it is built and leaves when it is destroyed, so a run reports exactly the modules it built,
// with no list kept by the machine. Groups that share a name (a module and the queue it is, a
// processor and the counters its subclass adds) are one entry.
//
// stats.json `modules`:
//   {name: {busy_s, utilization, ...values by name, queue: {capacity, mean_occupancy,
//           max_occupancy}, utilization_windows: {begin_s, window_s, values}}}
// (docs/stats.md). SystemC runs one simulation per process, so one directory serves.
// Used by MachineRun (every machine) and MachineTrace.
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "modules/statistics.hpp"

namespace rtsim::modules {

/// One group's trace signal: NAME.kind.
struct NamedSignal {
  std::string name;
  std::string kind;
  std::vector<LevelChange> changes;
};

class StatDirectory {
 public:
  static StatDirectory& instance();

  void add(const StatGroup& group);
  void remove(const StatGroup& group);

  /// Every group, by name; groups of one name in the order they were built.
  const std::multimap<std::string, const StatGroup*>& groups() const { return groups_; }
  /// The report of every name over `window`.
  std::map<std::string, StatReport> reports(const StatWindow& window) const;
  /// stats.json `modules` over `window`.
  nlohmann::ordered_json to_json(const StatWindow& window) const;
  /// The traces' level signals of every group whose name `keep` accepts, by name then kind
  /// (a signal's changes are worked out only for a name kept).
  std::vector<NamedSignal> signals(const std::function<bool(const std::string&)>& keep) const;

 private:
  std::multimap<std::string, const StatGroup*> groups_;
};

/// A group's report as stats.json writes it.
nlohmann::ordered_json report_json(const StatReport& r, const StatWindow& window);

}  // namespace rtsim::modules
