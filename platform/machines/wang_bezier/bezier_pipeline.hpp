#pragma once
// The ray/Bezier-patch pipeline of Wang, Lewis & Hung (seed 002 §3-§4, Fig. 10, L280-L288): stage
// 0 (PlaneGenerator and the first four-way split) and N identical loop stages (bezier.iterations,
// 10 in the paper), unrolled, no feedback. Each loop stage has the five substages of Table 4
// (L436-L441): SplitInHalf in u on 4 DSPs, in v on 8, HullClassification on 32 (one plane each),
// PatchCenter + PatchDistance on 16, and the Culler (an ASIC of at most 800 ns, L318, or the
// software routine of 3081 cycles, L432). TMS320C6701s at 6 ns a cycle (L436).
//
// Data flows through the stages: each job is stage 0's output carried through every loop stage
// (kernels::wang_stage0, wang_loop_stage, wang_output on the control net and ray the job
// brought); what leaves the last stage is the result the host reads.
//
// Timing by arithmetic (every block's work is data-independent, L193): a substage with k DSPs
// doing u units of c cycles takes ceil(u / k) c cycle times; the pipeline cycle is the slowest
// substage, one job enters per cycle, and a job leaves after (stage 0's substages + 5 N) cycles.
// One thread for the whole pipeline.
#include <tlm_utils/simple_initiator_socket.h>

#include <array>
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

namespace rtsim::platform::wang_bezier {

/// One kind of substage: its name, and the time it takes for a job.
struct Substage {
  std::string name;   ///< "split_u", ...: its parameters and statistics
  unsigned dsps = 0;  ///< 0: custom hardware (the Culler ASIC)
  std::uint64_t units = 0;
  std::uint64_t cycles = 0;
  sc_core::sc_time time;  ///< per job
};

/// A loop substage's statistics ("pipeline.split_u"): the first loop stage's, busy its time
/// each job.
struct SubstageStats : modules::StatGroup {
  SubstageStats(const modules::StatGroup& pipeline, const Substage& s)
      : modules::StatGroup(pipeline, s.name),
        dsps(*this, "dsps", "DSPs of the substage (0: custom hardware)",
             [d = s.dsps] { return d; }),
        time_per_job(*this, "time_per_job_s", "its time for one job",
                     [t = s.time] { return t.to_seconds(); }) {}
  modules::Busy busy{*this, "its time each job (the first loop stage's)"};
  modules::Computed dsps, time_per_job;
};

/// The statistics group "pipeline": busy a cycle a job, jobs, hits, in_flight_peak.
class BezierPipeline : public sc_core::sc_module, public modules::StatGroup {
 public:
  modules::MessageQueue<PatchJob> input;  ///< stage 0's input: one job
  tlm_utils::simple_initiator_socket<BezierPipeline> result_out;

  /// Its parameters under `pipeline`.
  static void declare_params(const modules::ParamDecls& pipeline);

  SC_HAS_PROCESS(BezierPipeline);
  /// `loop_stages`: N (bezier.iterations); `culler_key_bits`: its sort keys' width
  /// (bezier.culler_key_bits, as the twin's).
  BezierPipeline(sc_core::sc_module_name name, const params::ParamRegistry& registry,
                 int loop_stages, int culler_key_bits);

  int loop_stages() const { return loop_stages_; }
  const std::vector<Substage>& stage0() const { return stage0_; }
  const std::vector<Substage>& loop_substages() const { return loop_; }
  /// The slowest substage's time: one job a cycle.
  sc_core::sc_time cycle() const { return cycle_; }
  sc_core::sc_time latency() const { return latency_; }
  /// Pipeline cycles a job spends in each loop stage's Culler (1 unless it is pipelined).
  std::uint64_t culler_slots() const { return culler_slots_; }
  /// Faults in flight on its input (job_fault.hpp), before the simulation.
  void set_faults(std::vector<JobFault> faults) { faults_ = std::move(faults); }
  const std::vector<JobFault>& faults() const { return faults_; }

 private:
  void run();

  int loop_stages_;
  kernels::CullerConfig culler_;  ///< the ASIC's bitonic network or the software's sort
  std::vector<JobFault> faults_;
  std::vector<Substage> stage0_, loop_;
  sc_core::sc_time cycle_, latency_;
  /// A pipelined Culler's answer delay (zero otherwise) and the cycles it spans.
  sc_core::sc_time culler_delay_ = sc_core::SC_ZERO_TIME;
  std::uint64_t culler_slots_ = 1;
  modules::LocalClock clock_;
  std::vector<sc_core::sc_time> leaving_;  ///< when the jobs in flight leave, oldest first
  kernels::WangCounters counters_;
  modules::Busy busy_{*this, "its issue slots: a cycle a job (its utilisation)"};
  modules::Counter jobs_{*this, "jobs", "jobs taken"};
  modules::Counter hits_{*this, "hits", "jobs answered with a hit"};
  modules::Peak in_flight_peak_{*this, "in_flight_peak", "jobs in the pipeline at once"};
  std::vector<std::unique_ptr<SubstageStats>> substages_;
};

}  // namespace rtsim::platform::wang_bezier
