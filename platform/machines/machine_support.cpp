#include "platform/machines/machine_support.hpp"

#include <systemc>
#include <tlm>

#include "common/input_error.hpp"
#include "common/suggest.hpp"
#include "modules/module_params.hpp"
#include "modules/sim_time.hpp"
#include "platform/functional/auto_view.hpp"
#include "platform/functional/scene_tracer.hpp"

namespace rtsim::platform {

FunctionalTwin make_functional_twin(scenes::Scene& scene, const functional::RenderSettings& s) {
  FunctionalTwin twin;
  twin.settings = s;
  twin.geometry = std::make_unique<functional::SceneGeometry>(functional::convert_scene(scene, s));
  if (!scene.has_camera) functional::frame_automatically(scene, twin.geometry->scene_bounds);
  if (s.view_azimuth_deg != 0.0 || s.view_elevation_deg != 0.0)
    functional::turn_view(scene.camera, s.view_azimuth_deg, s.view_elevation_deg);
  twin.settings.shade.scene_extent = functional::scene_extent(twin.geometry->scene_bounds);
  try {
    twin.tracer = functional::make_tracer(*twin.geometry, scene, twin.settings);
  } catch (const std::length_error& e) {
    // The search structure cannot hold this scene at these settings (the grid's subvolume
    // references outgrow its 32-bit offsets): bad input, with what to change.
    throw InputError(scene.name, 0,
                     std::string("the acceleration structure cannot hold this scene: ") + e.what() +
                         ", or search without a grid");
  }
  return twin;
}

void require_surviving_primitives(const std::string& machine, const scenes::Scene& scene,
                                  const FunctionalTwin& twin, const std::string& what_is_empty) {
  const auto& g = *twin.geometry;
  if (!g.shapes.empty()) return;
  throw InputError(
      scene.name, 0,
      machine + ": no primitive of this scene survives the repair of degenerate geometry (" +
          std::to_string(g.report.rejected) + " rejected" +
          (g.report.messages.empty() ? std::string() : ", the first: " + g.report.messages[0]) +
          "), so " + what_is_empty + "; `rtsim render` and vax-750 draw the empty scene");
}

namespace {
const modules::TimeParam kQuantum(
    {.name = "quantum",
     .default_value = "0 s",
     .max = "1 s",
     .description = "Global TLM quantum: how far a thread may run ahead of simulated time. 0 is "
                    "the reference setting (every interaction in time order); larger values run "
                    "faster at a measured frame-time error (docs/quantum.md)",
     .source = "simulator setting: TLM-2.0 loosely-timed coding style"});
}  // namespace

void declare_quantum_param(params::ParamRegistry& r) {
  modules::ParamDecls(r, "", false).add(kQuantum);
}

void begin_simulation(const params::ParamRegistry& r) {
  tlm::tlm_global_quantum::instance().set(modules::ModuleParams(r, "").get(kQuantum));
}

void require_polygons(const std::string& machine, const scenes::Scene& scene) {
  std::size_t other = 0;
  std::uint32_t first_line = 0;
  for (const auto& p : scene.primitives) {
    if (p.kind == scenes::PrimitiveKind::Polygon) continue;
    if (other++ == 0) first_line = p.source_line;
  }
  if (other > 0)
    throw InputError(scene.name, first_line,
                     machine +
                         " intersects polygons only (convex quadrilaterals, seed 000 L267); this "
                         "scene has " +
                         std::to_string(other) +
                         " sphere/cone/patch primitive(s). Use a polygon scene or another "
                         "machine (`rtsim list machines`)");
}

void inject_faults(const std::string& machine, const std::vector<MemoryFault>& faults,
                   const std::vector<modules::Memory*>& memories,
                   const std::vector<std::string>& in_flight) {
  for (const auto& f : faults) {
    const std::string arg = "--fault " + f.memory + ":" + std::to_string(f.word);
    modules::Memory* target = nullptr;
    std::vector<std::string_view> names;
    for (auto* m : memories) {
      names.emplace_back(m->name());
      if (f.memory == m->name()) target = m;
    }
    for (const auto& p : in_flight) names.emplace_back(p);
    if (!target) {
      std::string msg = machine + " has no memory '" + f.memory + "' whose words its answers use";
      const std::string suggestion = did_you_mean(f.memory, names);
      msg += suggestion;
      if (names.empty())
        msg += " (it has none: its answers are not computed from the words of a modelled memory)";
      else if (suggestion.empty() && !memories.empty())
        msg += " (it has: " + std::string(memories.front()->name()) +
               (memories.size() > 1 ? ", ..." : "") + ")";
      if (!in_flight.empty()) {
        msg += "; in flight it corrupts words at";
        for (std::size_t k = 0; k < in_flight.size(); ++k) msg += (k ? ", " : " ") + in_flight[k];
      }
      throw InputError(arg, 0, msg);
    }
    if (f.word >= target->size_words())
      throw InputError(arg, 0,
                       f.memory + " holds " + std::to_string(target->size_words()) +
                           " words on this scene (0 to " +
                           std::to_string(target->size_words() - 1) + ")");
    target->inject_fault(f.word, f.xor_mask);
  }
}

modules::UnitSchema faults_units() {
  using modules::StatUnit;
  // The mask is a word's bits to flip, shown as the number it is.
  return {{"word", StatUnit::count}, {"xor_mask", StatUnit::count}, {"applied", StatUnit::count}};
}

nlohmann::ordered_json faults_json(const std::vector<modules::Memory*>& memories) {
  nlohmann::ordered_json out = nlohmann::ordered_json::array();
  for (const auto* m : memories)
    for (const auto& f : m->faults())
      out.push_back({{"memory", m->name()},
                     {"word", f.word},
                     {"xor_mask", f.xor_mask},
                     {"applied", f.applied}});
  return out;
}

}  // namespace rtsim::platform
