#pragma once
// The functional renderer's Tracer: the kernel shapes of a SceneGeometry behind one of the
// machines' acceleration structures (Ullner's grid, Gaudet's shells) or none.
#include <memory>

#include "firmware/tracer.hpp"
#include "platform/functional/render_params.hpp"
#include "platform/functional/scene_geometry.hpp"
#include "scenes/scene.hpp"

namespace rtsim::functional {

/// Builds the tracer chosen by settings.accel over `geometry` (which must outlive it) and
/// writes a one-line description of the structure into geometry.accel_description.
std::unique_ptr<Tracer> make_tracer(SceneGeometry& geometry, const scenes::Scene& scene,
                                    const RenderSettings& settings);

}  // namespace rtsim::functional
