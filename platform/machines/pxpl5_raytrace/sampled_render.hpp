#pragma once
// pxpl5-raytrace's functional twin when its casters sample the screen rather than trace every
// pixel (firmware/tasks/region_sampling.hpp): the same regions, sampled by the same rule, the
// replicated positions merged by the same rule (tasks::better_copy), the positions kept from
// frame to frame under partial updating as the compositors keep them, and display pixels
// resampled by the same arithmetic (SampleLattice::resample) -- with no ring and no timing, so
// that the machine's image, built from what crossed the ring, can be checked against it.
#include "firmware/tasks/refinement_schedule.hpp"
#include "platform/functional/functional_renderer.hpp"
#include "platform/machines/pxpl5_raytrace/camera_path.hpp"
#include "platform/machines/pxpl5_raytrace/layout.hpp"

namespace rtsim::platform::pxpl5 {

/// The image displayed at frame `display_frame` of the camera path `path` (its last frame the
/// scene's camera), following the refinement schedule `schedule`. `layout` gives the regions and
/// the sampling rule; its size is the render's.
functional::RenderResult sampled_render(const scenes::Scene& scene, const Tracer& tracer,
                                        const functional::RenderOptions& opts, Layout layout,
                                        const CameraPath& path,
                                        const tasks::RefinementSchedule& schedule,
                                        int display_frame);

}  // namespace rtsim::platform::pxpl5
