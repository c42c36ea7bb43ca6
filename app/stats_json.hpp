#pragma once
// stats.json of a run. Schema documented in docs/stats.md; keys are stable.
#include <nlohmann/json.hpp>

#include "firmware/scene.hpp"
#include "modules/stat_unit.hpp"
#include "params/registry.hpp"
#include "platform/functional/functional_renderer.hpp"
#include "platform/functional/render_params.hpp"
#include "platform/functional/scene_geometry.hpp"

namespace rtsim::app {

/// stats.json's layout: 2 since modules report their own statistics (queues have no busy time,
/// host.job_latency_s, parameter_memories.words_written: docs/stats.md "Schema versions").
inline constexpr int kStatsSchemaVersion = 2;

/// The keys every run shares. `simulated_time_s` < 0 leaves that key out (functional render).
nlohmann::ordered_json frame_stats_json(const std::string& command, const std::string& machine,
                                        const scenes::Scene& scene,
                                        const functional::SceneGeometry& geometry,
                                        const params::ParamRegistry& registry,
                                        const functional::RenderSettings& settings,
                                        const functional::RenderResult& result, int threads,
                                        double simulated_time_s);

/// The units of frame_stats_json's numbers and of `--overhead`'s (modules/stat_unit.hpp); a
/// run adds its machine's and modules' (RunResult::units) and writes them as `units`.
modules::UnitSchema frame_units();
/// The units a `rtsim run` stats.json carries: frame_units(), then the run's own (its machine's,
/// modules' and options' keys: RunResult::units), then `--sample-error`'s plan.
modules::UnitSchema run_units(const modules::UnitSchema& of_the_run);

}  // namespace rtsim::app
