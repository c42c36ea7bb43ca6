#pragma once
// Checks a sweep before any point runs, the way `rtsim run` would check each point: every
// machine exists, every parameter exists for the machine of each point that sets it and its value
// fits (applied to that machine's registry, built as `rtsim run` builds it: common parameters,
// the machine's preset, the sweep's config files), and every scene loads.
#include <vector>

#include "platform/sweep/sweep_file.hpp"
#include "platform/sweep/sweep_points.hpp"

namespace rtsim::sweep {

struct CheckOptions {
  /// Load each distinct scene once (a scene file's syntax, a builtin name). Off in tests that
  /// look at parameters alone, and in `rtsim sweep --mpi`'s ranks other than 0, which read the
  /// sweep only to know which points write images (rank 0 checks it whole).
  bool load_scenes = true;
};

/// Throws rtsim::InputError naming the sweep file, the line of the offending value and what was
/// expected (with the closest valid names). Errors inside a config file name that file.
void check_sweep(const SweepFile& file, const std::vector<Point>& points,
                 const CheckOptions& options = {});

}  // namespace rtsim::sweep
