#include "modules/stat_directory.hpp"

#include <algorithm>
#include <exception>
#include <thread>
#include <unordered_map>
#include <vector>

namespace rtsim::modules {
namespace {

/// Below this many statistics a second thread is not worth starting (a small machine's report
/// takes milliseconds).
constexpr std::size_t kStatisticsForTwoThreads = 2000;

}  // namespace

StatDirectory& StatDirectory::instance() {
  static StatDirectory directory;
  return directory;
}

void StatDirectory::add(const StatGroup& group) { groups_.emplace(group.stat_path(), &group); }

void StatDirectory::remove(const StatGroup& group) {
  auto [first, last] = groups_.equal_range(group.stat_path());
  for (auto it = first; it != last; ++it)
    if (it->second == &group) {
      groups_.erase(it);
      return;
    }
}

std::map<std::string, StatReport> StatDirectory::reports(const StatWindow& window) const {
  // What each statistic can work out alone (a busy time's utilisation windows: 6,000 timelines
  // in a 32 x 32 array) is done first on two threads, every other statistic each; the reports
  // are then written in order on this one, so they do not depend on the threads.
  std::vector<const Statistic*> all;
  for (const auto& [name, group] : groups_)
    for (const Statistic* s : group->statistics()) all.push_back(s);
  const auto prepare = [&](std::size_t first) {
    for (std::size_t k = first; k < all.size(); k += 2) all[k]->prepare_report(window);
  };
  if (all.size() >= kStatisticsForTwoThreads) {
    std::exception_ptr failed;
    std::thread other([&] {
      try {
        prepare(1);
      } catch (...) {
        failed = std::current_exception();
      }
    });
    try {
      prepare(0);
    } catch (...) {
      other.join();
      throw;
    }
    other.join();
    if (failed) std::rethrow_exception(failed);
  }
  std::map<std::string, StatReport> out;
  for (const auto& [name, group] : groups_) {
    StatReport& r = out[name];
    for (const Statistic* s : group->statistics()) s->report(r, window);
  }
  return out;
}

nlohmann::ordered_json report_json(StatReport&& r, const StatWindow& window) {
  nlohmann::ordered_json j = nlohmann::ordered_json::object();
  const double frame = (window.end - window.begin).to_seconds();
  if (r.busy_reported) {
    j["busy_s"] = r.busy.to_seconds();
    j["utilization"] = frame > 0 ? r.busy.to_seconds() / frame : 0.0;
  }
  for (auto& [k, v] : r.values) j[k] = std::move(v);
  if (!r.queue.is_null()) j["queue"] = std::move(r.queue);
  if (!r.windows.is_null()) j["utilization_windows"] = std::move(r.windows);
  return j;
}

nlohmann::ordered_json StatDirectory::to_json(const StatWindow& window, UnitSchema* units) const {
  nlohmann::ordered_json out = nlohmann::ordered_json::object();
  // The names are unique and sorted: appended without ordered_json's linear search for an
  // existing key (a 16 x 16 array has thousands of modules).
  auto& modules = out.get_ref<nlohmann::ordered_json::object_t&>();
  // Its (const name, report) pairs are copied, not moved, when the vector grows.
  modules.reserve(groups_.size());
  // By class: the keys and units its last instance declared. An instance that declares the same
  // adds nothing the schema has not got (UnitSchema::add keeps the first unit of a pattern), so
  // its keys are not worked out again: 1024 processors' hundred keys were 136,000 adds.
  std::unordered_map<std::string, std::vector<std::pair<std::string, StatUnit>>> declared;
  for (auto& [name, r] : reports(window)) {
    if (units && !r.units.empty()) {
      // Under the class's name: an array's 1024 nodes declare their keys once. (A path's class
      // is its parts' classes: the group's is worked out once, not once a key.)
      const std::string group_class = instance_class("modules." + name) + ".";
      auto& last = declared[group_class];
      if (last != r.units) {
        for (const auto& [key, unit] : r.units) units->add(group_class + instance_class(key), unit);
        last = r.units;
      }
    }
    modules.emplace_back(name, report_json(std::move(r), window));
  }
  return out;
}

std::vector<NamedSignal> StatDirectory::signals(
    const std::function<bool(const std::string&)>& keep) const {
  std::vector<NamedSignal> out;
  std::vector<TraceSignal> of_group;
  for (const auto& [name, group] : groups_) {
    if (!keep(name)) continue;
    of_group.clear();
    for (const Statistic* s : group->statistics()) s->signals(of_group);
    for (auto& s : of_group) out.push_back({name, std::move(s.kind), std::move(s.changes)});
  }
  // Per name: the busy signal, the depth signal, then the others as their groups built them.
  const auto rank = [](const NamedSignal& s) {
    return s.kind == "busy" ? 0 : s.kind == "depth" ? 1 : 2;
  };
  std::stable_sort(out.begin(), out.end(), [&](const NamedSignal& a, const NamedSignal& b) {
    return a.name != b.name ? a.name < b.name : rank(a) < rank(b);
  });
  return out;
}

}  // namespace rtsim::modules
