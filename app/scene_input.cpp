#include "app/scene_input.hpp"

#include "platform/functional/render_params.hpp"
#include "scenes/scene_loader.hpp"

namespace rtsim::app {

scenes::Scene load_scene_with_seed(const std::string& spec, const params::ParamRegistry& r) {
  scenes::GeneratorSeeds seeds = scenes::default_generator_seeds();
  if (const std::uint64_t seed = functional::read_scene_seed(r); seed != 0)
    seeds.npp = seeds.ullner_cubes = seeds.ullner_random = seed;
  return scenes::load_scene(spec, seeds);
}

}  // namespace rtsim::app
