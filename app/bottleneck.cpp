#include "app/bottleneck.hpp"

#include <algorithm>
#include <map>

#include "app/json_number.hpp"
#include "app/number_text.hpp"

namespace rtsim::app {
namespace {

using json = nlohmann::json;

double number(const json& j, const char* key) { return json_number(j, key); }

/// The module (not `bottleneck`) that spent the largest share of the frame blocked on output or
/// waiting for data it asked for: who waits for the bottleneck. Empty if none waited.
std::pair<std::string, double> longest_waiter(const json& modules, const std::string& bottleneck,
                                              double frame_s) {
  std::pair<std::string, double> best{"", 0.0};
  if (frame_s <= 0) return best;
  for (const auto& [name, m] : modules.items()) {
    if (name == bottleneck) continue;
    const double waited = (number(m, "blocked_s") + number(m, "waiting_for_data_s")) / frame_s;
    if (waited > best.second) best = {name, waited};
  }
  return best;
}

/// A module's class: numbers as "*", a final one-letter suffix after "_" as "*" (the links and
/// ports of a mesh, one a direction).
std::string module_class(const std::string& name) {
  std::string c;
  c.reserve(name.size());
  for (std::size_t i = 0; i < name.size(); ++i) {
    const bool digit = name[i] >= '0' && name[i] <= '9';
    if (!digit)
      c += name[i];
    else if (i == 0 || name[i - 1] < '0' || name[i - 1] > '9')
      c += '*';  // a run of digits, once
  }
  const std::size_t n = c.size();
  if (n >= 2 && c[n - 2] == '_' && c[n - 1] >= 'a' && c[n - 1] <= 'z') c[n - 1] = '*';
  return c;
}

/// Where the time went, by class and way, largest first (only when nothing is saturated).
std::vector<TimeShare> time_by_class(const json& modules, double frame_s) {
  std::map<std::string, double> seconds;
  for (const auto& [name, m] : modules.items()) {
    if (!m.is_object()) continue;
    const std::string c = module_class(name);
    if (const double busy = number(m, "busy_s"); busy > 0) seconds[c + " busy"] += busy;
    if (const auto q = m.find("queue"); q != m.end() && q->is_object())
      if (const double occ = number(*q, "mean_occupancy"); occ > 0)
        seconds[c + " queued"] += occ * frame_s;
    for (const auto& [key, v] : m.items()) {
      if (!v.is_number() || v.get<double>() <= 0) continue;
      if (key == "waited_s")
        seconds[c + " waited"] += v.get<double>();
      else if (key.size() > 9 && key.ends_with("_waited_s"))
        seconds[c + " waiting for " + key.substr(0, key.size() - 9)] += v.get<double>();
    }
  }
  double total = 0;
  for (const auto& [w, s] : seconds) total += s;
  std::vector<TimeShare> out;
  for (const auto& [w, s] : seconds) out.push_back({w, s, total > 0 ? s / total : 0.0});
  std::stable_sort(out.begin(), out.end(),
                   [](const TimeShare& a, const TimeShare& b) { return a.seconds > b.seconds; });
  return out;
}

}  // namespace

std::vector<BusyModule> busy_modules(const json& modules) {
  std::vector<BusyModule> busy;
  for (const auto& [name, m] : modules.items())
    if (m.contains("utilization") && number(m, "busy_s") > 0)
      busy.push_back({name, m["utilization"].get<double>()});
  std::stable_sort(busy.begin(), busy.end(), [](const BusyModule& a, const BusyModule& b) {
    return a.utilization > b.utilization;
  });
  return busy;
}

Bottleneck find_bottleneck(const json& stats) {
  Bottleneck b;
  if (!stats.contains("modules")) return b;
  const json& modules = stats["modules"];
  const auto busy = busy_modules(modules);
  if (busy.empty()) return b;
  b.any = true;
  b.busiest = busy.front().name;
  b.utilization = busy.front().utilization;
  b.saturated = b.utilization >= kSaturated;
  const double frame_s = number(stats, "simulated_time_s");
  if (!b.saturated) {
    b.time = time_by_class(modules, frame_s);
    return b;
  }
  std::tie(b.waiter, b.wait_share) = longest_waiter(modules, b.busiest, frame_s);
  if (busy.size() > 1) {
    b.next = busy[1].name;
    b.next_utilization = busy[1].utilization;
  }
  return b;
}

std::string bottleneck_text(const Bottleneck& b) {
  if (!b.any) return "";
  if (!b.saturated) {
    std::string s = "none saturated: the busiest, " + b.busiest + ", is " +
                    format_percent(b.utilization) +
                    " busy; latency, dependencies and bursts of work set the frame";
    if (b.time.empty()) return s;
    s += "; the work's time: ";
    for (std::size_t i = 0; i < b.time.size() && i < 4; ++i)
      s += (i ? ", " : "") + b.time[i].where + " " + format_percent(b.time[i].share);
    return s;
  }
  std::string s = b.busiest + ", " + format_percent(b.utilization) + " busy";
  if (!b.waiter.empty() && b.wait_share >= 0.01)
    s += ": " + b.waiter + " waits " + format_percent(b.wait_share) + " of the frame";
  if (!b.next.empty())
    s += " (next busiest " + b.next + " " + format_percent(b.next_utilization) + ")";
  return s;
}

}  // namespace rtsim::app
