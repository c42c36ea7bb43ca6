#include "app/scene_input.hpp"

#include "scenes/scene_loader.hpp"

namespace rtsim::app {

scenes::Scene load_scene_with_seed(const std::string& spec, const params::ParamRegistry& r) {
  scenes::GeneratorSeeds seeds = scenes::default_generator_seeds();
  if (const auto seed = static_cast<std::uint64_t>(r.get_int("scene.seed")); seed != 0)
    seeds.npp = seeds.ullner_cubes = seeds.ullner_random = seed;
  return scenes::load_scene(spec, seeds);
}

}  // namespace rtsim::app
