#pragma once
// What `rtsim run` prints when it has finished: the frame time, the modules by utilisation with
// the bottleneck named, the ray latency, the sample estimate, the overhead over the functional
// render, and where the outputs went. Numbers in engineering units (number_text.hpp).
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace rtsim::app {

/// The summary of a run from its stats.json document; `outputs` are the lines naming the files
/// written ({"image", "out/run/image.png  out/run/image.exr"}, ...).
std::string format_run_summary(const nlohmann::json& stats,
                               const std::vector<std::pair<std::string, std::string>>& outputs);
/// The same from the document as `rtsim run` builds it, through summary_view: a 32 x 32
/// array's stats.json is 21 MB, most of it the modules' utilisation series, and a whole copy
/// into nlohmann::json (and its release) cost more instructions than the statistics themselves.
std::string format_run_summary(const nlohmann::ordered_json& stats,
                               const std::vector<std::pair<std::string, std::string>>& outputs);
/// What the summary reads of a stats document: every key but the modules' utilisation series
/// (`modules.*.utilization_windows`), as nlohmann::json.
nlohmann::json summary_view(const nlohmann::ordered_json& stats);

/// A sampled run's frame time is an estimate: " +- 0.31 s (estimated, 99.7%)", the half-width of
/// its interval; "" for a run in full detail. The console's and the report's headline.
std::string estimate_suffix(const nlohmann::json& stats);
/// What a sampled run's module figures cover ("busy, bottleneck and latency figures cover the 8
/// of 32 windows simulated in detail (2.1 s simulated)"); "" for a run in full detail.
std::string sampled_scope(const nlohmann::json& stats);

/// How many modules the busy line shows, busiest first.
inline constexpr std::size_t kBusiestShown = 8;

}  // namespace rtsim::app
