#pragma once
// One substage of the Bezier pipeline as a module (Table 4, L436-L441; stage 0, L284): a DSP
// pool (or the Culler ASIC) that receives a job as a TLM transaction on its input socket, does
// its part of the stage with the firmware's blocks (kernels::wang_split_u, ...) on the payload it
// received, and hands the payload on through its output socket into the next substage's input
// buffer of `buffer_depth` jobs (pipeline.buffer_depth; the paper gives none, note 002 §4).
//
// Its timing is its own state's and its neighbour's, job by job (j):
//     takes      S(j) = max(A(j), F(j-1))            A: the job is in its input buffer
//     ready      D(j) = S(j) + latency
//     hands on   O(j) = max(D(j), S'(j - depth))     S': the next substage's; its buffer has room
//     free       F(j) = max(S(j) + issue, O(j) - (latency - issue))
// A DSP pool doing `units` calls of `cycles` cycles on `dsps` DSPs works ceil(units / dsps)
// rounds (a pool smaller than its work takes several). Not pipelined, issue = latency = its work
// (a job held until it is handed on: a slower substage back-pressures the ones before it); the
// pipelined Culler takes a job every compare stage (issue = delay / 10) and a stalled output
// stalls it whole. With pipeline.advance = cycle every substage holds a job for whole pipeline
// cycles (issue = the cycle, latency rounded up to cycles): the lock-step pipeline of the paper's
// "pipeline cycle" (L437).
//
// With pipeline.interconnect = link its output is a kit Link (pipeline.link.*, statistics at
// NAME.link): the job leaves at O(j) when the link is free, occupies it for its words'
// serialisation and arrives at the next buffer the link's latency after its last bit.
//
// The pipeline's thread carries each job into stage 0 (loosely timed: no substage waits in
// simulated time; each computes its times from its state and the next one's S').
#include <cstdint>
#include <memory>
#include <string>
#include <systemc>
#include <tlm>
#include <vector>

#include "firmware/kernels/bezier_wang.hpp"
#include "modules/chain_hop.hpp"
#include "modules/link.hpp"
#include "modules/module_params.hpp"
#include "modules/statistics.hpp"
#include "platform/machines/wang_bezier/job_fault.hpp"
#include "platform/machines/wang_bezier/job_in_flight.hpp"

namespace rtsim::platform::wang_bezier {

/// `in`: from the previous substage (or the pipeline's input); `out`: to the next (or the
/// pipeline's output).
class Substage : public modules::ChainHop, public modules::StatGroup {
 public:
  /// Its resource: `dsps` DSPs (0: custom hardware) doing `units` calls of `cycles` a job.
  struct Pool {
    unsigned dsps = 0;
    std::uint64_t units = 0;
    std::uint64_t cycles = 0;
  };
  struct Timing {
    sc_core::sc_time work;     ///< its pool's (or the Culler's) time on one job
    sc_core::sc_time issue;    ///< between two jobs it takes
    sc_core::sc_time latency;  ///< from taking a job to handing it on, unblocked
  };

  /// What every substage of the pipeline shares.
  struct Shared {
    std::size_t buffer_depth = 1;                 ///< pipeline.buffer_depth
    kernels::CullerConfig culler;                 ///< how a Culler sorts
    kernels::WangArithmetic arithmetic;           ///< bezier.arithmetic, as the twin's
    const modules::ModuleParams* link = nullptr;  ///< pipeline.link, or none (instant)
  };

  Substage(const sc_core::sc_module_name& name, SubstageWork work, const Pool& pool,
           const Timing& timing, const Shared& shared);

  /// Faults: `fault` corrupts every job entering it; a dead substage passes every job on
  /// unchanged (it computes nothing; its timing stays).
  void add_fault(JobFault& fault) { faults_.push_back(&fault); }
  void set_dead(bool dead) { dead_ = dead; }

  /// The substage after this one (its input buffer), at elaboration; none for the last.
  void set_next(const Substage* next) { next_ = next; }
  /// When it took the job `ago` jobs back (1: the last one); zero if it has taken fewer.
  sc_core::sc_time taken_ago(std::size_t ago) const;
  /// When it can take its next job.
  const sc_core::sc_time& free() const { return free_; }

  SubstageWork work() const { return work_; }
  const Pool& pool() const { return pool_; }
  const Timing& timing() const { return timing_; }

 private:
  void b_transport(tlm::tlm_generic_payload& gp, sc_core::sc_time& delay) override;
  /// Its work on the job in the pipeline's arithmetic: `w` and `work` are the job's float or
  /// wide (double) copies.
  template <typename T>
  void compute(const PatchJob& in, kernels::WangJob<T>& w, kernels::WangStageWork<T>& work);

  SubstageWork work_;
  Pool pool_;
  Timing timing_;
  kernels::CullerConfig culler_;
  kernels::WangArithmetic arithmetic_;
  const Substage* next_ = nullptr;
  std::vector<JobFault*> faults_;
  bool dead_ = false;
  std::size_t depth_;
  /// Its last `depth_` take times (the previous substage's buffer room), a ring of a power of
  /// two at least that long.
  std::vector<sc_core::sc_time> taken_;
  std::uint64_t ring_mask_;
  std::uint64_t count_ = 0;
  sc_core::sc_time free_ = sc_core::SC_ZERO_TIME;
  kernels::WangCounters counters_;
  modules::Busy busy_{*this, "its DSP pool's (or the Culler's) work on each job"};
  modules::Counter jobs_{*this, "jobs", "jobs it took"};
  modules::Duration blocked_{*this, "blocked_s",
                             "time finished jobs waited for room in the next buffer"};
  modules::Computed dsps_{*this, "dsps", modules::StatUnit::count,
                          "DSPs of the substage (0: custom hardware)",
                          [this] { return pool_.dsps; }};
  modules::Computed time_per_job_{*this, "time_per_job_s", modules::StatUnit::seconds,
                                  "its work on one job",
                                  [this] { return timing_.work.to_seconds(); }};
  /// The Culler's survivors (candidate survival, note 002 §4.7).
  std::unique_ptr<modules::Counter> kept_;
  std::unique_ptr<modules::Link> link_;
};

}  // namespace rtsim::platform::wang_bezier
