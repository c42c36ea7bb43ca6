#include "platform/machines/machine_support.hpp"

#include <systemc>
#include <tlm>

#include "modules/sim_time.hpp"
#include "platform/functional/auto_view.hpp"
#include "platform/functional/scene_tracer.hpp"

namespace rtsim::platform {

FunctionalTwin make_functional_twin(scenes::Scene& scene, const functional::RenderSettings& s) {
  FunctionalTwin twin;
  twin.settings = s;
  twin.geometry = std::make_unique<functional::SceneGeometry>(functional::convert_scene(scene, s));
  if (!scene.has_camera) functional::frame_automatically(scene, twin.geometry->scene_bounds);
  twin.settings.shade.scene_extent = functional::scene_extent(twin.geometry->scene_bounds);
  twin.tracer = functional::make_tracer(*twin.geometry, scene, twin.settings);
  return twin;
}

void begin_simulation(const params::ParamRegistry& r) {
  tlm::tlm_global_quantum::instance().set(modules::from_ps(r.get_time_ps("quantum")));
}

}  // namespace rtsim::platform
