#include "app/trace_options.hpp"

#include "app/number_text.hpp"
#include "common/input_error.hpp"
#include "params/units.hpp"

namespace rtsim::app {

namespace {

/// A time in picoseconds (SystemC's resolution, so a window edge is an exact sc_time).
std::uint64_t window_edge(std::string text, const std::string& flag) {
  const auto first = text.find_first_not_of(" \t");
  const auto last = text.find_last_not_of(" \t");
  text = first == std::string::npos ? std::string() : text.substr(first, last - first + 1);
  params::Quantity q;
  try {
    q = params::parse_quantity(text, params::UnitClass::kTime);
  } catch (const params::UnitError&) {
    try {
      // Plain seconds, as the traces' own time axis is labelled.
      q = params::parse_quantity(text, params::UnitClass::kDimensionless);
      q.unit_class = params::UnitClass::kTime;
    } catch (const params::UnitError&) {
      throw InputError(flag, 0,
                       "\"" + text + "\" is not a time; " +
                           params::expected_form(params::UnitClass::kTime) + ", or plain seconds");
    }
  }
  if (q.value < 0) throw InputError(flag, 0, "\"" + text + "\" is negative; times start at 0");
  try {
    return static_cast<std::uint64_t>(q.to_ps());
  } catch (const params::UnitError& e) {
    throw InputError(flag, 0, "\"" + text + "\": " + e.what());
  }
}

}  // namespace

modules::TraceFilter trace_filter_from(const std::string& window,
                                       const std::vector<std::string>& modules) {
  modules::TraceFilter f;
  if (!window.empty()) {
    const std::string flag = "--trace-window " + window;
    const auto comma = window.find(',');
    if (comma == std::string::npos || window.find(',', comma + 1) != std::string::npos)
      throw InputError(flag, 0,
                       "expected T0,T1: two times separated by one comma, e.g. \"10 ms,20 ms\"");
    f.from = window_edge(window.substr(0, comma), flag);
    f.to = window_edge(window.substr(comma + 1), flag);
    if (f.to <= f.from) throw InputError(flag, 0, "T1 must be later than T0");
  }
  for (const std::string& p : modules) {
    const std::string flag = "--trace-modules " + p;
    if (p.empty()) throw InputError(flag, 0, "an empty pattern matches no module");
    int depth = 0;
    for (char c : p) {
      if (c == '[') ++depth;
      if (c == ']' && depth > 0) --depth;
    }
    if (depth != 0) throw InputError(flag, 0, "unbalanced '[' in the pattern");
    f.modules.push_back(p);
  }
  return f;
}

template <class Json>
std::vector<std::string> trace_warnings(const Json& stats) {
  std::vector<std::string> out;
  if (!stats.contains("trace") || !stats["trace"].is_object()) return out;
  const auto& t = stats["trace"];
  const std::string cap = std::to_string(t.value("max_events", std::size_t{0}));
  for (const auto& [key, count] :
       {std::pair{"perfetto", "events_dropped"}, std::pair{"vcd", "changes_dropped"}}) {
    if (!t.contains(key)) continue;
    const auto dropped = t[key].value(count, std::size_t{0});
    if (dropped == 0) continue;
    std::string whole;
    if (t.contains("window_s") && t["window_s"].is_array() && t["window_s"].size() == 2)
      whole = ": it holds every event from " +
              format_seconds(t["window_s"][0].template get<double>()) + " to " +
              format_seconds(t["window_s"][1].template get<double>()) + " only";
    out.push_back(t[key].value("file", std::string(key)) + ": " + std::to_string(dropped) +
                  (std::string(key) == "vcd" ? " value changes" : " events") +
                  " dropped at --trace-max-events " + cap + "; the trace is incomplete" + whole +
                  " (stats.json trace.window_s, trace." + key + ")");
  }
  // A file too large for the viewers: Perfetto's web UI holds the whole trace in the browser's
  // memory and gives up on JSON traces of a few hundred MB; GTKWave loads a VCD whole.
  for (const char* key : {"perfetto", "vcd"}) {
    if (!t.contains(key)) continue;
    const auto bytes = t[key].value("bytes", std::uint64_t{0});
    if (bytes <= kTraceWarnBytes) continue;
    out.push_back(t[key].value("file", std::string(key)) + " is " +
                  std::to_string((bytes + 500000) / 1000000) + " MB, more than the " +
                  std::to_string(kTraceWarnBytes / 1000000) + " MB " +
                  (std::string(key) == "vcd" ? "GTKWave" : "Perfetto's UI") +
                  " opens comfortably: keep less with --trace-window T0,T1 (a part of the "
                  "frame), --trace-modules PATTERN (some modules) or --trace-max-events N, or "
                  "render a smaller frame");
  }
  if (t.contains("modules") && stats.contains("modules")) {
    for (const auto& pattern : t["modules"]) {
      modules::TraceFilter one;
      one.modules = {pattern.template get<std::string>()};
      bool any = false;
      for (const auto& [name, m] : stats["modules"].items()) any = any || one.keeps_module(name);
      if (!any)
        out.push_back("--trace-modules " + pattern.template get<std::string>() +
                      " matched no module (the names are stats.json's `modules`)");
    }
  }
  return out;
}
template std::vector<std::string> trace_warnings(const nlohmann::json&);
template std::vector<std::string> trace_warnings(const nlohmann::ordered_json&);

bool trace_is_complete(const nlohmann::json& stats) {
  if (!stats.contains("trace") || !stats["trace"].is_object()) return false;
  const auto& t = stats["trace"];
  if (!t.value("modules", nlohmann::json::array()).empty()) return false;
  if (t.contains("perfetto") && t["perfetto"].value("events_dropped", std::size_t{0}) != 0)
    return false;
  if (t.contains("vcd") && t["vcd"].value("changes_dropped", std::size_t{0}) != 0) return false;
  // The window: from 0 to at least the end of the frame.
  const auto& w = t["window_s"];
  const auto& f = t["stats_interval_s"];
  return w[0].get<double>() == 0.0 && w[1].get<double>() >= f[1].get<double>();
}

}  // namespace rtsim::app
