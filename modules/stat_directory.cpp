#include "modules/stat_directory.hpp"

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <exception>
#include <stdexcept>
#include <thread>
#include <unordered_map>
#include <vector>

namespace rtsim::modules {
namespace {

/// Below this many statistics a second thread is not worth starting (a small machine's report
/// takes milliseconds).
constexpr std::size_t kStatisticsForTwoThreads = 2000;
/// Names a thread takes at a time (named_reports).
constexpr std::size_t kNamesATake = 16;

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

std::vector<StatDirectory::NamedReport> StatDirectory::named_reports(const StatWindow& window,
                                                                     bool as_json) const {
  // One entry a name: groups of one name report as one.
  std::vector<NamedReport> out;
  std::vector<std::pair<Groups::const_iterator, Groups::const_iterator>> ranges;
  std::size_t statistics = 0;
  for (auto it = groups_.begin(); it != groups_.end();) {
    const auto last = groups_.upper_bound(it->first);
    out.push_back({it->first, {}, {}});
    ranges.emplace_back(it, last);
    for (auto g = it; g != last; ++g) statistics += g->second->statistics().size();
    it = last;
  }
  // Every name's statistics work out their reports (a busy time's utilisation windows: 6,000
  // timelines in a 32 x 32 array) and, for stats.json, their JSON, on two threads that take the
  // names a few at a time, in name order, whichever is free (names cost very differently: every
  // second name, as it was, gave one thread 2.3 times the other's work at 32 x 32). Each name's
  // report is its own statistics' alone, so it does not depend on the threads; the caller takes
  // them in name order.
  const auto report = [&](std::size_t k) {
    NamedReport& n = out[k];
    for (auto g = ranges[k].first; g != ranges[k].second; ++g)
      for (const Statistic* s : g->second->statistics()) s->report(n.report, window);
    if (as_json) {
      n.units = std::move(n.report.units);
      n.json = report_json(std::move(n.report), window);
      n.report = StatReport{};
    }
  };
  // A failure is the first name's in name order, as if one thread had done them all: each
  // thread takes its names in increasing order and stops at its first failure, and every name
  // before that one had been taken, by one thread or the other, which stopped at its own first.
  struct Failure {
    std::size_t at = SIZE_MAX;
    std::exception_ptr error;
  };
  std::atomic<std::size_t> next{0};
  const auto run = [&](Failure& failed) {
    for (;;) {
      const std::size_t from = next.fetch_add(kNamesATake, std::memory_order_relaxed);
      if (from >= out.size()) return;
      for (std::size_t k = from; k < std::min(from + kNamesATake, out.size()); ++k) {
        try {
          report(k);
        } catch (const std::logic_error& e) {
          // A modelling error (two busy times under one name): which module it is in.
          failed = {k, std::make_exception_ptr(std::logic_error(out[k].name + ": " + e.what()))};
          return;
        } catch (...) {
          failed = {k, std::current_exception()};
          return;
        }
      }
    }
  };
  Failure mine, other_failed;
  if (statistics >= kStatisticsForTwoThreads) {
    std::thread other([&] { run(other_failed); });
    run(mine);
    other.join();
  } else {
    run(mine);
  }
  const Failure& first = mine.at <= other_failed.at ? mine : other_failed;
  if (first.error) std::rethrow_exception(first.error);
  return out;
}

std::map<std::string, StatReport> StatDirectory::reports(const StatWindow& window) const {
  std::map<std::string, StatReport> out;
  for (NamedReport& n : named_reports(window, false))
    out.emplace(std::move(n.name), std::move(n.report));
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
  for (NamedReport& n : named_reports(window, true)) {
    if (units && !n.units.empty()) {
      // Under the class's name: an array's 1024 nodes declare their keys once. (A path's class
      // is its parts' classes: the group's is worked out once, not once a key.)
      const std::string group_class = instance_class("modules." + n.name) + ".";
      auto& last = declared[group_class];
      if (last != n.units) {
        for (const auto& [key, unit] : n.units) units->add(group_class + instance_class(key), unit);
        last = std::move(n.units);
      }
    }
    modules.emplace_back(std::move(n.name), std::move(n.json));
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
