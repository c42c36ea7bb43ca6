#include "app/stats_json.hpp"

#include <cmath>

#include "app/sample_pilot.hpp"

namespace rtsim::app {

using nlohmann::ordered_json;

namespace {

ordered_json cost_json(const Cost& c) {
  return ordered_json{{"fp_add", c.fp_add},       {"fp_mul", c.fp_mul},
                      {"fp_div", c.fp_div},       {"fp_sqrt", c.fp_sqrt},
                      {"mem_words", c.mem_words}, {"instructions", c.instructions}};
}

ordered_json rays_json(const TraceCounters& c) {
  return ordered_json{{"total", c.total_rays()},
                      {"primary", c.rays[static_cast<int>(RayKind::Primary)]},
                      {"shadow", c.rays[static_cast<int>(RayKind::Shadow)]},
                      {"reflected", c.rays[static_cast<int>(RayKind::Reflected)]},
                      {"refracted", c.rays[static_cast<int>(RayKind::Refracted)]}};
}

ordered_json params_json(const params::ParamRegistry& registry) {
  ordered_json out = ordered_json::object();
  for (const auto& e : registry.list()) out[e.name] = e.value_text;
  return out;
}

const char* accel_name(functional::AccelKind k) {
  switch (k) {
    case functional::AccelKind::Grid:
      return "grid";
    case functional::AccelKind::Shells:
      return "shells";
    case functional::AccelKind::None:
      return "none";
  }
  return "?";
}

}  // namespace

modules::UnitSchema frame_units() {
  using modules::StatUnit;
  return {{"schema_version", StatUnit::count},
          {"width", StatUnit::count},
          {"height", StatUnit::count},
          {"spp", StatUnit::count},
          {"simulated_time_s", StatUnit::seconds},
          {"wall_time_s", StatUnit::seconds},
          {"functional_wall_time_s", StatUnit::seconds},
          {"overhead_ratio", StatUnit::ratio},
          {"threads", StatUnit::count},
          {"rays.*", StatUnit::count},
          {"rays_per_second", StatUnit::rate},
          {"intersection_tests", StatUnit::count},
          {"hits", StatUnit::count},
          {"accel.*", StatUnit::count},
          {"patch_subdivisions", StatUnit::count},
          {"firmware_cost.mem_words", StatUnit::words},
          {"firmware_cost.*", StatUnit::count},
          {"scene_stats.*", StatUnit::count},
          {"geometry.*", StatUnit::count},
          {"image.nonfinite_values", StatUnit::count},
          // A linear pixel value, 1 the white of the scene's lights.
          {"image.mean_rgb", StatUnit::ratio}};
}

modules::UnitSchema run_units(const modules::UnitSchema& of_the_run) {
  modules::UnitSchema units = frame_units();
  units.add(of_the_run);
  units.add(SamplePlan::units(), "sample.plan.");
  return units;
}

ordered_json frame_stats_json(const std::string& command, const std::string& machine,
                              const scenes::Scene& scene, const functional::SceneGeometry& geometry,
                              const params::ParamRegistry& registry,
                              const functional::RenderSettings& settings,
                              const functional::RenderResult& result, int threads,
                              double simulated_time_s) {
  const TraceCounters& c = result.counters;
  std::size_t nonfinite = 0;
  double sum[3] = {0, 0, 0};
  for (std::size_t i = 0; i < result.rgb.size(); ++i) {
    if (!std::isfinite(result.rgb[i]))
      ++nonfinite;
    else
      sum[i % 3] += result.rgb[i];
  }
  const double pixels = static_cast<double>(result.width) * result.height;
  ordered_json j;
  j["tool"] = "rtsim";
  j["version"] = RTSIM_VERSION;
  // The layout of this file (docs/stats.md, "Schema versions"): bumped when a key is renamed
  // or moved. Files without it are schema 1.
  j["schema_version"] = kStatsSchemaVersion;
  j["command"] = command;
  j["machine"] = machine;
  j["scene"] = scene.name;
  j["width"] = result.width;
  j["height"] = result.height;
  j["spp"] = settings.spp;
  if (simulated_time_s >= 0) j["simulated_time_s"] = simulated_time_s;
  j["wall_time_s"] = result.wall_time_s;
  j["threads"] = threads;
  j["rays"] = rays_json(c);
  j["rays_per_second"] =
      result.wall_time_s > 0 ? static_cast<double>(c.total_rays()) / result.wall_time_s : 0.0;
  j["intersection_tests"] = c.intersection_tests;
  j["hits"] = c.hits;
  j["accel"] = ordered_json{{"kind", accel_name(settings.accel)},
                            {"box_tests", c.box_tests},
                            {"dda_steps", c.dda_steps},
                            {"cells_visited", c.cells_visited},
                            {"description", geometry.accel_description}};
  j["patch_subdivisions"] = c.patch_subdivisions;
  j["firmware_cost"] = cost_json(c.cost);
  j["scene_stats"] =
      ordered_json{{"primitives", scene.primitives.size()}, {"spheres", scene.spheres.size()},
                   {"polygons", scene.polygons.size()},     {"cones", scene.cones.size()},
                   {"patches", scene.patches.size()},       {"lights", scene.lights.size()},
                   {"materials", scene.materials.size()}};
  j["geometry"] = ordered_json{
      {"triangles", geometry.report.triangles}, {"ullner_quads", geometry.report.quads},
      {"spheres", geometry.report.spheres},     {"cones", geometry.report.cones},
      {"patches", geometry.report.patches},     {"rejected", geometry.report.rejected},
      {"messages", geometry.report.messages}};
  j["image"] = ordered_json{{"nonfinite_values", nonfinite},
                            {"mean_rgb", {sum[0] / pixels, sum[1] / pixels, sum[2] / pixels}}};
  j["params"] = params_json(registry);
  return j;
}

}  // namespace rtsim::app
