#include "app/run_summary.hpp"

#include <algorithm>
#include <sstream>

#include "app/bottleneck.hpp"
#include "app/json_number.hpp"
#include "app/number_text.hpp"

namespace rtsim::app {
namespace {

using json = nlohmann::json;

double number(const json& j, const char* key) { return json_number(j, key); }

/// "frame time ", or for a sequence of frames "N frames in ".
std::string frame_heading(const json& stats) {
  const int frames =
      stats.contains("frame_sequence") ? stats["frame_sequence"].value("frames", 1) : 1;
  return frames > 1 ? std::to_string(frames) + " frames in " : "frame time ";
}

void print_busy(std::ostream& out, const json& stats) {
  if (!stats.contains("modules")) return;
  const auto busy = busy_modules(stats["modules"]);
  if (busy.empty()) return;
  out << "  busy        ";
  for (std::size_t i = 0; i < busy.size() && i < kBusiestShown; ++i)
    out << (i ? "  " : "") << busy[i].name << " " << format_percent(busy[i].utilization);
  if (busy.size() > kBusiestShown)
    out << "  (" << busy.size() - kBusiestShown << " more in stats.json)";
  out << "\n";
  out << "  bottleneck  " << bottleneck_text(find_bottleneck(stats)) << "\n";
  if (const std::string scope = sampled_scope(stats); !scope.empty())
    out << "              (" << scope << ")\n";
}

void print_sample(std::ostream& out, const json& stats) {
  if (!stats.contains("sample")) return;
  const auto& sm = stats["sample"];
  if (sm.contains("plan")) {
    const auto& plan = sm["plan"];
    const int every = plan.value("every", 0);
    out << "  sample      K = " << every << (every >= 2 ? "" : " (the whole frame in detail)")
        << " for +-" << format_significant(100.0 * plan.value("target_error", 0.0), 3)
        << "%, chosen by a pilot at K = " << plan.value("pilot_every", 0) << " ("
        << format_seconds(plan.value("pilot_wall_time_s", 0.0)) << " wall)\n";
  }
  if (!sm.contains("ci99_7_s")) return;
  out << "  sample      " << sm.value("detailed_windows", 0) << " of " << sm.value("windows", 0)
      << " windows of " << sm.value("window_rows", sm.value("window_units", 0)) << " "
      << sm.value("unit", std::string("rows")) << " in detail ("
      << format_seconds(number(sm, "detailed_frame_s")) << " simulated): frame time "
      << format_seconds(number(sm, "estimate_s")) << " +- "
      << format_significant(100.0 * number(sm, "half_width_relative"), 2)
      << "% (99.7% confidence)\n";
}

void print_latency(std::ostream& out, const json& stats) {
  // A machine that follows no ray from start to answer (pxpl5-raytrace: a caster traces a
  // region in one go) records none.
  if (stats.contains("ray_latency_s") && number(stats["ray_latency_s"], "count") > 0) {
    const auto& l = stats["ray_latency_s"];
    out << "  ray latency mean " << format_seconds(number(l, "mean")) << ", p50 "
        << format_seconds(number(l, "p50")) << ", p99 " << format_seconds(number(l, "p99")) << "\n";
  }
  if (!stats.contains("latency_probe")) return;
  const auto& p = stats["latency_probe"];
  // The stages where a ray spends most of its time first.
  std::vector<std::pair<std::string, const json*>> stages;
  for (const auto& [name, st] : p["stages"].items()) stages.emplace_back(name, &st);
  std::stable_sort(stages.begin(), stages.end(), [](const auto& a, const auto& b) {
    return number(*a.second, "share") > number(*b.second, "share");
  });
  const std::string unit = p.value("unit", std::string("ray"));
  out << "  per " << unit << std::string(unit.size() < 8 ? 8 - unit.size() : 1, ' ');
  for (std::size_t i = 0; i < stages.size(); ++i)
    out << (i ? ", " : "") << stages[i].first << " "
        << format_seconds(number(*stages[i].second, "total_s")) << " ("
        << format_percent(number(*stages[i].second, "share")) << ")";
  out << "; unattributed " << format_seconds(number(p, "unattributed_s")) << "\n";
  if (p.contains("scope") && p["scope"].is_string())
    out << "              (" << p["scope"].get<std::string>() << ")\n";
}

/// A machine that renders a sequence of frames (stats.json `frame_sequence`): its frame rate,
/// the latency from a frame's start to its display, and each frame's figures (the first few).
void print_frames(std::ostream& out, const json& stats) {
  if (!stats.contains("frame_sequence")) return;
  const auto& fs = stats["frame_sequence"];
  const int frames = fs.value("frames", 0);
  if (frames < 2) return;
  out << "  frames      " << frames << " at "
      << format_significant(number(fs, "frames_per_second"), 3) << " frames/s (after the first "
      << format_significant(number(fs, "steady_frames_per_second"), 3) << ", the last "
      << format_significant(number(fs, "last_frame_per_second"), 3) << "); latency mean "
      << format_seconds(number(fs, "latency_mean_s")) << ", max "
      << format_seconds(number(fs, "latency_max_s")) << "\n";
  constexpr std::size_t kShown = 12;
  const auto& per = fs["per_frame"];
  for (std::size_t i = 0; i < per.size() && i < kShown; ++i) {
    const auto& f = per[i];
    std::string label = "frame " + std::to_string(f.value("frame", 0));
    label.resize(std::max<std::size_t>(label.size() + 1, 12), ' ');
    out << "  " << label << "start " << format_seconds(number(f, "start_s")) << ", displayed "
        << format_seconds(number(f, "display_s")) << ", latency "
        << format_seconds(number(f, "latency_s")) << ", interval "
        << format_seconds(number(f, "interval_s"));
    // A machine that refines (pxpl5-raytrace): the level it cast and the one it showed.
    if (f.contains("display_level"))
      out << ", cast level " << f.value("cast_level", 0) << ", shown at "
          << f.value("display_level", 0);
    out << "\n";
  }
  if (per.size() > kShown)
    out << "              (" << per.size() - kShown << " more in stats.json frame_sequence)\n";
}

}  // namespace

std::string estimate_suffix(const json& stats) {
  if (!stats.contains("sample") || !stats["sample"].contains("ci99_7_s")) return {};
  const auto& ci = stats["sample"]["ci99_7_s"];
  if (!ci.is_array() || ci.size() != 2 || !ci[0].is_number() || !ci[1].is_number()) return {};
  return " +- " + format_seconds((ci[1].get<double>() - ci[0].get<double>()) / 2.0) +
         " (estimated, 99.7%)";
}

std::string sampled_scope(const json& stats) {
  if (!stats.contains("sample") || !stats["sample"].contains("ci99_7_s")) return {};
  const auto& sm = stats["sample"];
  return "busy, bottleneck and latency figures cover the " +
         std::to_string(sm.value("detailed_windows", 0)) + " of " +
         std::to_string(sm.value("windows", 0)) + " windows simulated in detail (" +
         format_seconds(number(sm, "detailed_frame_s")) + " simulated)";
}

std::string format_run_summary(const json& stats,
                               const std::vector<std::pair<std::string, std::string>>& outputs) {
  std::ostringstream out;
  out << "rtsim run: " << stats.value("machine", std::string()) << " on "
      << stats.value("scene", std::string()) << " at " << stats.value("width", 0) << "x"
      << stats.value("height", 0) << ": " << frame_heading(stats)
      << format_seconds(number(stats, "simulated_time_s")) << estimate_suffix(stats)
      << " simulated, " << format_seconds(number(stats, "wall_time_s")) << " wall\n";
  print_busy(out, stats);
  print_frames(out, stats);
  print_latency(out, stats);
  print_sample(out, stats);
  if (stats.contains("overhead_ratio"))
    out << "  overhead    " << format_significant(number(stats, "overhead_ratio"), 3)
        << "x the functional render of the same frame ("
        << format_seconds(number(stats, "functional_wall_time_s")) << " wall)\n";
  for (const auto& [what, where] : outputs) {
    std::string label = what;
    label.resize(std::max<std::size_t>(label.size() + 1, 12), ' ');
    out << "  " << label << where << "\n";
  }
  return out.str();
}

nlohmann::json summary_view(const nlohmann::ordered_json& stats) {
  json view = json::object();
  for (const auto& [key, value] : stats.items()) {
    if (key != "modules" || !value.is_object()) {
      view[key] = value;
      continue;
    }
    json& modules = view[key];
    modules = json::object();
    for (const auto& [name, module] : value.items()) {
      if (!module.is_object()) {
        modules[name] = module;
        continue;
      }
      json& m = modules[name];
      m = json::object();
      for (const auto& [k, v] : module.items())
        if (k != "utilization_windows") m[k] = v;
    }
  }
  return view;
}

std::string format_run_summary(const nlohmann::ordered_json& stats,
                               const std::vector<std::pair<std::string, std::string>>& outputs) {
  return format_run_summary(summary_view(stats), outputs);
}

}  // namespace rtsim::app
