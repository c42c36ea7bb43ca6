#pragma once
// Gaudet's "npp" test scenes (seed 001 L968-L971, §6.1.2; note 001 §4.2): 64 clusters of
// randomly placed spheres; pp = spheres per cluster (= per leaf shell); n = order of the complete
// shell tree built over the 64 clusters, 2 (binary), 4 (quad) or 8 (oct). "Scenes 204, 404 and
// 804 look the same because they share the same primitive data" (L970): the primitives here
// depend only on pp and the seed, never on n. n only travels with the scene name and is what the
// box-shell builder (elsewhere) uses.
//
// Layout (the thesis gives none; Resolution, lights, camera of these scenes are absent, note 001
// §4.2 / §6.6, so all of it is a documented choice):
// - the 64 clusters occupy the cells of a 4 x 4 x 4 grid of cubes of side kNppCellSize centred
//   on the origin, one cluster per cell;
// - clusters are numbered in Morton (Z-order) of their cell: cluster k has cell
//   x = bits 0,3 of k; y = bits 1,4; z = bits 2,5. So every run of 2, 4, 8, 16, 32 consecutive
//   clusters aligned to its size is a compact block of cells (2x1x1, 2x2x1, 2x2x2, 4x2x2, 4x4x2)
//   and grouping consecutive clusters b at a time gives spatially sensible parents for b = 2, 4, 8;
// - the spheres of a cluster lie in a ball at a random place in their cell (npp_scene.cpp), inside
//   the cell shrunk by kNppCellMargin on every side, so leaf shells of different clusters never
//   overlap and there is void between clusters;
// - spheres never overlap each other (rejection sampling, bounded; see npp_scene.cpp);
// - primitives of cluster k are contiguous, clusters in order 0..63; cluster_of_primitive is set.
#include <cstdint>
#include <string>
#include <string_view>

#include "firmware/bounds.hpp"
#include "firmware/scene.hpp"

namespace rtsim::scenes {

inline constexpr int kNppClusterCount = 64;     ///< seed 001 L970: "64 clusters"
inline constexpr int kNppCellsPerAxis = 4;      ///< 4^3 = 64 cells, one cluster each
inline constexpr double kNppCellSize = 1.0;     ///< side of one cluster cell (scene units)
inline constexpr double kNppCellMargin = 0.04;  ///< empty border inside each cell (cell units)
inline constexpr int kNppMinSpheresPerCluster = 1;
inline constexpr int kNppMaxSpheresPerCluster = 99;     ///< pp is two digits
inline constexpr std::uint64_t kNppDefaultSeed = 1985;  ///< the thesis year

/// Cell of cluster k (0..63) in world space (whole cell, margin not removed).
Bounds npp_cluster_cell(int cluster);

/// Makes scene `npp-NPP` (n in {2,4,8}, pp in kNppMin..kNppMaxSpheresPerCluster); throws
/// std::invalid_argument otherwise. Scene::name = "builtin:npp-" + n + pp (two digits).
Scene make_npp_scene(int branching, int spheres_per_cluster, std::uint64_t seed = kNppDefaultSeed);

/// Parses "npp-NPP" (e.g. "npp-408") into n and pp; false if the name is not of that form or
/// out of range.
bool parse_npp_name(std::string_view name, int& branching, int& spheres_per_cluster);

/// Fig 6-1 of the thesis (seed 001 L980-L989): what the box-shell hierarchy of an npp scene must
/// count. Shells exclude the root ("scene") shell; a shell packet is the child list of one parent
/// (root included); a primitive packet is the primitives of one leaf shell.
struct NppShellCounts {
  int shells = 0;
  int shell_packets = 0;
  int primitives = 0;
  int primitive_packets = 0;
};

/// Counts for a complete `branching`-ary tree over 64 leaf shells of `spheres_per_cluster`
/// spheres: shells = b + b^2 + ... + 64, packets = 1 + b + ... + 64/b, primitives = 64 pp,
/// primitive packets = 64. E.g. 204 -> 126/63/256/64, 408 -> 84/21/512/64, 812 -> 72/9/768/64.
NppShellCounts npp_expected_counts(int branching, int spheres_per_cluster);

}  // namespace rtsim::scenes
