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
#include <string_view>
#include <vector>

#include "modules/stat_classes.hpp"
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
  /// stats.json `modules` over `window`; with `units`, declares there the unit of each key of
  /// each module class ("modules.node*.link_e.bits": bits), as its statistics give it.
  nlohmann::ordered_json to_json(const StatWindow& window, UnitSchema* units = nullptr) const;
  /// The traces' level signals of every group whose name `keep` accepts, by name then kind
  /// (a signal's changes are worked out only for a name kept).
  std::vector<NamedSignal> signals(const std::function<bool(const std::string&)>& keep) const;

  /// The statistics of type S named `stat` of every module of class `cls` (stat_classes.hpp:
  /// "pert*.shell"; a name without digits is a class of one), in name order: what a machine's
  /// own section sums over a class (gaudet-pert's figures per ray over every PERT) without a
  /// getter in the module.
  template <class S>
  std::vector<const S*> of_class(std::string_view cls, std::string_view stat) const {
    std::vector<const S*> out;
    for (const auto& [name, group] : groups_) {
      if (instance_class(name) != cls) continue;
      for (const Statistic* s : group->statistics())
        if (s->name() == stat)
          if (const auto* typed = dynamic_cast<const S*>(s)) out.push_back(typed);
    }
    return out;
  }
  /// The sum of the Counters named `stat` over the modules of class `cls` (of_class).
  std::uint64_t count_over(std::string_view cls, std::string_view stat) const {
    std::uint64_t total = 0;
    for (const Counter* c : of_class<Counter>(cls, stat)) total += c->value();
    return total;
  }

 private:
  using Groups = std::multimap<std::string, const StatGroup*>;
  /// A name's report, or (as_json) its stats.json object and the units of its keys.
  struct NamedReport {
    std::string name;
    StatReport report;
    nlohmann::ordered_json json;
    std::vector<std::pair<std::string, StatUnit>> units{};
  };
  /// Every name's report over `window`, in name order (on two threads for a large machine).
  std::vector<NamedReport> named_reports(const StatWindow& window, bool as_json) const;

  Groups groups_;
};

/// A group's report as stats.json writes it (its values moved out: the utilisation windows of
/// thousands of modules are not copied).
nlohmann::ordered_json report_json(StatReport&& r, const StatWindow& window);

}  // namespace rtsim::modules
