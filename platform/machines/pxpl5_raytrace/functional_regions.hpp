#pragma once
// Sampled simulation on pxpl5-raytrace (`rtsim run --sample K`, FrameSample::of_units): the
// master hands out only the regions simulated in detail; the others are cast here, before the
// simulation, by the same firmware (tasks::sample_region and LatticeRayTask, as a caster and the
// functional twin cast them), and each compositor starts the frame holding their samples in its
// bands. The back end then resamples a whole lattice, so the image is the same bytes.
#include <functional>
#include <vector>

#include "platform/machines/pxpl5_raytrace/nodes.hpp"

namespace rtsim::platform::pxpl5 {

/// The samples of every region `not_detailed(id)` names, by the compositor owning their rows, for
/// a run of one frame (the primary hits recorded as the casters record them). With `cast`
/// false (a --sample-error pilot, which wants only the estimate) the samples are blank: the
/// same positions, no rays.
std::vector<std::vector<Sample>> cast_functionally(const Setup& setup, MachineRun& run,
                                                   const std::function<bool(int)>& not_detailed,
                                                   bool cast = true);

}  // namespace rtsim::platform::pxpl5
