#pragma once
// One entry point for every scene the command accepts:
//   path/to/file.nff   Eric Haines' NFF (see nff_reader.hpp)
//   path/to/file.bpt   bicubic Bezier patches (see bpt_reader.hpp)
//   builtin:NAME       a generated scene (see builtin_scenes())
// The extension is matched case-insensitively. Every failure is one rtsim::InputError.
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "firmware/scene.hpp"

namespace rtsim::scenes {

inline constexpr std::string_view kBuiltinPrefix = "builtin:";

/// Seeds of the random generators, for the lead to wire to config later.
struct GeneratorSeeds {
  std::uint64_t npp;
  std::uint64_t ullner_cubes;
  std::uint64_t ullner_random;  ///< builtin:ullner-random-N
};
GeneratorSeeds default_generator_seeds();

struct BuiltinScene {
  std::string name;         ///< without the "builtin:" prefix
  std::string description;  ///< one line, for `rtsim list scenes`
};

/// Every builtin scene, in listing order: default, ullner-cubes, ullner-random-N for N = 100,
/// 1000, 10000, 100000, 1000000 (Ullner's analytic-model scene, seed 000 L654), then the npp
/// scenes n = 2, 4, 8 with pp = 04, 08, 12, 16, 20 (Gaudet's Fig 6-1 and §6.2 set).
/// make_builtin_scene also accepts any other npp-NPP with n in {2,4,8} and pp in 01..99, and
/// any ullner-random-N with N in [kUllnerRandomMinPolygons, kUllnerRandomMaxPolygons].
const std::vector<BuiltinScene>& builtin_scenes();
std::vector<std::string> builtin_scene_names();

/// Makes builtin scene `name` (without prefix). Unknown name -> InputError("", 0, ...) listing
/// the valid names that contain it, then the closest by edit distance (rtsim::closest_names).
Scene make_builtin_scene(std::string_view name,
                         const GeneratorSeeds& seeds = default_generator_seeds());

/// Loads a scene file or builtin:NAME (see above).
Scene load_scene(const std::string& spec, const GeneratorSeeds& seeds = default_generator_seeds());

}  // namespace rtsim::scenes
