#include "app/sweep_report.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <stdexcept>

#include "app/configuration.hpp"
#include "app/number_text.hpp"
#include "app/run_diff.hpp"
#include "common/input_error.hpp"
#include "common/seed_citation.hpp"
#include "modules/stat_classes.hpp"
#include "platform/machine.hpp"
#include "platform/machine_registry.hpp"

namespace rtsim::app {

namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;

namespace {

// The sweep file is shown whole up to this size.
constexpr std::size_t kMaxSweepText = 200000;
// Failed points listed with their error (the results table has them all).
constexpr std::size_t kMaxFailuresListed = 200;
// Values of an axis listed in the headline before "...".
constexpr std::size_t kMaxAxisValuesShown = 12;
// The other axes become the lines of an axis's plots when their combinations are at most this
// many; else the first other axis with at most this many values does, the rest are averaged.
constexpr std::size_t kMaxLines = 12;
// A stat spanning more than this ratio (all values above 0) is drawn on a log axis.
constexpr double kLogSpan = 20.0;
// Thumbnails are drawn this many pixels wide (pixels kept sharp).
constexpr int kThumbPixels = 128;

bool ends_with(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

bool starts_with(const std::string& s, const std::string& head) { return s.rfind(head, 0) == 0; }

/// A cell's number: JSON numbers as they are, "250 ns" as 250 (the axis's values share a unit,
/// so ratios and spacing are right); NaN for anything else.
double as_number(const Json& v) {
  if (v.is_number()) return v.get<double>();
  if (v.is_string()) {
    const std::string s = v.get<std::string>();
    char* end = nullptr;
    const double d = std::strtod(s.c_str(), &end);
    if (end != s.c_str()) return d;
  }
  return NAN;
}

/// A results cell as people read it: a stats column in the unit its points' stats.json declare
/// (format_figure; ResultsTable::units), a swept value as written.
std::string cell_text(const Json& v, const std::string& column, const modules::UnitSchema& units) {
  if (v.is_null()) return "";
  if (v.is_string()) return v.get<std::string>();
  if (v.is_boolean()) return v.get<bool>() ? "true" : "false";
  if (v.is_number_integer() && !units.unit_of(column)) return std::to_string(v.get<long long>());
  if (v.is_number()) return format_figure(units, column, v.get<double>());
  return v.dump();
}

std::string value_list(const std::vector<sweep::Value>& values) {
  std::string s;
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (i == kMaxAxisValuesShown && values.size() > kMaxAxisValuesShown + 1) {
      s += ", ... " + values.back().text;
      break;
    }
    s += (i ? ", " : "") + values[i].text;
  }
  return s;
}

/// The table's columns by name and its successful rows.
struct TableView {
  const sweep::ResultsTable& table;
  std::map<std::string, std::size_t> index;
  std::vector<std::size_t> ok_rows;

  explicit TableView(const sweep::ResultsTable& t) : table(t) {
    for (std::size_t i = 0; i < t.columns.size(); ++i) index[t.columns[i]] = i;
    const auto status = index.find("status");
    for (std::size_t r = 0; r < t.rows.size(); ++r)
      if (status != index.end() && t.rows[r][status->second] == "ok") ok_rows.push_back(r);
  }
  bool has(const std::string& c) const { return index.contains(c); }
  const Json& at(std::size_t row, const std::string& c) const {
    static const Json null;
    const auto it = index.find(c);
    return it == index.end() ? null : table.rows[row][it->second];
  }
  /// The column's numbers over the successful rows (NaN-free).
  std::vector<double> numbers(const std::string& c) const {
    std::vector<double> out;
    if (!has(c)) return out;
    for (std::size_t r : ok_rows) {
      const Json& v = at(r, c);
      if (v.is_number() && std::isfinite(v.get<double>())) out.push_back(v.get<double>());
    }
    return out;
  }
};

bool spans_decades(const std::vector<double>& v) {
  if (v.empty()) return false;
  const auto [lo, hi] = std::minmax_element(v.begin(), v.end());
  return *lo > 0 && *hi / *lo > kLogSpan;
}

/// Whether sorted positive values are closer to equal ratios than to equal steps.
bool log_spaced(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  v.erase(std::unique(v.begin(), v.end()), v.end());
  if (v.size() < 3 || v.front() <= 0 || v.back() / v.front() < 16) return false;
  const auto spread = [](const std::vector<double>& d) {
    double mean = 0, var = 0;
    for (double x : d) mean += x;
    mean /= static_cast<double>(d.size());
    for (double x : d) var += (x - mean) * (x - mean);
    return std::sqrt(var / static_cast<double>(d.size())) / mean;
  };
  std::vector<double> lin, lg;
  for (std::size_t i = 1; i < v.size(); ++i) {
    lin.push_back(v[i] - v[i - 1]);
    lg.push_back(std::log(v[i] / v[i - 1]));
  }
  return spread(lg) < spread(lin);
}

/// How much brighter a point's thumbnail is shown: an image whose mean is dark (no light
/// reaches the camera, or shade.max_depth = 0 leaves the ambient term alone) would look black at
/// thumbnail size. 1 for an image bright enough, or without a mean in its stats.json.
double thumbnail_gain(const std::string& stats_text) {
  constexpr double kDark = 0.15, kShownMean = 0.45, kMaxGain = 8.0;
  const auto stats = nlohmann::json::parse(stats_text, nullptr, false);
  if (stats.is_discarded() || !stats.contains("image") || !stats["image"].contains("mean_rgb"))
    return 1.0;
  const auto& rgb = stats["image"]["mean_rgb"];
  if (!rgb.is_array() || rgb.size() != 3) return 1.0;
  // Rec. 709 luma of the mean colour.
  const double luma =
      0.2126 * rgb[0].get<double>() + 0.7152 * rgb[1].get<double>() + 0.0722 * rgb[2].get<double>();
  if (luma >= kDark) return 1.0;
  return luma > 0 ? std::min(kMaxGain, kShownMean / luma) : kMaxGain;
}

/// --baseline: every point that ran against the baseline point, as `rtsim diff` compares two
/// runs: frame time, its change, the speed-up, and the largest other changes.
void baseline_section(HtmlReport& page, const SweepReportInputs& in) {
  constexpr std::size_t kChangesShown = 3;
  const auto& points = *in.points;
  const auto& base_outcome = (*in.outcomes)[*in.baseline];
  page.heading("Against the baseline: point " + points[*in.baseline].key);
  if (!base_outcome.ok) {
    page.note("Point " + points[*in.baseline].key +
              " did not run to the end: nothing to compare with.");
    return;
  }
  const auto base = nlohmann::ordered_json::parse(base_outcome.stats_text, nullptr, false);
  if (base.is_discarded()) return;  // an ok point's stats.json was read as JSON already
  std::vector<std::vector<std::string>> rows;
  std::vector<bool> bold;
  for (const auto& p : points) {
    const auto& o = (*in.outcomes)[p.index];
    if (!o.ok) continue;
    const auto stats = nlohmann::ordered_json::parse(o.stats_text, nullptr, false);
    if (stats.is_discarded()) continue;
    const RunDiff d = diff_runs(base, stats);
    std::string frame_change = "0%", speedup = "1", others;
    std::size_t shown = 0;
    for (const auto& c : d.stats) {
      if (c.name == "simulated_time_s") {
        if (c.relative) frame_change = format_change(*c.relative);
        continue;
      }
      if (!c.relative || shown == kChangesShown) continue;
      others += (others.empty() ? "" : "; ") + c.name + " " + format_change(*c.relative);
      ++shown;
    }
    const double t = stats.value("simulated_time_s", 0.0), t0 = base.value("simulated_time_s", 0.0);
    if (t > 0) speedup = format_significant(t0 / t, 3);
    rows.push_back({p.key, p.swept_text(", "), format_seconds(t), frame_change, speedup, others});
    bold.push_back(p.index == *in.baseline);
  }
  page.paragraph("Each point that ran against point " + points[*in.baseline].key +
                 " (bold): its frame time, the change, the speed-up (the baseline's frame time "
                 "over the point's) and its " +
                 std::to_string(kChangesShown) +
                 " largest other relative changes (`rtsim diff points/" + points[*in.baseline].key +
                 " points/NNNN` lists them all).");
  page.raw("<div style=\"overflow-x:auto\">\n");
  page.table({"point", "swept", "frame time", "change", "speed-up", "largest other changes"}, rows,
             bold);
  page.raw("</div>\n");
}

/// What a plot's picture says it is, and how to draw it again.
std::string reproduce(const SweepPlotSpec& s) {
  std::string cmd = "/usr/bin/python3 analysis/sweep_plot.py results.jsonl plot.png";
  for (const auto& a : s.script_args()) {
    cmd += ' ';
    cmd += runs::shell_quote(a);
  }
  return cmd;
}

}  // namespace

std::vector<std::string> SweepPlotSpec::script_args() const {
  std::vector<std::string> a = {"--x", x};
  for (const auto& c : y) a.insert(a.end(), {"--y", c});
  a.insert(a.end(), {"--group", group.empty() ? "none" : group});
  if (!ratio_to.empty()) a.insert(a.end(), {"--ratio-to", ratio_to});
  if (logx) a.push_back("--logx");
  if (logy) a.push_back("--logy");
  if (!title.empty()) a.insert(a.end(), {"--title", title});
  if (!ylabel.empty()) a.insert(a.end(), {"--ylabel", ylabel});
  for (const auto& [column, low, high] : bands)
    a.insert(a.end(), {"--band", column + "=" + low + "," + high});
  return a;
}

std::vector<SweepPlotSpec> choose_sweep_plots(const sweep::SweepFile& file,
                                              const sweep::ResultsTable& table) {
  const TableView view(table);
  std::vector<SweepPlotSpec> plots;
  if (view.ok_rows.empty()) return plots;

  struct AxisInfo {
    std::string column;
    std::size_t size = 0;
    bool run_option = false;
    bool numeric = true;
    std::vector<double> values;
    std::string smallest;  // the text of the smallest value
  };
  std::vector<AxisInfo> axes;
  for (const auto& axis : file.axes) {
    const sweep::AxisMember& m = axis.members.front();
    if (axis.size() < 2 || !view.has(m.name)) continue;
    AxisInfo a;
    a.column = m.name;
    a.size = axis.size();
    a.run_option = m.name == sweep::kMachine || m.name == sweep::kScene;
    double lo = INFINITY;
    for (const auto& v : m.values) {
      const double d = as_number(v.json);
      if (a.run_option || !std::isfinite(d)) {
        a.numeric = false;
        continue;
      }
      a.values.push_back(d);
      if (d < lo) lo = d, a.smallest = v.text;
    }
    axes.push_back(std::move(a));
  }
  // x: every axis of numbers; names (machines, scenes, broadcast.mode = "adaptive", ...) make
  // lines. Only when no axis has numbers, the first axis of names is x.
  std::vector<std::size_t> xs;
  for (std::size_t i = 0; i < axes.size(); ++i)
    if (axes[i].numeric) xs.push_back(i);
  if (xs.empty() && !axes.empty()) xs.push_back(0);

  const auto add = [&](SweepPlotSpec s) {
    if (plots.size() < kSweepPlots) plots.push_back(std::move(s));
  };
  for (const std::size_t i : xs) {
    const AxisInfo& xa = axes[i];
    // Lines: every other axis together when their combinations are few, else the first other
    // axis short enough (machine and scene lists come first) with the rest averaged.
    std::vector<std::size_t> group;
    std::size_t combinations = 1;
    for (std::size_t j = 0; j < axes.size(); ++j)
      if (j != i) group.push_back(j), combinations *= axes[j].size;
    if (combinations > kMaxLines) {
      group.clear();
      for (std::size_t j = 0; j < axes.size() && group.empty(); ++j)
        if (j != i && axes[j].size <= kMaxLines) group.push_back(j);
    }
    std::string averaged, group_columns;
    std::size_t lines = 1;
    for (std::size_t j = 0; j < axes.size(); ++j) {
      if (j == i) continue;
      if (std::find(group.begin(), group.end(), j) != group.end()) {
        group_columns += (group_columns.empty() ? "" : ",") + axes[j].column;
        lines *= axes[j].size;
      } else {
        averaged += (averaged.empty() ? "" : ", ") + axes[j].column;
      }
    }
    const std::string over =
        averaged.empty() ? "" : " Points that differ only in " + averaged + " are averaged.";

    SweepPlotSpec base;
    base.x = xa.column;
    base.group = group_columns;
    base.logx = xa.numeric && log_spaced(xa.values);
    std::string per = base.group;  // "scene,broadcast.mode" -> "scene and broadcast.mode"
    for (auto c = per.find(','); c != std::string::npos; c = per.find(',', c))
      per.replace(c, 1, " and ");
    const std::string lines_text = per.empty() ? "" : ", one line per " + per;

    const auto stat_plot = [&](std::vector<std::string> ys, const std::string& what,
                               const std::string& ylabel) {
      SweepPlotSpec s = base;
      std::vector<double> all;
      for (const auto& y : ys) {
        const auto v = view.numbers(y);
        all.insert(all.end(), v.begin(), v.end());
      }
      s.y = std::move(ys);
      s.logy = spans_decades(all);
      s.title = what + " against " + xa.column;
      s.ylabel = ylabel;
      s.caption = what + lines_text + "." + over;
      return s;
    };

    if (!view.numbers("simulated_time_s").empty()) {
      add(stat_plot({"simulated_time_s"}, "Simulated frame time", "simulated frame time (s)"));
      std::string lower = xa.column;
      std::transform(lower.begin(), lower.end(), lower.begin(),
                     [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
      if (xa.numeric && lower.find("count") != std::string::npos && !xa.smallest.empty()) {
        SweepPlotSpec s = base;
        s.y = {"simulated_time_s"};
        s.ratio_to = xa.column + "=" + xa.smallest;
        s.logy = s.logx;
        s.title = "Speed-up over " + xa.column + " = " + xa.smallest;
        s.ylabel = "speed-up (frame time at " + xa.column + " = " + xa.smallest + " / frame time)";
        s.caption = "The simulated frame time at " + xa.column + " = " + xa.smallest +
                    " divided by each point's" + lines_text + " (each line over its own " +
                    xa.column + " = " + xa.smallest + " point)." + over;
        add(std::move(s));
      }
    }
    for (const auto& c : table.columns)
      if (ends_with(c, "time_per_ray_s") && !view.numbers(c).empty())
        add(stat_plot({c}, c, c + " (s)"));

    // The busiest modules, fewer when there are several lines already. A module of its own
    // kind by its utilisation; a class of instances (node*, pert*.shell) by its mean, its
    // min..max shaded: an instance's name (node16) means another node at another array size.
    struct Busiest {
      double hi;
      std::string y;
      std::array<std::string, 3> band;  ///< empty: a module of its own kind
    };
    std::vector<Busiest> busy;
    const std::set<std::string> columns(table.columns.begin(), table.columns.end());
    const std::string util = ".utilization";
    for (const auto& c : table.columns) {
      Busiest b;
      if (starts_with(c, "modules.") && ends_with(c, util)) {
        const std::string name = c.substr(8, c.size() - 8 - util.size());
        const std::string cls = "module_classes." + modules::instance_class(name) + util;
        if (columns.contains(cls + ".mean")) continue;  // drawn as its class
        b.y = c;
      } else if (starts_with(c, "module_classes.") && ends_with(c, util + ".mean")) {
        const std::string base = c.substr(0, c.size() - 5);
        b.y = c;
        if (columns.contains(base + ".min") && columns.contains(base + ".max"))
          b.band = {c, base + ".min", base + ".max"};
      } else {
        continue;
      }
      const auto v = view.numbers(b.band[0].empty() ? c : b.band[2]);
      if (v.empty()) continue;
      b.hi = *std::max_element(v.begin(), v.end());
      if (b.hi > 0.01) busy.push_back(std::move(b));
    }
    std::stable_sort(busy.begin(), busy.end(),
                     [](const Busiest& a, const Busiest& b) { return a.hi > b.hi; });
    const std::size_t keep = lines >= 8 ? 1 : std::max<std::size_t>(2, 8 / lines);
    if (busy.size() > keep) busy.resize(keep);
    if (!busy.empty()) {
      std::vector<std::string> ys;
      for (const auto& b : busy) ys.push_back(b.y);
      SweepPlotSpec s = stat_plot(std::move(ys), "Module utilisation",
                                  "utilisation (busy fraction of the frame)");
      bool classes = false;
      for (const auto& b : busy)
        if (!b.band[0].empty()) {
          s.bands.push_back(b.band);
          classes = true;
        }
      s.logy = false;
      s.caption = "Busy fraction of the frame of the " + std::to_string(busy.size()) +
                  " busiest modules (modules.NAME.utilization" +
                  (classes ? "; a class of instances, such as node*, by its mean over them, the "
                             "range from the least to the busiest shaded: "
                             "module_classes.CLASS.utilization"
                           : "") +
                  ")" + lines_text + "." + over;
      add(std::move(s));
    }

    std::vector<std::string> latency;
    for (const char* c : {"ray_latency_s.mean", "ray_latency_s.p99"}) {
      const auto v = view.numbers(c);
      if (!v.empty() && *std::max_element(v.begin(), v.end()) > 0 &&
          (latency.empty() || lines <= 4))
        latency.push_back(c);
    }
    if (!latency.empty()) add(stat_plot(latency, "Ray latency", "ray latency (s)"));
    if (!view.numbers("point_wall_time_s").empty()) {
      SweepPlotSpec s = stat_plot({"point_wall_time_s"}, "Wall time per point",
                                  "wall time of the point's rtsim run (s)");
      s.caption += " What the simulation cost, not a simulated figure.";
      add(std::move(s));
    }
  }
  return plots;
}

namespace {

/// The page; `progress` is told of each plot made (a second pass, with the plots started).
HtmlReport sweep_report_page(const SweepReportInputs& in, const ReportTools& tools_in,
                             const std::function<void(std::size_t, std::size_t)>& progress) {
  const ReportTools tools = tools_in.resolved();
  const sweep::SweepFile& file = *in.file;
  const std::vector<sweep::Point>& points = *in.points;
  const std::vector<sweep::PointOutcome>& outcomes = *in.outcomes;
  const TableView view(*in.table);
  const std::string origin_name = fs::path(file.origin).filename().string();

  HtmlReport page("rtsim sweep: " +
                  (file.name.empty() ? fs::path(file.origin).stem().string() : file.name));
  if (!in.command_line.empty()) page.paragraph(in.command_line);

  // ---- Headline: what was swept and how it went ----
  std::vector<std::string> machines, scenes;
  for (const auto& p : points) {
    if (std::find(machines.begin(), machines.end(), p.machine()) == machines.end())
      machines.push_back(p.machine());
    if (std::find(scenes.begin(), scenes.end(), p.scene()) == scenes.end())
      scenes.push_back(p.scene());
  }
  const auto join = [](const std::vector<std::string>& v) {
    std::string s;
    for (const auto& x : v) s += (s.empty() ? "" : ", ") + x;
    return s;
  };
  std::size_t failed = 0;
  for (const auto& o : outcomes) failed += o.ok ? 0 : 1;
  std::vector<std::pair<std::string, std::string>> head;
  head.emplace_back("sweep file", file.origin);
  head.emplace_back("machines", join(machines));
  head.emplace_back("scenes", join(scenes));
  std::string size;
  for (const auto& f : file.fixed)
    if (f.name == sweep::kWidth || f.name == sweep::kHeight)
      size += (size.empty() ? "" : ", ") + f.name + " " + f.value.text;
  head.emplace_back("image", size.empty() ? "the scene's size" : size);
  for (const auto& axis : file.axes) {
    std::string names;
    for (const auto& m : axis.members) names += (names.empty() ? "" : " + ") + m.name;
    std::string values;
    for (const auto& m : axis.members)
      values += (values.empty() ? "" : "; ") + (axis.members.size() > 1 ? m.name + ": " : "") +
                value_list(m.values);
    head.emplace_back("axis " + names, values + " (" + std::to_string(axis.size()) +
                                           " values, line " + std::to_string(axis.line) + ")");
  }
  for (const auto& [config, line] : file.configs) head.emplace_back("config", config.string());
  head.emplace_back(
      "points", std::to_string(points.size()) + ": " + std::to_string(points.size() - failed) +
                    " ok, " + std::to_string(failed) + " failed; " + std::to_string(in.run_now) +
                    " run now, " + std::to_string(points.size() - in.run_now) + " done before");
  head.emplace_back("this run", format_seconds(in.wall_s) + " wall" +
                                    (in.ranks > 0 ? ", " + std::to_string(in.ranks) + " MPI ranks"
                                                  : std::string()));
  head.emplace_back("outputs", "results.csv, results.jsonl, points/NNNN/ (beside this page)");
  page.heading("Sweep");
  page.key_values(head);

  if (failed > 0) {
    page.heading("Failed points");
    page.paragraph(std::to_string(failed) + " of " + std::to_string(points.size()) +
                   " points failed; their rows in the table below are bold. The report and "
                   "the plots are made from the others.");
    std::vector<std::vector<std::string>> rows;
    for (const auto& p : points) {
      const auto& o = outcomes[p.index];
      if (o.ok) continue;
      if (rows.size() == kMaxFailuresListed) {
        rows.push_back({"...", "", "the rest are in results.csv"});
        break;
      }
      rows.push_back({p.key, p.swept_text(" "), o.error});
    }
    page.table({"point", "swept values", "error"}, rows);
  }

  // ---- Plots ----
  page.heading("Plots");
  std::vector<std::string> problems;
  if (view.ok_rows.empty()) {
    page.note("No point succeeded: there is nothing to plot.");
  } else if (in.results_jsonl.empty() || !fs::exists(in.results_jsonl)) {
    page.note("No results.jsonl to plot from.");
  } else {
    const auto specs = choose_sweep_plots(file, *in.table);
    if (specs.empty()) page.paragraph("The sweep has no axis with two values or more to plot.");
    std::error_code ec;
    fs::create_directories(tools.scratch_dir, ec);
    for (std::size_t k = 0; k < specs.size(); ++k) {
      const fs::path png = tools.scratch_dir / ("sweep-plot-" + std::to_string(k) + ".png");
      std::vector<std::string> args = {in.results_jsonl.string(), png.string()};
      const auto more = specs[k].script_args();
      args.insert(args.end(), more.begin(), more.end());
      const auto r = run_analysis_script(tools, "sweep_plot.py", args);
      if (progress) progress(k + 1, specs.size());
      if (r.ok)
        page.image(png, specs[k].title, specs[k].caption + " (" + reproduce(specs[k]) + ")");
      else
        problems.push_back(r.message);
    }
  }
  if (!problems.empty()) {
    std::string text = "Plots are missing: ";
    std::set<std::string> said;
    for (const auto& p : problems)
      if (said.insert(p).second) text += (said.size() > 1 ? " | " : "") + p;
    text +=
        ". They need Debian's python3 with python3-matplotlib, python3-numpy and "
        "python3-pandas (set RTSIM_PYTHON to use another interpreter).";
    page.note(text);
  }

  // ---- The results table: the leading columns and the headline stats ----
  {
    std::vector<std::string> cols = {"point"};
    for (const auto& axis : file.axes)
      for (const auto& m : axis.members)
        if (view.has(m.name) && std::find(cols.begin(), cols.end(), m.name) == cols.end())
          cols.push_back(m.name);
    cols.push_back("status");
    for (const char* c : {"simulated_time_s", "rays.total", "intersection_tests",
                          "ray_latency_s.mean", "ray_latency_s.p99"})
      if (!view.numbers(c).empty()) cols.emplace_back(c);
    for (const auto& c : in.table->columns)
      if (ends_with(c, "time_per_ray_s") && !view.numbers(c).empty()) cols.push_back(c);
    cols.push_back("point_wall_time_s");
    cols.push_back("error");
    std::vector<std::vector<std::string>> rows;
    std::vector<bool> bold;
    for (std::size_t r = 0; r < in.table->rows.size() && r < kSweepTableRows; ++r) {
      std::vector<std::string> row;
      for (const auto& c : cols)
        row.push_back(c == "point" && r < points.size()
                          ? points[r].key
                          : cell_text(view.at(r, c), c, in.table->units));
      rows.push_back(std::move(row));
      bold.push_back(view.at(r, "status") != "ok");
    }
    page.heading("Results");
    page.paragraph(
        "One row per point, in point order, with the headline numbers (times in readable "
        "units). results.csv and results.jsonl beside this page have every stats.json number "
        "of every point (docs/sweeps.md lists the columns)." +
        std::string(in.table->rows.size() > kSweepTableRows
                        ? " Only the first " + std::to_string(kSweepTableRows) + " of " +
                              std::to_string(in.table->rows.size()) + " rows are shown here."
                        : ""));
    page.raw("<div style=\"overflow-x:auto\">\n");
    page.table(cols, rows, bold);
    page.raw("</div>\n");
  }

  // ---- Against the baseline ----
  if (in.baseline) baseline_section(page, in);

  // ---- Thumbnails ----
  {
    std::string grid;
    std::size_t shown = 0, without = 0, brightened = 0, shared = 0;
    int images = 0;
    // A point that shares another's image (platform/sweep/image_sharing.hpp) is not shown
    // again: its image point stands for it.
    std::map<std::size_t, std::size_t> sharers;  // image point -> points sharing its image
    for (const auto& p : points)
      if (p.image_from) ++sharers[*p.image_from];
    for (const auto& p : points) {
      if (p.image_from) {
        ++shared;
        continue;
      }
      const fs::path png = in.points_dir / p.key / "image.png";
      std::error_code ec;
      if (in.points_dir.empty() || !fs::exists(png, ec)) {
        ++without;
        continue;
      }
      if (shown == kSweepThumbnails) continue;
      std::string data;
      try {
        data = read_whole_file(png);
      } catch (const std::exception&) {
        ++without;
        continue;
      }
      std::string swept = p.swept_text(", ");
      if (const auto it = sharers.find(p.index); it != sharers.end())
        swept += "; the image of " + std::to_string(it->second + 1) + " points";
      const auto& outcome = (*in.outcomes)[p.index];
      const double gain = outcome.ok ? thumbnail_gain(outcome.stats_text) : 1.0;
      std::string filter, note;
      if (gain > 1.0) {
        filter = ";filter:brightness(" + format_number(gain, 3) + ")";
        note = " (dark: shown " + format_number(gain, 2) + "x brighter)";
        ++brightened;
      }
      grid += "<figure style=\"margin:0;width:" + std::to_string(kThumbPixels + 8) +
              "px\"><img alt=\"point " + html_escape(p.key) +
              "\" style=\"width:" + std::to_string(kThumbPixels) + "px;image-rendering:pixelated" +
              filter + "\" src=\"data:image/png;base64," + base64(data) +
              "\"><figcaption style=\"overflow-wrap:anywhere\">" +
              html_escape(p.key + (swept.empty() ? "" : ": " + swept) + note) +
              "</figcaption></figure>\n";
      ++shown;
      ++images;
    }
    page.heading("Images");
    const std::size_t with = points.size() - without - shared;
    if (shown == 0) {
      page.paragraph(
          "No point's image.png is here (failed points, or images written on other "
          "nodes without a shared file system).");
    } else {
      const std::string whose = shared > 0 ? " distinct images" : " points' images";
      page.paragraph(
          (with > shown
               ? "The first " + std::to_string(shown) + " of the " + std::to_string(with) + whose
           : shared > 0 ? "The " + std::to_string(shown) + whose
                        : "Every point's image (" + std::to_string(shown) + ")") +
          ", in point order (points/NNNN/image.png)." +
          (shared > 0 ? " " + std::to_string(shared) +
                            " point(s) differ from an earlier one only in parameters "
                            "the image does not depend on: they share its image, "
                            "shown once."
                      : std::string()) +
          (without > 0 ? " " + std::to_string(without) +
                             " point(s) have no image.png here (failed, or written on another "
                             "node without a shared file system)."
                       : std::string()) +
          (brightened > 0 ? " Dark images (a mean below 15% grey: no light reaches "
                            "the camera, or shade.max_depth = 0 leaves the ambient "
                            "term alone) are shown brighter, as their captions say; "
                            "image.png itself is as rendered."
                          : std::string()));
      page.raw("<div style=\"display:flex;flex-wrap:wrap;gap:10px\">\n" + grid + "</div>\n",
               images);
    }
  }

  // ---- Parameters with their sources, per machine ----
  std::map<std::string, std::pair<std::string, std::string>> swept;  // name -> values, where
  for (const auto& axis : file.axes)
    for (const auto& m : axis.members)
      if (!sweep::is_run_option(m.name))
        swept[m.name] = {"swept: " + value_list(m.values),
                         "axis, " + origin_name + ":" + std::to_string(m.line)};
  for (const auto& machine_name : machines) {
    page.heading("Parameters: " + machine_name);
    try {
      const platform::Machine& machine = platform::find_machine(machine_name);
      ConfigArgs cfg;
      for (const auto& [config, line] : file.configs) cfg.config_files.push_back(config.string());
      params::ParamRegistry registry = build_registry(cfg, &machine);
      std::map<std::string, std::string> fixed_where;
      for (const auto& f : file.fixed) {
        if (sweep::is_run_option(f.name)) continue;
        registry.apply_override(f.name + "=" + f.value.text);
        fixed_where[f.name] = origin_name + ":" + std::to_string(f.value.line);
      }
      std::vector<std::vector<std::string>> rows;
      std::vector<bool> set;
      for (const auto& e : registry.list()) {
        std::string value = e.value_text, where = e.where_set;
        if (const auto s = swept.find(e.name); s != swept.end()) {
          value = s->second.first;
          where = s->second.second;
        } else if (const auto f = fixed_where.find(e.name); f != fixed_where.end()) {
          where = f->second;
        }
        set.push_back(where != "default");
        rows.push_back({e.name, value, e.default_text, where, cite_seeds(e.source)});
      }
      page.paragraph(
          "Every parameter of " + machine_name +
          " in this sweep. \"set by\" is where the value came from: default, a config file "
          "(FILE:LINE), the sweep file's [params] (" +
          origin_name +
          ":LINE) or an axis; rows not at their default are bold. \"source\" is "
          "where the default comes from (a seed line or an assumption).");
      page.table({"parameter", "value", "default", "set by", "source"}, rows, set);
    } catch (const std::exception& e) {
      page.note(std::string("The parameters cannot be listed: ") + e.what());
    }
  }

  // ---- The sweep file itself ----
  page.heading("The sweep file: " + file.origin);
  try {
    std::string text = read_whole_file(file.origin);
    if (text.size() > kMaxSweepText) text = text.substr(0, kMaxSweepText) + "\n...\n";
    page.raw(
        "<pre style=\"background:#f8f8f8;border:1px solid #ddd;padding:.6em;"
        "overflow-x:auto;font-size:.85em\">" +
        html_escape(text) + "</pre>\n");
  } catch (const std::exception& e) {
    page.note(e.what());
  }

  page.paragraph(
      "Written by rtsim sweep --report. Every number here is also in results.csv and "
      "each point's stats.json (docs/sweeps.md, docs/stats.md).");
  return page;
}

}  // namespace

void write_sweep_report(const SweepReportInputs& in, const fs::path& out_html,
                        const ReportTools& tools) {
  // Every plot is started at once (a Python each, sharing the cores), then the page is made
  // again waiting for each: a sweep's plots take about a second each one after another.
  ScriptBatch scripts;
  (void)sweep_report_page(in, tools, {});
  scripts.collect();
  sweep_report_page(in, tools, in.progress).write(out_html);
}

}  // namespace rtsim::app
