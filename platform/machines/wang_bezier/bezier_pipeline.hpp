#pragma once
// The ray/Bezier-patch pipeline of Wang, Lewis & Hung (seed 002 §3-§4, Fig. 10, L280-L288): stage
// 0 (PlaneGenerator and the first four-way split) and N identical loop stages (bezier.iterations,
// 10 in the paper), unrolled, no feedback. Each loop stage has the five substages of Table 4
// (L436-L441): SplitInHalf in u on 4 DSPs, in v on 8, HullClassification on 32 (one plane each),
// PatchCenter + PatchDistance on 16, and the Culler (an ASIC of at most 800 ns, L318, or the
// software routine of 3081 cycles, L432). TMS320C6701s at 6 ns a cycle (L436).
//
// Stage by stage (pipeline_stage.hpp, substage.hpp): stage 0's substages and each loop stage's
// five are modules; a job enters stage 0 as a transaction from the pipeline's input queue, passes
// every substage as a transaction carrying its payload (job_in_flight.hpp), each substage
// computing its part on what it received, and leaves the last into the pipeline's output, which
// sends the host the result (kernels::wang_output on what left). The timing is the substages':
// each takes a job when it is free and hands it on when the next buffer has room, so a slower
// substage sets the cycle and back-pressures the ones before it.
//
// What it measures: jobs that left while the pipeline was kept full (each had waited at the
// input for stage 0), and the time between them and their predecessors leaving: the pipeline's
// steady-state throughput (W1, L437); each job's transit from stage 0 to the output.
#include <tlm_utils/simple_initiator_socket.h>
#include <tlm_utils/simple_target_socket.h>

#include <memory>
#include <string>
#include <systemc>
#include <vector>

#include "modules/local_clock.hpp"
#include "modules/message_channel.hpp"
#include "modules/module_params.hpp"
#include "modules/statistics.hpp"
#include "platform/machines/wang_bezier/job_fault.hpp"
#include "platform/machines/wang_bezier/messages.hpp"
#include "platform/machines/wang_bezier/pipeline_stage.hpp"

namespace rtsim::platform::wang_bezier {

/// The statistics group "pipeline": busy while stage 0 cannot take a job, jobs, hits,
/// in_flight_peak, kept_full, kept_full_s, transit.
class BezierPipeline : public sc_core::sc_module, public modules::StatGroup {
 public:
  modules::MessageQueue<PatchJob> input;  ///< stage 0's input: one job
  tlm_utils::simple_initiator_socket<BezierPipeline> result_out;

  /// Its parameters under `pipeline`.
  static void declare_params(const modules::ParamDecls& pipeline);

  SC_HAS_PROCESS(BezierPipeline);
  /// `loop_stages`: N (bezier.iterations); `culler_key_bits`: its sort keys' width
  /// (bezier.culler_key_bits); `arithmetic`: bezier.arithmetic (all as the twin's).
  BezierPipeline(sc_core::sc_module_name name, const params::ParamRegistry& registry,
                 int loop_stages, int culler_key_bits, const kernels::WangArithmetic& arithmetic);

  int loop_stages() const { return static_cast<int>(loops_.size()); }
  const PipelineStage& stage0() const { return *stage0_; }
  /// Loop stage 1's substages (all loop stages are alike).
  const PipelineStage& first_loop() const { return *loops_.front(); }
  /// Every substage, in the order a job passes them.
  const std::vector<Substage*>& substages() const { return chain_; }
  /// Faults in flight on its input and its loop stages' (job_fault.hpp), before the
  /// simulation.
  void set_faults(std::vector<JobFault> faults);
  const std::vector<JobFault>& faults() const { return faults_; }

  /// Jobs that left while it was kept full, and the time between them and the jobs before
  /// them leaving (their sum): its steady-state cycle, measured.
  std::uint64_t kept_full() const { return kept_full_.value(); }
  const sc_core::sc_time& kept_full_time() const { return kept_full_time_.value(); }
  /// The shortest transit through it (a job that never waited inside), zero before any job.
  const sc_core::sc_time& shortest_transit() const { return shortest_transit_; }

 private:
  void run();
  /// The pipeline's output: the last substage hands a job here; its result goes to the host.
  void leave(tlm::tlm_generic_payload& gp, sc_core::sc_time& delay);

  kernels::WangArithmetic arithmetic_;
  std::vector<JobFault> faults_;
  JobInFlight flight_;
  std::unique_ptr<PipelineStage> stage0_;
  std::vector<std::unique_ptr<PipelineStage>> loops_;
  std::vector<Substage*> chain_;
  tlm_utils::simple_initiator_socket<BezierPipeline> entry_{"entry"};
  tlm_utils::simple_target_socket<BezierPipeline> exit_{"exit"};
  modules::LocalClock clock_;
  std::vector<sc_core::sc_time> leaving_;  ///< when the jobs in flight leave, oldest first
  sc_core::sc_time last_left_ = sc_core::SC_ZERO_TIME;
  sc_core::sc_time shortest_transit_ = sc_core::SC_ZERO_TIME;
  kernels::WangCounters counters_;
  modules::Busy busy_{*this, "stage 0 holding a job (it could take no other): its utilisation"};
  modules::Counter jobs_{*this, "jobs", "jobs taken"};
  modules::Counter hits_{*this, "hits", "jobs answered with a hit"};
  modules::Peak in_flight_peak_{*this, "in_flight_peak", "jobs in the pipeline at once"};
  modules::Counter kept_full_{*this, "kept_full",
                              "jobs that left while it was kept full (each had waited at the "
                              "input for stage 0)"};
  modules::Duration kept_full_time_{*this, "kept_full_s",
                                    "time between those jobs leaving and the jobs before them"};
  modules::Distribution transit_{*this, "transit", "a job's time from stage 0 to the output"};
};

}  // namespace rtsim::platform::wang_bezier
