#pragma once
// The functional renderer's Tracer: the kernel shapes of a SceneGeometry behind one of the
// machines' acceleration structures (Ullner's grid, Gaudet's shells) or none.
#include <memory>

#include "firmware/accel/shell_traversal.hpp"
#include "firmware/accel/shell_tree.hpp"
#include "firmware/accel/uniform_grid.hpp"
#include "firmware/scene.hpp"
#include "firmware/tracer.hpp"
#include "platform/functional/candidate_test.hpp"
#include "platform/functional/render_params.hpp"
#include "platform/functional/scene_geometry.hpp"

namespace rtsim::functional {

/// The tracer of render.accel = shells (Gaudet's Shell and Prim tasks), which can also report
/// what one search did: the PERT's processors time their packets from it.
class ShellSearch : public Tracer {
 public:
  using Tracer::any_hit;
  using Tracer::closest_hit;
  virtual const accel::ShellTree& tree() const = 0;
  /// As closest_hit / any_hit, adding what the search did to `stats`.
  virtual bool closest_hit(const Ray& ray, double t_min, double t_max, Hit& hit,
                           TraceCounters& counters, accel::ShellTraversalStats& stats) const = 0;
  virtual bool any_hit(const Ray& ray, double t_min, double t_max, TraceCounters& counters,
                       accel::ShellTraversalStats& stats) const = 0;
};

/// Tests shape `slot` of `geometry` with its kernel over (t_min, t_max), counting the test and
/// its cost: every search's candidate test, also for a machine that runs the search itself.
bool test_shape(const SceneGeometry& geometry, std::uint32_t slot, const Ray& ray, double t_min,
                double t_max, SurfaceHit& out, TraceCounters& counters);
/// `hit` for a hit `s` on shape `slot`: the surface, the scene primitive and its material.
void fill_hit(const SceneGeometry& geometry, std::uint32_t slot, const SurfaceHit& s, Hit& hit);

/// Builds the tracer chosen by settings.accel over `geometry` (which must outlive it) and
/// writes a one-line description of the structure into geometry.accel_description. With a
/// `machine_test` (which must outlive the tracer) the search tests its candidates with that
/// instead of the geometry's kernels: a machine's search on its own memories.
std::unique_ptr<Tracer> make_tracer(SceneGeometry& geometry, const scenes::Scene& scene,
                                    const RenderSettings& settings,
                                    const CandidateTest* machine_test = nullptr);

/// The same search as `twin` (a tracer make_tracer built over `g`: the grid or brute force),
/// over the same structure (the grid is shared, not rebuilt), testing its candidates with
/// `machine_test`: the peripheral's search on its parameter memories. Both must outlive it.
std::unique_ptr<Tracer> make_tracer_sharing(const Tracer& twin, const SceneGeometry& g,
                                            const CandidateTest* machine_test);

/// The subvolume grid of `twin` (a grid tracer make_tracer built), nullptr for another
/// structure: a machine whose nodes walk the twin's subvolumes themselves (ullner-array).
std::shared_ptr<const accel::UniformGrid> grid_of(const Tracer& twin);

}  // namespace rtsim::functional
