#pragma once
// The functional renderer's Tracer: the kernel shapes of a SceneGeometry behind one of the
// machines' acceleration structures (Ullner's grid, Gaudet's shells) or none.
#include <memory>

#include "firmware/accel/shell_traversal.hpp"
#include "firmware/accel/shell_tree.hpp"
#include "firmware/tracer.hpp"
#include "platform/functional/render_params.hpp"
#include "platform/functional/scene_geometry.hpp"
#include "scenes/scene.hpp"

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

/// Builds the tracer chosen by settings.accel over `geometry` (which must outlive it) and
/// writes a one-line description of the structure into geometry.accel_description.
std::unique_ptr<Tracer> make_tracer(SceneGeometry& geometry, const scenes::Scene& scene,
                                    const RenderSettings& settings);

}  // namespace rtsim::functional
