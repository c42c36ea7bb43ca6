#pragma once
// `rtsim run --trace-window T0,T1 --trace-modules GLOB --trace-max-events N`: what the user
// asked the traces to keep, checked before anything runs (bad input: InputError, exit 2), and
// afterwards what became of it (events a cap dropped, patterns that matched nothing), for the
// console and the report.
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "modules/trace/trace_filter.hpp"

namespace rtsim::app {

/// `window`: "" (all of time) or "T0,T1", each a time with a unit ("10 ms") or plain seconds,
/// 0 <= T0 < T1, in the simulated time the traces show (the frame starts after the scene load).
/// `modules`: fnmatch patterns on stats.json module names; none empty, brackets balanced.
modules::TraceFilter trace_filter_from(const std::string& window,
                                       const std::vector<std::string>& modules);

using modules::kTraceWarnBytes;

/// One sentence per thing the user should know about the traces of a run, from its stats.json
/// (`trace`, `modules`): events dropped at the cap, a file larger than kTraceWarnBytes (with
/// the options that keep less), patterns that kept no module. Empty when the traces are
/// complete as asked and open.
/// For stats.json as read (nlohmann::json) and as written (ordered_json): the run reads it in
/// place, without a copy of every module's statistics.
template <class Json>
std::vector<std::string> trace_warnings(const Json& stats);

/// The traces hold every event of the whole frame for every module (no window, no module
/// patterns, nothing dropped): only then can a plot of the frame be drawn from them.
bool trace_is_complete(const nlohmann::json& stats);

}  // namespace rtsim::app
