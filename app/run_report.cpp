#include "app/run_report.hpp"

#include <cmath>
#include <cstdio>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <stdexcept>

#include "app/bottleneck.hpp"
#include "app/number_text.hpp"
#include "app/run_summary.hpp"
#include "app/trace_options.hpp"
#include "common/seed_citation.hpp"
#include "modules/stat_classes.hpp"
#include "platform/machine_registry.hpp"

namespace rtsim::app {

namespace fs = std::filesystem;
// Ordered: a machine's figures keep the order stats.json has them in (shade, shell, prim).
using json = nlohmann::ordered_json;

namespace {

std::string value_text(const json& v) {
  if (v.is_string()) return v.get<std::string>();
  if (v.is_number_integer()) return std::to_string(v.get<long long>());
  if (v.is_number()) return format_number(v.get<double>(), 6);
  if (v.is_boolean()) return v.get<bool>() ? "true" : "false";
  if (v.is_null()) return "-";
  std::string s = v.dump();
  if (s.size() > 160) s = s.substr(0, 157) + "...";
  return s;
}

/// An array of numbers as a person reads it: the first values in their unit, and for a longer
/// or a nested one (rows of a grid) its size and range; other arrays as JSON, cut short.
std::string array_text(const modules::UnitSchema& units, const std::string& name, const json& v) {
  constexpr std::size_t kShown = 8;
  if (v.empty()) return "none";
  std::vector<double> flat;
  std::size_t rows = 0, cols = 0;
  bool numeric = true;
  for (const auto& e : v) {
    if (e.is_number()) {
      flat.push_back(e.get<double>());
    } else if (e.is_array()) {
      ++rows;
      cols = std::max(cols, e.size());
      for (const auto& x : e) {
        if (!x.is_number()) numeric = false;
        if (x.is_number()) flat.push_back(x.get<double>());
      }
    } else {
      numeric = false;
    }
  }
  if (!numeric || flat.empty()) return value_text(v);
  double lo = flat.front(), hi = flat.front(), sum = 0.0;
  for (double x : flat) {
    lo = std::min(lo, x);
    hi = std::max(hi, x);
    sum += x;
  }
  const std::string range = "min " + format_figure(units, name, lo) + ", mean " +
                            format_figure(units, name, sum / static_cast<double>(flat.size())) +
                            ", max " + format_figure(units, name, hi);
  if (rows > 0)
    return std::to_string(rows) + " x " + std::to_string(cols) + ": " + range +
           " (stats.json has every value)";
  std::string text;
  for (std::size_t i = 0; i < flat.size() && i < kShown; ++i)
    text += (i ? ", " : "") + format_figure(units, name, flat[i]);
  if (flat.size() > kShown)
    text += ", ... (" + std::to_string(flat.size()) + " values: " + range + ")";
  return text;
}

/// A figure of a machine's section as the page shows it (format_figure, array_text); a summary
/// of times (a latency recorder's count, mean, p50, p99, max) as its mean and p99; another
/// object as its scalar figures.
/// `path` is the figure's stats path ("pxpl5.frame_times_s"), whose unit `units` declares.
std::string figure_text(const modules::UnitSchema& units, const std::string& path, const json& v) {
  if (v.is_array()) return array_text(units, path, v);
  if (v.is_object()) {
    if (v.contains("count") && v.contains("mean") && v.contains("p99"))
      return "mean " + figure_text(units, path + ".mean", v["mean"]) + ", p99 " +
             figure_text(units, path + ".p99", v["p99"]) + " (" + value_text(v["count"]) + ")";
    std::string text;
    for (const auto& [k, x] : v.items())
      if (!x.is_structured())
        text += (text.empty() ? "" : ", ") + k + " " + figure_text(units, path + "." + k, x);
    return text.empty() ? "-" : text;
  }
  if (!v.is_number()) return value_text(v);
  return format_figure(units, path, v.get<double>());
}

/// The scalar figures of `o`, nested objects' by dotted path ("eal.n"), in document order.
void each_figure(const json& o, const std::string& prefix,
                 const std::function<void(const std::string&, const json&)>& f) {
  for (const auto& [k, x] : o.items()) {
    const std::string path = prefix.empty() ? k : prefix + "." + k;
    if (x.is_object())
      each_figure(x, path, f);
    else
      f(path, x);
  }
}

/// The objects `names` of `parent` (at stats path `prefix`) in one table, a row per figure and a
/// column per object, so that figures of the same kind (three processors' latency per ray) read
/// side by side.
void side_by_side(HtmlReport& page, const modules::UnitSchema& units, const std::string& prefix,
                  const json& parent, const std::vector<std::string>& names) {
  std::vector<std::string> figures;
  std::map<std::string, std::map<std::string, std::string>> cells;  // figure -> object -> text
  for (const auto& name : names)
    each_figure(parent[name], "", [&](const std::string& path, const json& x) {
      auto& row = cells[path];
      if (row.empty()) figures.push_back(path);
      row[name] = figure_text(units, prefix + "." + name + "." + path, x);
    });
  // Figures every object has first (the processors' common time split), then the others.
  std::stable_partition(figures.begin(), figures.end(),
                        [&](const std::string& f) { return cells[f].size() == names.size(); });
  std::vector<std::string> head = {""};
  head.insert(head.end(), names.begin(), names.end());
  std::vector<std::vector<std::string>> rows;
  for (const auto& f : figures) {
    std::vector<std::string> row = {f};
    for (const auto& name : names) {
      const auto it = cells[f].find(name);
      row.push_back(it == cells[f].end() ? "" : it->second);
    }
    rows.push_back(std::move(row));
  }
  page.table(head, rows);
}

/// The seed documents the parameters' sources cite, linked to their text (a line number is a
/// line of that file): beside the checkout, ../shared/reference/seeds/NNN_*.txt.
void seed_links(HtmlReport& page, const std::vector<params::ParamEntry>& params) {
  std::set<std::string> cited;
  for (const auto& p : params)
    for (auto& number : cited_seeds(p.source)) cited.insert(std::move(number));
  std::error_code ec;
  const fs::path seeds = fs::weakly_canonical(
      fs::path(RTSIM_SOURCE_DIR) / ".." / "shared" / "reference" / "seeds", ec);
  std::string links;
  for (const auto& number : cited) {
    std::string file;
    if (!ec && fs::is_directory(seeds, ec))
      for (const auto& e : fs::directory_iterator(seeds, ec))
        if (e.path().filename().string().rfind(number + "_", 0) == 0) file = e.path().string();
    links += links.empty() ? "" : ", ";
    const std::string who = html_escape(std::string(seed_author(number)));
    links += file.empty() ? who
                          : "<a href=\"file://" + html_escape(file) + "\">" + who + "</a> (" +
                                html_escape(fs::path(file).filename().string()) + ")";
  }
  if (!links.empty())
    page.raw("<p>Sources cite the seed documents by author, year and line: " + links + ".</p>\n");
}

/// A machine's own stats.json object (gaudet-pert's `gaudet`): its plain figures as a list;
/// its objects of figures (the shade, shell and prim processors) side by side in one table;
/// and each object of such objects (the buses) as a table of its own.
void machine_section(HtmlReport& page, const modules::UnitSchema& units, const std::string& key,
                     const json& v) {
  std::vector<std::pair<std::string, std::string>> plain;
  std::vector<std::string> members, groups, records;
  for (const auto& [k, x] : v.items()) {
    if (x.is_array() && !x.empty() &&
        std::all_of(x.begin(), x.end(), [](const json& e) { return e.is_object(); })) {
      records.push_back(k);  // a list of records (each frame's figures): a table below
    } else if (!x.is_object()) {
      plain.emplace_back(k, figure_text(units, key + "." + k, x));
    } else if (!x.empty() &&
               std::all_of(x.begin(), x.end(), [](const json& m) { return m.is_object(); })) {
      groups.push_back(k);
    } else {
      members.push_back(k);
    }
  }
  if (!plain.empty()) page.key_values(plain);
  if (!members.empty()) side_by_side(page, units, key, v, members);
  for (const auto& g : groups) {
    page.paragraph(key + "." + g + ":");
    std::vector<std::string> names;
    for (const auto& [k, x] : v[g].items()) names.push_back(k);
    side_by_side(page, units, key + "." + g, v[g], names);
  }
  // A list of records: a row each (the first kRecordRows), a column per figure.
  constexpr std::size_t kRecordRows = 24;
  for (const auto& r : records) {
    const json& list = v[r];
    std::vector<std::string> head;
    for (const auto& e : list)
      for (const auto& [k, x] : e.items())
        if (std::find(head.begin(), head.end(), k) == head.end()) head.push_back(k);
    std::vector<std::vector<std::string>> rows;
    for (std::size_t i = 0; i < list.size() && i < kRecordRows; ++i) {
      std::vector<std::string> row;
      for (const auto& k : head)
        row.push_back(list[i].contains(k) ? figure_text(units, key + "." + r + "." + k, list[i][k])
                                          : "");
      rows.push_back(std::move(row));
    }
    page.paragraph(key + "." + r +
                   (list.size() > kRecordRows
                        ? " (the first " + std::to_string(kRecordRows) + " of " +
                              std::to_string(list.size()) + "; stats.json has all):"
                        : ":"));
    page.table(head, rows);
  }
}

/// stats.json `simulation` with its `activations` folded by class: the processes of a class of
/// many instances (an array's 1024 "node12.activate") are one row, their sum, named
/// "node*.activate (1024 processes)"; stats.json keeps every process.
json folded_activations(const json& simulation) {
  json out = simulation;
  const auto it = simulation.find("activations");
  if (it == simulation.end() || !it->is_object()) return out;
  std::map<std::string, std::pair<double, std::size_t>> by_class;  // sum, processes
  std::vector<std::string> order;
  for (const auto& [process, n] : it->items()) {
    if (!n.is_number()) continue;
    const std::string cls = modules::instance_class(process);
    auto [c, added] = by_class.try_emplace(cls, 0.0, 0);
    if (added) order.push_back(cls);
    c->second.first += n.get<double>();
    ++c->second.second;
  }
  json folded = json::object();
  for (const auto& cls : order) {
    const auto& [sum, processes] = by_class.at(cls);
    folded[processes > 1 ? cls + " (" + std::to_string(processes) + " processes)" : cls] = sum;
  }
  out["activations"] = std::move(folded);
  return out;
}

const json* find(const json& j, const std::string& key) {
  const auto it = j.find(key);
  return it == j.end() ? nullptr : &*it;
}

double num(const json& j, const std::string& key, double fallback = NAN) {
  const json* v = find(j, key);
  return v && v->is_number() ? v->get<double>() : fallback;
}

std::string str(const json& j, const std::string& key) {
  const json* v = find(j, key);
  return v && v->is_string() ? v->get<std::string>() : std::string("?");
}

/// The note that says which plots could not be drawn and why.
std::string missing_plots_note(const std::vector<std::string>& problems) {
  std::string text = "Plots are missing: ";
  std::set<std::string> said;
  for (const auto& p : problems)
    if (said.insert(p).second) text += (said.size() > 1 ? " | " : "") + p;
  return text +
         ". They need Debian's python3 with python3-matplotlib, python3-numpy and "
         "python3-pandas (set RTSIM_PYTHON to use another interpreter).";
}

bool has_windows(const json& stats) {
  const json* mods = find(stats, "modules");
  if (!mods || !mods->is_object()) return false;
  for (const auto& [name, m] : mods->items())
    if (m.is_object() && m.contains("utilization_windows")) return true;
  return false;
}

/// Keys the report shows in their own sections; every other top-level object of stats.json
/// (a machine's own figures: "peripheral", "vax", ...) gets a table.
const std::set<std::string> kShownKeys = {"tool",
                                          "version",
                                          "schema_version",
                                          "command",
                                          "machine",
                                          "scene",
                                          "width",
                                          "height",
                                          "spp",
                                          "simulated_time_s",
                                          "wall_time_s",
                                          "threads",
                                          "rays",
                                          "rays_per_second",
                                          "params",
                                          "modules",
                                          "ray_latency_s",
                                          "latency_probe",
                                          "module_classes",
                                          "image",
                                          "firmware_cost",
                                          "scene_stats",
                                          "geometry",
                                          "accel",
                                          "hits",
                                          "intersection_tests",
                                          "patch_subdivisions",
                                          "functional_wall_time_s",
                                          "overhead_ratio",
                                          "functional_image_identical",
                                          "units"};

/// What the traces hold (stats.json `trace`), and any event they lost, where it cannot be missed.
void write_trace_section(HtmlReport& page, const json& stats) {
  const json* t = find(stats, "trace");
  if (!t || !t->is_object()) return;
  page.heading("Traces");
  // Reserved: without it GCC 12 -O3 warns (-Warray-bounds, a false positive) on the first
  // emplace_back into an empty vector, depending on where the source tree lies.
  std::vector<std::pair<std::string, std::string>> rows;
  rows.reserve(8);
  const json& w = (*t)["window_s"];
  std::string traced =
      format_seconds(w[0].get<double>()) + " to " + format_seconds(w[1].get<double>());
  if (const json* r = find(*t, "requested_window_s"))
    traced +=
        " (whole; " + format_seconds((*r)[1].get<double>()) + " asked for: a cap dropped the rest)";
  rows.emplace_back("simulated time traced", traced);
  std::string mods;
  for (const auto& m : (*t)["modules"]) mods += (mods.empty() ? "" : ", ") + m.get<std::string>();
  rows.emplace_back(std::string("modules"), mods.empty() ? std::string("all") : mods);
  rows.emplace_back("signals (busy levels, queue depths)", value_text((*t)["signals"]));
  if (const json* p = find(*t, "perfetto"))
    rows.emplace_back(str(*p, "file"), value_text((*p)["events_written"]) + " events written, " +
                                           value_text((*p)["events_dropped"]) + " dropped");
  if (const json* v = find(*t, "vcd"))
    rows.emplace_back(str(*v, "file"), value_text((*v)["changes_written"]) +
                                           " value changes written, " +
                                           value_text((*v)["changes_dropped"]) + " dropped");
  const auto cap = (*t).value("max_events", std::size_t{0});
  rows.emplace_back("event cap (--trace-max-events)",
                    cap == 0 ? std::string("none") : std::to_string(cap) + " per file");
  page.key_values(rows);
  for (const std::string& warning : trace_warnings(stats)) page.note(warning);
}

}  // namespace

namespace {

/// The headline numbers: machine, scene, image, frame and wall time, rays, latency.
void headline_section(HtmlReport& page, const json& stats) {
  const std::string machine = str(stats, "machine");
  const std::string scene = str(stats, "scene");
  // Headline numbers.
  std::vector<std::pair<std::string, std::string>> head;
  head.emplace_back("machine", machine);
  head.emplace_back("scene", scene);
  head.emplace_back("image", format_number(num(stats, "width")) + " x " +
                                 format_number(num(stats, "height")) + ", " +
                                 format_number(num(stats, "spp")) + " sample(s) per pixel");
  if (const double t = num(stats, "simulated_time_s"); std::isfinite(t))
    head.emplace_back("simulated frame time", format_seconds(t) + estimate_suffix(stats));
  if (const std::string scope = sampled_scope(stats); !scope.empty())
    head.emplace_back("sampled", scope);
  if (const json* fs = find(stats, "frame_sequence");
      fs && fs->is_object() && num(*fs, "frames") > 1)
    head.emplace_back("frames", format_number(num(*fs, "frames")) + " at " +
                                    format_significant(num(*fs, "frames_per_second"), 3) +
                                    " frames/s (a frame every " +
                                    format_seconds(1.0 / num(*fs, "frames_per_second")) +
                                    "); latency from a frame's start to its display: mean " +
                                    format_seconds(num(*fs, "latency_mean_s")) + ", max " +
                                    format_seconds(num(*fs, "latency_max_s")));
  if (const double t = num(stats, "wall_time_s"); std::isfinite(t))
    head.emplace_back("wall time", format_seconds(t));
  if (const json* rays = find(stats, "rays"); rays && rays->is_object()) {
    std::string by_kind;
    for (const char* k : {"primary", "shadow", "reflected", "refracted"})
      by_kind += std::string(by_kind.empty() ? "" : ", ") + k + " " + value_text((*rays)[k]);
    head.emplace_back("rays", value_text((*rays)["total"]) + " (" + by_kind + ")");
  }
  if (const double v = num(stats, "intersection_tests"); std::isfinite(v))
    head.emplace_back("intersection tests", format_number(v));
  if (const double v = num(stats, "overhead_ratio"); std::isfinite(v))
    head.emplace_back("overhead (wall / functional wall)", format_number(v));
  if (const std::string b = bottleneck_text(find_bottleneck(stats)); !b.empty())
    head.emplace_back("bottleneck", b);
  // A machine that times no ray's latency (pxpl5-raytrace follows samples) has no such row.
  if (const json* lat = find(stats, "ray_latency_s");
      lat && lat->is_object() && num(*lat, "count", 0) > 0)
    head.emplace_back("ray latency", "mean " + format_seconds(num(*lat, "mean")) + ", p50 " +
                                         format_seconds(num(*lat, "p50")) + ", p99 " +
                                         format_seconds(num(*lat, "p99")) + ", max " +
                                         format_seconds(num(*lat, "max")) + " (" +
                                         value_text((*lat)["count"]) + " rays)");
  page.heading("Headline");
  page.key_values(head);
}

/// Runs analysis/`script` on stats.json into scratch/`png`: the image on the page, or the
/// reason it could not be drawn in `problems`.
void plot_from_stats(HtmlReport& page, const RunReportInputs& in, const ReportTools& tools,
                     const std::string& script, const std::string& png_name,
                     const std::string& title, const std::string& caption,
                     std::vector<std::string>& problems) {
  const fs::path png = tools.scratch_dir / png_name;
  const auto r = run_analysis_script(tools, script, {in.stats_json.string(), png.string()});
  if (r.ok)
    page.image(png, title, caption);
  else
    problems.push_back(r.message);
}

/// Utilisation over time, the latency histogram and the machine's own plots; what could not be
/// drawn is said in a note.
void plots_section(HtmlReport& page, const json& stats, const RunReportInputs& in,
                   const ReportTools& tools) {
  page.heading("Utilisation and latency");
  std::vector<std::string> problems;
  fs::create_directories(tools.scratch_dir);
  // The trace's signals are stats.json's numbers over time; a trace narrowed to a window or to
  // some modules, or cut at a cap, cannot draw the whole frame, so stats.json's windows do.
  // A large trace is not loaded: Python would take tens of seconds and gigabytes to read what
  // stats.json's windows already hold (it only adds the queue depths).
  constexpr std::uintmax_t kMaxTraceBytes = 32u << 20;
  std::error_code size_error;
  const std::uintmax_t trace_bytes =
      in.trace_json.empty() ? 0 : fs::file_size(in.trace_json, size_error);
  const bool trace_too_large = !size_error && trace_bytes > kMaxTraceBytes;
  const bool trace = !in.trace_json.empty() && fs::exists(in.trace_json) &&
                     trace_is_complete(stats) && !(trace_too_large && has_windows(stats));
  if (trace || has_windows(stats)) {
    const fs::path png = tools.scratch_dir / "utilisation.png";
    const auto r = run_analysis_script(
        tools, "utilisation_timeline.py",
        {trace ? in.trace_json.string() : in.stats_json.string(), png.string()});
    if (r.ok)
      page.image(png, "utilisation over time",
                 trace ? "Busy fraction of each module and mean queue depths per window "
                         "(from trace.json's busy and depth counters, the sources of stats.json's "
                         "utilisation and occupancy; analysis/utilisation_timeline.py)"
                       : "Busy fraction of each module per window of the frame (stats.json "
                         "utilization_windows; analysis/utilisation_timeline.py)" +
                             std::string(trace_too_large
                                             ? ". The trace (" + std::to_string(trace_bytes >> 20) +
                                                   " MiB) is not loaded for the report; "
                                                   "`analysis/utilisation_timeline.py "
                                                   "trace.json OUT.png` draws its queue "
                                                   "depths too"
                                             : ""));
    else
      problems.push_back(r.message);
  }
  if (const json* lat = find(stats, "ray_latency_s"); lat && num(*lat, "count", 0) > 0)
    plot_from_stats(page, in, tools, "latency_histogram.py", "latency.png", "ray latency histogram",
                    "Per-ray latency from entering the ray queue to the host having the answer "
                    "(analysis/latency_histogram.py)",
                    problems);
  // The machine's own plots, as its registration lists them (none for a machine this build
  // does not know).
  const platform::Machine* machine = platform::machine_named(str(stats, "machine"));
  for (const platform::ReportPlot& plot :
       machine ? machine->info().report_plots : std::vector<platform::ReportPlot>{}) {
    const json* object = find(stats, plot.object);
    if (!object || !find(*object, plot.key)) continue;
    plot_from_stats(page, in, tools, plot.script, fs::path(plot.script).stem().string() + ".png",
                    plot.title, plot.caption, problems);
  }
  if (!problems.empty()) page.note(missing_plots_note(problems));
}

/// A machine's answers checked against a reference solver (its object's `accuracy`, e.g. with
/// `-p accuracy.check=true`): per job and per primary ray, what was missed, invented or found
/// on another surface, and how far off the rest are.
void accuracy_section(HtmlReport& page, const std::string& key, const json& accuracy) {
  page.heading("Accuracy against the reference solver");
  page.paragraph(
      "Every job's answer, and every primary ray's nearest hit, compared with the "
      "double-precision reference solver: missed (the reference hits, the machine does not), "
      "phantom (the reverse), another surface (both hit, farther apart than the machine's "
      "tolerance); the error is the distance between the machine's point and the reference's "
      "over the rest, in object sizes and in pixels. stats.json " +
      key + ".accuracy.");
  std::vector<std::vector<std::string>> rows;
  for (const char* kind : {"jobs", "rays"}) {
    const json* a = find(accuracy, kind);
    if (!a || !a->is_object()) continue;
    const json* pe = find(*a, "point_error");
    const json* px = find(*a, "pixel_error");
    rows.push_back({kind == std::string("jobs") ? "jobs" : "primary rays",
                    value_text((*a)["compared"]), value_text((*a)["missed"]),
                    value_text((*a)["phantom"]), value_text((*a)["another_surface"]),
                    format_number(100.0 * num(*a, "wrong_of_hits", 0.0), 3) + " %",
                    pe ? format_number(num(*pe, "p50", 0.0), 3) : "",
                    pe ? format_number(num(*pe, "p99", 0.0), 3) : "",
                    px ? format_number(num(*px, "p99", 0.0), 3) : ""});
  }
  page.table({"compared", "count", "missed", "phantom", "another surface", "wrong / reference hits",
              "error p50 (object sizes)", "p99", "p99 (pixels)"},
             rows);
}

/// `--latency-probe`: the per-stage breakdown of a ray's latency.
void latency_probe_section(HtmlReport& page, const json& stats, const RunReportInputs& in,
                           const ReportTools& tools) {
  if (const json* probe = find(stats, "latency_probe"); probe && probe->is_object()) {
    page.heading("Where a ray spends its time");
    const json* stages = find(*probe, "stages");
    const json* e2e = find(*probe, "end_to_end_s");
    const double mean = e2e && e2e->is_object() ? num(*e2e, "mean", 0.0) : 0.0;
    const double rest = num(*probe, "unattributed_s", 0.0);
    const std::string unit =
        probe->contains("unit") ? (*probe)["unit"].get<std::string>() : std::string("ray");
    const std::string scope = probe->contains("scope")
                                  ? (*probe)["scope"].get<std::string>()
                                  : "from the ray entering the machine until the host has its "
                                    "answer (the window of the ray latency above)";
    page.paragraph(
        "Mean time per " + unit + " at each stage (module or queue, in the order a " + unit +
        " meets them) over " + value_text((*probe)["rays"]) + " " + unit + "s, " + scope +
        ": queueing is waiting for the stage, service the stage "
        "working on the ray, transfer moving its data. A ray that never met a stage counts 0 "
        "there; share is the stage's total over the end-to-end mean; unattributed is what no "
        "stage reported (0 up to rounding when the machine reports everything). stats.json "
        "latency_probe; docs/stats.md says what each part means on each machine.");
    std::vector<std::vector<std::string>> rows;
    // The stages in the file's order, as a ray meets them (ordered_json keeps it).
    std::vector<std::string> order;
    if (stages && stages->is_object())
      for (const auto& [name, st] : stages->items()) order.push_back(name);
    for (const std::string& name : order)
      if (const json& st = (*stages)[name]; st.is_object())
        rows.push_back({name, format_seconds(num(st, "queueing_s", 0.0)),
                        format_seconds(num(st, "service_s", 0.0)),
                        format_seconds(num(st, "transfer_s", 0.0)),
                        format_seconds(num(st, "total_s", 0.0)),
                        format_number(100.0 * num(st, "share", 0.0), 4) + " %",
                        format_seconds(num(st, "p99_s", 0.0))});
    // Below 1e-9 of the mean the rest is the rounding of summing the parts: say so.
    const double rest_share = mean > 0 ? rest / mean : 0.0;
    if (std::abs(rest_share) < 1e-9)
      rows.push_back({"unattributed", "", "", "", "0 (rounding)", "0 %", ""});
    else
      rows.push_back({"unattributed", "", "", "", format_seconds(rest),
                      format_number(100.0 * rest_share, 4) + " %", ""});
    rows.push_back({"end to end (mean)", "", "", "", format_seconds(mean), "100 %",
                    e2e && e2e->is_object() ? format_seconds(num(*e2e, "p99", 0.0)) : ""});
    page.table({"stage", "queueing", "service", "transfer", "total", "share", "p99 of total"},
               rows);
    std::vector<std::string> problems;
    plot_from_stats(page, in, tools, "latency_breakdown.py", "latency_breakdown.png",
                    "where a ray spends its time",
                    "Mean queueing, service and transfer time per ray at each stage, the "
                    "unattributed rest and the end-to-end mean (analysis/latency_breakdown.py)",
                    problems);
    if (!problems.empty()) page.note(missing_plots_note(problems));
  }
}

/// Modules. A class of many instances (an array's nodes) is one row of its aggregates: a row
/// per node would be thousands.
void modules_section(HtmlReport& page, const modules::UnitSchema& units, const json& stats) {
  if (const json* mods = find(stats, "modules"); mods && mods->is_object() && !mods->empty()) {
    page.heading("Modules");
    std::set<std::string> grouped;
    const json* classes = find(stats, "module_classes");
    if (classes && classes->is_object())
      for (const auto& [name, c] : classes->items())
        if (num(c, "instances", 0.0) > modules::kInstancesShownUpTo) grouped.insert(name);
    std::vector<std::vector<std::string>> rows;
    for (const auto& [name, m] : mods->items()) {
      if (grouped.contains(modules::instance_class(name))) continue;
      std::string other;
      for (const auto& [k, v] : m.items()) {
        if (k == "busy_s" || k == "utilization" || k == "queue" || k == "utilization_windows")
          continue;
        other += (other.empty() ? "" : ", ") + k + " " +
                 figure_text(units, "modules." + name + "." + k, v);
      }
      std::string queue;
      if (const json* q = find(m, "queue"))
        queue = "capacity " + value_text((*q)["capacity"]) + ", mean " +
                format_significant(num(*q, "mean_occupancy"), 4) + ", max " +
                value_text((*q)["max_occupancy"]);
      rows.push_back({name, format_seconds(num(m, "busy_s", 0.0)),
                      format_number(100.0 * num(m, "utilization", 0.0), 4) + " %", queue, other});
    }
    for (const std::string& name : grouped) {
      const json& c = (*classes)[name];
      const auto agg = [&](const char* key, const char* what) {
        const json* a = find(c, key);
        return a && a->is_object() ? num(*a, what, 0.0) : 0.0;
      };
      std::string util, queue, other;
      if (const json* u = find(c, "utilization"); u && u->is_object())
        util = "mean " + format_number(100.0 * num(*u, "mean", 0.0), 4) + " %, " +
               format_number(100.0 * num(*u, "min", 0.0), 4) + " to " +
               format_number(100.0 * num(*u, "max", 0.0), 4) + " % (" +
               value_text((*u)["max_instance"]) + ")";
      if (find(c, "queue.mean_occupancy"))
        queue = "mean " + format_significant(agg("queue.mean_occupancy", "mean"), 4) + ", max " +
                format_number(agg("queue.max_occupancy", "max"), 4);
      for (const auto& [k, a] : c.items()) {
        if (k == "instances" || k == "busy_s" || k == "utilization" || k.rfind("queue.", 0) == 0 ||
            !a.is_object())
          continue;
        // A peak is the largest instance's; a count or a time, the sum over them.
        const bool peak = k.size() > 5 && k.compare(k.size() - 5, 5, "_peak") == 0;
        const std::string path = "modules." + name + "." + k;  // the class's key, its unit
        other += (other.empty() ? "" : ", ") + k + " " +
                 (peak ? figure_text(units, path, a["max"]) + " at most"
                       : figure_text(units, path, a["sum"]) + " in all");
      }
      rows.push_back({name + " (" + value_text(c["instances"]) + " instances)",
                      find(c, "busy_s") ? "mean " + format_seconds(agg("busy_s", "mean")) : "",
                      util, queue, other});
    }
    if (!grouped.empty())
      page.paragraph("A class of more than " + std::to_string(modules::kInstancesShownUpTo) +
                     " instances (node*: node0, node1, ...) is one row: its mean busy time, its "
                     "utilisation's mean and range (the busiest instance in brackets), its "
                     "queues' mean depth and its counts over all instances (stats.json "
                     "module_classes; each instance is in stats.json modules).");
    page.table({"module", "busy", "utilisation", "queue occupancy", "counts"}, rows);
  }
}

/// The scene's, the search structure's and the firmware's figures.
void scene_section(HtmlReport& page, const modules::UnitSchema& units, const json& stats) {
  std::vector<std::pair<std::string, std::string>> kv;
  for (const char* key : {"accel", "scene_stats", "geometry", "firmware_cost", "image"}) {
    const json* o = find(stats, key);
    if (!o || !o->is_object()) continue;
    for (const auto& [k, x] : o->items())
      kv.emplace_back(std::string(key) + "." + k,
                      figure_text(units, std::string(key) + "." + k, x));
  }
  if (!kv.empty()) {
    page.heading("Scene and firmware");
    page.key_values(kv);
  }
}

/// Every parameter with its value, where it was set and its source.
void parameters_section(HtmlReport& page, const json& stats, const RunReportInputs& in) {
  page.heading("Parameters");
  if (!in.params.empty()) {
    page.paragraph(
        "Every parameter as used. \"set by\" is where the value came from (default, "
        "FILE:LINE of a config, or -p); rows not at their default are bold. \"source\" is "
        "where the default comes from (a seed line or an assumption).");
    std::vector<std::vector<std::string>> rows;
    std::vector<bool> set;
    for (const auto& p : in.params) {
      rows.push_back({p.name, p.value_text, p.default_text, p.where_set, cite_seeds(p.source)});
      set.push_back(p.where_set != "default");
    }
    page.table({"parameter", "value", "default", "set by", "source"}, rows, set);
    seed_links(page, in.params);
  } else if (const json* ps = find(stats, "params"); ps && ps->is_object()) {
    page.paragraph("Every parameter as used (stats.json params; sources: `rtsim list params`).");
    std::vector<std::vector<std::string>> rows;
    for (const auto& [k, v] : ps->items()) rows.push_back({k, value_text(v)});
    page.table({"parameter", "value"}, rows);
  }
}

HtmlReport run_report_page(const RunReportInputs& in, const ReportTools& tools_in) {
  const ReportTools tools = tools_in.resolved();
  json stats;
  try {
    stats = json::parse(read_whole_file(in.stats_json));
  } catch (const json::exception& e) {
    throw std::runtime_error("report: " + in.stats_json.string() + " is not JSON: " + e.what());
  }
  // The unit of each number, as the run declared it (by the key's name for an older file).
  const modules::UnitSchema units = modules::UnitSchema::from_stats(stats);
  HtmlReport page("rtsim " + str(stats, "command") + ": " + str(stats, "machine") + " on " +
                  str(stats, "scene"));
  if (!in.command_line.empty()) page.paragraph(in.command_line);
  headline_section(page, stats);
  write_trace_section(page, stats);
  if (!in.image_png.empty() && fs::exists(in.image_png)) {
    page.heading("Image");
    page.image(in.image_png, "rendered image", "image.png", true);
  }
  plots_section(page, stats, in, tools);
  for (const auto& [key, v] : stats.items())
    if (const json* a = !kShownKeys.count(key) && v.is_object() ? find(v, "accuracy") : nullptr;
        a && a->is_object())
      accuracy_section(page, key, *a);
  latency_probe_section(page, stats, in, tools);
  // A machine's own figures and the other measured objects.
  for (const auto& [key, v] : stats.items()) {
    if (kShownKeys.count(key) || !v.is_object()) continue;
    page.heading(key);
    machine_section(page, units, key, key == "simulation" ? folded_activations(v) : v);
  }
  modules_section(page, units, stats);
  scene_section(page, units, stats);
  parameters_section(page, stats, in);
  page.paragraph("Written by " + str(stats, "tool") + " " + str(stats, "version") +
                 ". Every figure here is also in stats.json (schema: docs/stats.md).");
  return page;
}

}  // namespace

void write_run_report(const RunReportInputs& in, const fs::path& out_html,
                      const ReportTools& tools) {
  ScriptBatch scripts;
  (void)run_report_page(in, tools);  // starts the plots
  scripts.collect();
  const HtmlReport page = run_report_page(in, tools);  // waits for them
  page.write(out_html);
}

}  // namespace rtsim::app
