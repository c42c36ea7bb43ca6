#pragma once
// What every PERT and its processors are built from: the run (MachineRun: parameters, scene,
// twin, frame, trace), what the machine built once for all the rings (the shell tree, the data
// sets, the record sizes, the PrimProcessor's test costs, the buses) and the two things the
// processors share as they work: the frame's progress (termination detection) and the latency
// probe.
#include <cstdint>
#include <vector>

#include "firmware/accel/gaudet_data_sets.hpp"
#include "firmware/cost.hpp"
#include "firmware/shading/camera.hpp"
#include "platform/machines/gaudet_pert/broadcast_processor.hpp"
#include "platform/machines/gaudet_pert/data_sets.hpp"
#include "platform/machines/gaudet_pert/frame_progress.hpp"
#include "platform/machines/gaudet_pert/ray_probe.hpp"
#include "platform/machines/machine_run.hpp"

namespace rtsim::platform::gaudet {

struct PertContext {
  MachineRun& run;
  int pert_count;
  const shading::PinholeCamera& camera;  ///< the ShadeProcessors' vision rays
  const accel::ShellTree& tree;
  const accel::RecordWords& words;
  const PertDataSets& sets;
  const std::vector<Cost>& test_cost;  ///< the PrimProcessor's test cost per shape
  /// Shade, Shell and Prim broadcast buses; empty: direct memory.
  std::vector<BroadcastProcessor*> buses;
  FrameProgress& progress;
  RayProbe& probe;
  /// process = queue: the processors' programs run on the machine's event queue.
  bool on_queue = false;
};

}  // namespace rtsim::platform::gaudet
