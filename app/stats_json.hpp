#pragma once
// stats.json of a run. Schema documented in docs/stats.md; keys are stable.
#include <nlohmann/json.hpp>

#include "platform/functional/functional_renderer.hpp"
#include "platform/functional/render_params.hpp"
#include "platform/functional/scene_geometry.hpp"
#include "platform/params/registry.hpp"
#include "scenes/scene.hpp"

namespace rtsim::app {

nlohmann::ordered_json render_stats_json(const scenes::Scene& scene,
                                         const functional::SceneGeometry& geometry,
                                         const params::ParamRegistry& registry,
                                         const functional::RenderSettings& settings,
                                         const functional::RenderOptions& options,
                                         const functional::RenderResult& result);

}  // namespace rtsim::app
