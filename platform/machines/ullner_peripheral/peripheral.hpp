#pragma once
// Ullner's ray tracing peripheral (seed 000 §2.3.2, Fig. 2-11): polygon fetch from the 20
// parameter memories, the intersection pipeline, closest-hit selection with validity bits, and
// (optionally) the grid auxiliary processor in front of it (L592-L596).
//
// The answer for each ray comes from the parameter memories: the search (brute force, or the
// auxiliary processor's grid walk) tests each candidate polygon on the words the fetch stage
// reads out of line k (parameter_memory_test.hpp), as the host loaded them; the functional twin
// only checks the image afterwards. The time is computed from what the hardware does for it:
//  * brute force: every polygon streams through the pipe, one per intersect interval
//    (L482, L588); shadow rays stream them all too unless peripheral.shadow_early_exit;
//  * grid: the auxiliary processor steps t_d per subvolume visited (L654) and feeds the pipe
//    the polygon addresses of each, through one extra indirection stage (L596).
// The result leaves the pipe `latency` after its last polygon entered; the next ray's polygons
// follow the previous ray's without a gap (the pipe is never flushed, L522-L528).
#include <tlm_utils/simple_initiator_socket.h>

#include <memory>
#include <optional>
#include <systemc>

#include "firmware/tasks/shade_task.hpp"
#include "firmware/tracer.hpp"
#include "modules/latency_probe.hpp"
#include "modules/link.hpp"
#include "modules/local_clock.hpp"
#include "modules/memory.hpp"
#include "modules/message_channel.hpp"
#include "modules/module_params.hpp"
#include "modules/pipelined_unit.hpp"
#include "platform/machines/machine_run.hpp"
#include "platform/machines/machine_trace.hpp"
#include "platform/machines/ullner_peripheral/messages.hpp"
#include "platform/machines/ullner_peripheral/parameter_memory_test.hpp"
#include "platform/machines/ullner_peripheral/peripheral_settings.hpp"

namespace rtsim::platform::ullner {

class Peripheral : public sc_core::sc_module {
 public:
  modules::MessageQueue<RayRequest> rays;  ///< the ray queue (host -> peripheral)
  /// The 20 parameter memories (seed 000 L544): polygon k's 20 words at line k, loaded by the
  /// host through the dual-ported load path, read a whole line per cycle by the fetch stage.
  modules::Memory parameters;
  tlm_utils::simple_initiator_socket<Peripheral> result_out;  ///< to the host's result queue

  /// Its parameters, under `peripheral` (the pipeline, the grid auxiliary processor, the
  /// lighting devices, the parameter memories).
  static void declare_params(const modules::ParamDecls& peripheral);
  /// Their values, read once (the modelling space is the scene's: left empty); the search's
  /// are read_search_settings'.
  static PeripheralSettings read_settings(const modules::ModuleParams& peripheral);
  /// Only what the functional twin needs (the parameters the image depends on): the grid and
  /// the memories' capacity. The other fields keep their defaults.
  static PeripheralSettings read_search_settings(const modules::ModuleParams& peripheral);

  SC_HAS_PROCESS(Peripheral);
  /// In `run`: the twin's geometry is the host's copy of the scene, and the twin's search over
  /// it is the grid the auxiliary processor walks (shared, not built twice; the candidates'
  /// parameters are read from `parameters`).
  Peripheral(sc_core::sc_module_name name, MachineRun& run, const tasks::ShadeTask& shade,
             const PeripheralSettings& config);

  const modules::PipelinedUnit& pipeline() const { return pipe_; }

  /// What it served, under its own name ("peripheral"): the machine's per-ray figures (Ullner's
  /// t_r, n_i, d_r) are ratios of these.
  struct Served : modules::StatGroup {
    using modules::StatGroup::StatGroup;
    modules::Counter rays{*this, "rays_served", "rays answered"};
    modules::Duration service{*this, "service_time_s",
                              "the sum over rays of the time from starting a ray to its answer"};
    modules::Counter primary_hits{*this, "primary_hits", "primary rays that hit a polygon"};
    modules::Scalar primary_travel{
        *this, "primary_travel",
        "the sum of primary rays' hit distances from the modelling space (scene units)",
        modules::StatUnit::ratio};
  };
  const Served& served() const { return served_; }

 private:
  /// The grid auxiliary processor's statistics ("peripheral.aux").
  struct AuxProcessor : modules::StatGroup {
    using modules::StatGroup::StatGroup;
    modules::Busy busy{*this, "time walking subvolumes and feeding addresses (its utilisation)"};
    modules::Counter dda_steps{*this, "dda_steps", "steps of the 3D-DDA walk"};
    modules::Counter subvolumes_visited{*this, "subvolumes_visited", "subvolumes walked through"};
  };
  void run();

  ParameterMemoryTest memory_test_;  ///< the pipe's test of a polygon, on `parameters`' words
  std::unique_ptr<Tracer> search_;   ///< the grid walk or brute force, testing with memory_test_
  const tasks::ShadeTask& shade_;
  std::uint64_t polygons_;
  PeripheralSettings config_;
  TraceCounters& counters_;
  MachineTrace& trace_;
  modules::LocalClock clock_;
  modules::PipelinedUnit pipe_;
  /// `--latency-probe`: the stages a ray meets here, in order (aux only with the grid).
  modules::LatencyProbe& probe_;
  int probe_ray_queue_ = -1, probe_aux_ = -1, probe_memories_ = -1, probe_pipeline_ = -1;
  modules::Link result_link_;  ///< the answers into the host's result queue
  int probe_result_link_ = -1;
  sc_core::sc_time aux_free_ = sc_core::SC_ZERO_TIME;
  std::optional<AuxProcessor> aux_;  ///< with the grid
  Served served_;
  modules::Computed polygons_stat_{parameters, "polygons", modules::StatUnit::count,
                                   "polygons loaded (a line each)", [this] { return polygons_; }};
};

}  // namespace rtsim::platform::ullner
