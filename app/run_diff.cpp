#include "app/run_diff.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>

#include "app/number_text.hpp"
#include "platform/sweep/results_table.hpp"

namespace rtsim::app {
namespace {

using Json = nlohmann::ordered_json;

bool same(const Json& a, const Json& b, double tolerance) {
  if (a.is_number() && b.is_number()) {
    const double x = a.get<double>(), y = b.get<double>();
    if (x == y) return true;
    return std::abs(y - x) <= tolerance * std::max(std::abs(x), std::abs(y));
  }
  return a == b;
}

std::optional<double> relative_change(const Json& a, const Json& b) {
  if (!a.is_number() || !b.is_number() || a.get<double>() == 0.0) return std::nullopt;
  return (b.get<double>() - a.get<double>()) / std::abs(a.get<double>());
}

/// Name-keyed leaves of both sides, in a's order then b's new ones.
void compare(const std::vector<std::pair<std::string, Json>>& a,
             const std::vector<std::pair<std::string, Json>>& b, double tolerance,
             std::vector<RunDiff::Change>& out, std::size_t* compared = nullptr) {
  std::map<std::string, const Json*> in_b;
  for (const auto& [k, v] : b) in_b[k] = &v;
  std::map<std::string, bool> seen;
  for (const auto& [k, v] : a) {
    seen[k] = true;
    const auto it = in_b.find(k);
    const Json other = it == in_b.end() ? Json() : *it->second;
    if (!same(v, other, tolerance)) out.push_back({k, v, other, relative_change(v, other)});
  }
  std::size_t only_in_b = 0;
  for (const auto& [k, v] : b) {
    if (seen.count(k)) continue;
    out.push_back({k, Json(), v, std::nullopt});
    ++only_in_b;
  }
  if (compared) *compared = seen.size() + only_in_b;
}

std::vector<std::pair<std::string, Json>> params_of(const Json& stats) {
  std::vector<std::pair<std::string, Json>> out;
  if (const auto it = stats.find("params"); it != stats.end() && it->is_object())
    for (const auto& [k, v] : it->items()) out.emplace_back(k, v);
  return out;
}

/// A value as the diff shows it (format_figure in the unit the files declare: times in
/// engineering units, rates per second, fractions as percentages, numbers to 4 significant
/// digits), "-" for absent.
std::string shown(const modules::UnitSchema& units, const std::string& name, const Json& v) {
  if (v.is_null()) return "-";
  if (v.is_string()) return v.get<std::string>();
  if (v.is_boolean()) return v.get<bool>() ? "true" : "false";
  if (!v.is_number()) return v.dump();
  return format_figure(units, name, v.get<double>());
}

std::string relative_text(const RunDiff::Change& c) {
  if (c.a.is_null()) return "new";
  if (c.b.is_null()) return "gone";
  if (!c.relative) return c.a.is_number() ? "from 0" : "";
  return format_change(*c.relative);
}

void print_changes(std::ostream& out, const modules::UnitSchema& units,
                   const std::vector<RunDiff::Change>& changes, std::size_t max_count,
                   bool with_relative) {
  std::size_t width = 0;
  const std::size_t n = max_count > 0 ? std::min(max_count, changes.size()) : changes.size();
  for (std::size_t i = 0; i < n; ++i) width = std::max(width, changes[i].name.size());
  for (std::size_t i = 0; i < n; ++i) {
    const auto& c = changes[i];
    std::string name = c.name;
    name.resize(width + 2, ' ');
    out << "  " << name << shown(units, c.name, c.a) << " -> " << shown(units, c.name, c.b);
    if (with_relative) {
      const std::string rel = relative_text(c);
      if (!rel.empty()) out << "   " << rel;
    }
    out << "\n";
  }
  if (n < changes.size()) out << "  ... and " << changes.size() - n << " more (--all)\n";
}

}  // namespace

RunDiff diff_runs(const Json& a, const Json& b, double tolerance) {
  RunDiff d;
  d.units = modules::UnitSchema::from_stats(b);
  d.units.add(modules::UnitSchema::from_stats(a));
  std::vector<std::pair<std::string, Json>> run_a, run_b;
  for (const char* k : {"machine", "scene", "width", "height", "spp"}) {
    if (a.contains(k)) run_a.emplace_back(k, a[k]);
    if (b.contains(k)) run_b.emplace_back(k, b[k]);
  }
  compare(run_a, run_b, 0.0, d.run);
  compare(params_of(a), params_of(b), 0.0, d.params);

  std::vector<RunDiff::Change> all;
  compare(sweep::stats_leaves(a), sweep::stats_leaves(b), tolerance, all, &d.stats_compared);
  for (auto& c : all) {
    const std::string leaf = c.name.substr(c.name.rfind('.') + 1);
    (sweep::is_wall_clock_column(c.name) || sweep::is_wall_clock_column(leaf) ? d.wall_clock
                                                                              : d.stats)
        .push_back(std::move(c));
  }
  // Largest relative change first; changes with no relative size (new, gone, from 0, text)
  // after, by name.
  std::stable_sort(d.stats.begin(), d.stats.end(), [](const auto& x, const auto& y) {
    if (x.relative.has_value() != y.relative.has_value()) return x.relative.has_value();
    if (x.relative && std::abs(*x.relative) != std::abs(*y.relative))
      return std::abs(*x.relative) > std::abs(*y.relative);
    return x.name < y.name;
  });
  return d;
}

std::string format_run_diff(const RunDiff& d, const std::string& label_a,
                            const std::string& label_b, std::size_t max_stats) {
  std::ostringstream out;
  out << "rtsim diff: A = " << label_a << "\n            B = " << label_b << "\n";
  if (!d.run.empty()) {
    out << "runs differ in:\n";
    print_changes(out, d.units, d.run, 0, false);
  }
  if (d.params.empty()) {
    out << "parameters: the same\n";
  } else {
    out << "parameters that differ (" << d.params.size() << "):\n";
    print_changes(out, d.units, d.params, 0, false);
  }
  // The headline first: the simulated frame time.
  for (const auto& c : d.stats)
    if (c.name == "simulated_time_s")
      out << "frame time: " << shown(d.units, c.name, c.a) << " -> " << shown(d.units, c.name, c.b)
          << "   " << relative_text(c) << "\n";
  if (d.stats.empty()) {
    out << "statistics: the same (" << d.stats_compared << " compared)\n";
  } else {
    out << "statistics that changed (" << d.stats.size() << " of " << d.stats_compared
        << "), largest relative change first:\n";
    print_changes(out, d.units, d.stats, max_stats, true);
  }
  if (!d.wall_clock.empty()) {
    out << "wall clock (differs between any two runs):\n";
    print_changes(out, d.units, d.wall_clock, 0, true);
  }
  return out.str();
}

}  // namespace rtsim::app
