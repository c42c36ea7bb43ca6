#include "platform/sweep/results_table.hpp"

#include <algorithm>
#include <array>
#include <map>
#include <set>
#include <sstream>

#include "common/csv_field.hpp"
#include "modules/stat_classes.hpp"

namespace rtsim::sweep {

namespace {

using Json = nlohmann::ordered_json;

// stats.json keys that are not stats columns: constant for a sweep, already leading columns, or
// the whole parameter set and the units of the numbers (in each point's own stats.json).
constexpr std::array<std::string_view, 10> kNotStats = {
    "tool",  "version", "schema_version", "command", "machine",
    "scene", "width",   "height",         "params",  "units"};

// The stats a reader looks for first, in this order; the rest follow sorted by name.
constexpr std::array<std::string_view, 13> kHeadline = {
    "simulated_time_s",   "wall_time_s",        "rays.total",
    "rays.primary",       "rays.shadow",        "rays.reflected",
    "rays.refracted",     "intersection_tests", "hits",
    "ray_latency_s.mean", "ray_latency_s.p50",  "ray_latency_s.p99",
    "ray_latency_s.max"};

void flatten(const Json& j, const std::string& prefix,
             std::vector<std::pair<std::string, Json>>& out) {
  for (const auto& [key, value] : j.items()) {
    if (prefix.empty() && std::find(kNotStats.begin(), kNotStats.end(), key) != kNotStats.end())
      continue;
    const std::string path = prefix.empty() ? key : prefix + "." + key;
    if (value.is_object()) {
      flatten(value, path, out);
    } else if (!value.is_array()) {
      out.emplace_back(path, value);
    }
  }
}

// The aggregates the table keeps of every class, for the report's band of the class (min, mean,
// max and the busiest instance); a class too large for instance columns keeps every key's mean.
constexpr std::array<std::string_view, 2> kBandKeys = {"utilization", "queue.mean_occupancy"};

void class_columns(const Json& classes, const std::set<std::string>& aggregated,
                   std::vector<std::pair<std::string, Json>>& out) {
  for (const auto& [name, c] : classes.items()) {
    const std::string path = "module_classes." + name;
    out.emplace_back(path + ".instances", c.value("instances", std::size_t{0}));
    for (const auto& [key, agg] : c.items()) {
      if (key == "instances" || !agg.is_object()) continue;
      if (std::find(kBandKeys.begin(), kBandKeys.end(), key) != kBandKeys.end()) {
        for (const char* a : {"min", "mean", "max", "max_instance"})
          if (agg.contains(a)) out.emplace_back(path + "." + key + "." + a, agg[a]);
      } else if (aggregated.contains(name) && agg.contains("mean")) {
        out.emplace_back(path + "." + key + ".mean", agg["mean"]);
      }
    }
  }
}

/// Each class's instance count in `stats` (module_classes).
std::map<std::string, std::size_t> class_sizes(const Json& stats) {
  std::map<std::string, std::size_t> sizes;
  if (const auto c = stats.find("module_classes"); c != stats.end() && c->is_object())
    for (const auto& [name, j] : c->items()) sizes[name] = j.value("instances", std::size_t{0});
  return sizes;
}

}  // namespace

std::vector<std::pair<std::string, Json>> stats_leaves(const Json& stats) {
  std::vector<std::pair<std::string, Json>> out;
  flatten(stats, "", out);
  return out;
}

std::set<std::string> aggregated_classes(const std::vector<Json>& docs) {
  std::map<std::string, std::set<std::size_t>> sizes;
  for (const Json& d : docs)
    for (const auto& [name, n] : class_sizes(d)) sizes[name].insert(n);
  std::set<std::string> out;
  for (const auto& [name, n] : sizes)
    if (n.size() > 1 || *n.rbegin() > modules::kInstancesShownUpTo) out.insert(name);
  return out;
}

std::vector<std::pair<std::string, Json>> table_leaves(const Json& stats,
                                                       const std::set<std::string>& aggregated) {
  std::vector<std::pair<std::string, Json>> out;
  for (const auto& [key, value] : stats.items()) {
    if (std::find(kNotStats.begin(), kNotStats.end(), key) != kNotStats.end()) continue;
    if (key == "modules" && value.is_object()) {
      for (const auto& [name, m] : value.items()) {
        if (aggregated.contains(modules::instance_class(name))) continue;
        if (m.is_object())
          flatten(m, "modules." + name, out);
        else if (!m.is_array())
          out.emplace_back("modules." + name, m);
      }
    } else if (key == "module_classes" && value.is_object()) {
      class_columns(value, aggregated, out);
    } else if (key == "simulation" && value.is_object()) {
      // The totals; the activations by process are the point's stats.json's (a large array
      // would be a column a node).
      for (const auto& [name, v] : value.items())
        if (!v.is_structured()) out.emplace_back("simulation." + name, v);
    } else if (value.is_object()) {
      flatten(value, key, out);
    } else if (!value.is_array()) {
      out.emplace_back(key, value);
    }
  }
  return out;
}

std::string modules_csv(const Json& stats) {
  const auto m = stats.find("modules");
  if (m == stats.end() || !m->is_object()) return "module,class\n";
  std::vector<std::string> keys;
  std::set<std::string> seen;
  std::vector<std::vector<std::pair<std::string, double>>> rows;
  for (const auto& [name, module] : m->items()) {
    rows.push_back(modules::numeric_leaves(module));
    for (const auto& [k, v] : rows.back())
      if (seen.insert(k).second) keys.push_back(k);
  }
  std::ostringstream out;
  out << "module,class";
  for (const auto& k : keys) out << "," << csv_field(k);
  out << "\n";
  std::size_t r = 0;
  for (const auto& [name, module] : m->items()) {
    const std::map<std::string, double> values(rows[r].begin(), rows[r].end());
    ++r;
    out << csv_field(name) << "," << csv_field(modules::instance_class(name));
    for (const auto& k : keys) {
      out << ",";
      if (const auto v = values.find(k); v != values.end()) out << Json(v->second).dump();
    }
    out << "\n";
  }
  return out.str();
}

namespace {

std::string csv_cell(const Json& v) {
  if (v.is_null()) return "";
  if (v.is_string()) return csv_field(v.get<std::string>());
  return v.dump();
}

}  // namespace

bool is_wall_clock_column(std::string_view column) {
  return column == "point_wall_time_s" || column == "wall_time_s" || column == "rays_per_second" ||
         column == "functional_wall_time_s" || column == "overhead_ratio";
}

ResultsTable make_results_table(const SweepFile& file, const std::vector<Point>& points,
                                const std::vector<PointOutcome>& outcomes) {
  ResultsTable t;
  const std::vector<std::string> swept = file.swept_columns();
  std::vector<std::string> leading = {"point", "machine", "scene", "width", "height"};
  leading.insert(leading.end(), swept.begin(), swept.end());
  for (const char* c : {"status", "exit_code", "error", "point_wall_time_s", "dir"})
    leading.emplace_back(c);
  const std::set<std::string> taken(leading.begin(), leading.end());

  // Each row's stats, flattened; a stats path that is already a column gets "stats." in front.
  std::vector<Json> docs(points.size());
  std::vector<std::map<std::string, Json>> stats(points.size());
  std::set<std::string> stat_names;
  for (std::size_t i = 0; i < points.size(); ++i)
    if (outcomes[i].ok) {
      docs[i] = Json::parse(outcomes[i].stats_text);
      t.units.add(modules::UnitSchema::from_stats(docs[i]));
    }
  const std::set<std::string> aggregated = aggregated_classes(docs);
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!outcomes[i].ok) continue;
    const std::vector<std::pair<std::string, Json>> leaves = table_leaves(docs[i], aggregated);
    for (const auto& [path, value] : leaves) {
      std::string name = taken.contains(path) ? "stats." + path : path;
      stat_names.insert(name);
      stats[i][name] = value;
    }
  }
  std::vector<std::string> stat_columns;
  for (std::string_view h : kHeadline)
    if (stat_names.contains(std::string(h))) stat_columns.emplace_back(h);
  for (const auto& n : stat_names)
    if (std::find(kHeadline.begin(), kHeadline.end(), n) == kHeadline.end())
      stat_columns.push_back(n);

  t.columns = leading;
  t.columns.insert(t.columns.end(), stat_columns.begin(), stat_columns.end());
  t.columns.emplace_back("command");

  for (std::size_t i = 0; i < points.size(); ++i) {
    const Point& p = points[i];
    const PointOutcome& o = outcomes[i];
    std::vector<Json> row;
    row.emplace_back(p.index);
    row.emplace_back(p.machine());
    row.emplace_back(p.scene());
    for (std::string_view size : {kWidth, kHeight}) {
      // As rendered when the run said so; else as asked (null: the scene's own size).
      const std::string key(size);
      if (docs[i].contains(key)) {
        row.push_back(docs[i][key]);
      } else if (const Setting* set = p.find(size)) {
        row.push_back(set->value.json);
      } else {
        row.emplace_back(nullptr);
      }
    }
    for (const auto& name : swept) row.push_back(p.find(name)->value.json);
    row.emplace_back(o.ok ? "ok" : (o.interrupted ? "interrupted" : "failed"));
    row.emplace_back(o.exit_code);
    row.emplace_back(o.error);
    row.emplace_back(o.wall_s);
    row.emplace_back("points/" + p.key);
    for (const auto& c : stat_columns) {
      auto it = stats[i].find(c);
      row.push_back(it == stats[i].end() ? Json() : it->second);
    }
    row.emplace_back(p.command_line());
    t.rows.push_back(std::move(row));
  }
  return t;
}

std::string to_csv(const ResultsTable& table) {
  std::ostringstream out;
  for (std::size_t c = 0; c < table.columns.size(); ++c)
    out << (c ? "," : "") << csv_field(table.columns[c]);
  out << "\n";
  for (const auto& row : table.rows) {
    for (std::size_t c = 0; c < row.size(); ++c) out << (c ? "," : "") << csv_cell(row[c]);
    out << "\n";
  }
  return out.str();
}

std::string to_jsonl(const ResultsTable& table) {
  std::ostringstream out;
  for (const auto& row : table.rows) {
    Json j = Json::object();
    for (std::size_t c = 0; c < row.size(); ++c) j[table.columns[c]] = row[c];
    out << j.dump() << "\n";
  }
  return out.str();
}

}  // namespace rtsim::sweep
