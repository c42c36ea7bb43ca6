#include "platform/machines/wang_bezier/substage.hpp"

#include <algorithm>
#include <bit>

#include "modules/message_channel.hpp"
#include "modules/sim_time.hpp"

namespace rtsim::platform::wang_bezier {

using modules::plus;

Substage::Substage(const sc_core::sc_module_name& name, SubstageWork work, const Pool& pool,
                   const Timing& timing, std::size_t buffer_depth,
                   const kernels::CullerConfig& culler, const modules::ModuleParams* link)
    : sc_core::sc_module(name),
      modules::StatGroup(sc_core::sc_module::name()),
      in("in"),
      out("out"),
      work_(work),
      pool_(pool),
      timing_(timing),
      culler_(culler),
      depth_(std::max<std::size_t>(1, buffer_depth)),
      taken_(std::bit_ceil(depth_), sc_core::SC_ZERO_TIME),
      ring_mask_(taken_.size() - 1) {
  in.bind(*this);
  out.bind(*this);
  if (link) link_ = std::make_unique<modules::Link>(stat_path() + ".link", *link);
  if (work_ == SubstageWork::kCull)
    kept_ = std::make_unique<modules::Counter>(*this, "kept",
                                               "candidates it kept (at most 4 a job, L256)");
}

sc_core::sc_time Substage::taken_ago(std::size_t ago) const {
  if (ago == 0 || ago > count_ || ago > depth_) return sc_core::SC_ZERO_TIME;
  return taken_[(count_ - ago) & ring_mask_];
}

void Substage::compute(JobInFlight& f) {
  using namespace kernels;
  switch (work_) {
    case SubstageWork::kPlanesSplitU:
      f.w = wang_planes(f.job.net, f.job.o, f.job.d, counters_);
      wang_split_u(f.w, f.work);
      return;
    case SubstageWork::kSplitVOutput:
      wang_split_v(f.w, f.work, counters_);
      wang_stage0_output(f.w, f.work);
      return;
    case SubstageWork::kSubdivider:
      f.w = wang_planes(f.job.net, f.job.o, f.job.d, counters_);
      wang_split_u(f.w, f.work);
      wang_split_v(f.w, f.work, counters_);
      wang_stage0_output(f.w, f.work);
      return;
    case SubstageWork::kSplitU:
      wang_split_u(f.w, f.work);
      return;
    case SubstageWork::kSplitV:
      wang_split_v(f.w, f.work, counters_);
      return;
    case SubstageWork::kHull:
      wang_hull(f.w, f.work, counters_);
      return;
    case SubstageWork::kCenterDistance:
      wang_center_distance(f.w, f.work);
      return;
    case SubstageWork::kCull:
      wang_cull(f.w, f.work, counters_, culler_);
      *kept_ += static_cast<std::uint64_t>(f.w.n1);
      return;
  }
}

void Substage::b_transport(tlm::tlm_generic_payload& gp, sc_core::sc_time& delay) {
  JobInFlight& f = *gp.get_extension<modules::MessageExtension<JobInFlight>>()->message();
  // S(j): the job is in its input buffer `delay` from now; it takes it once free.
  const sc_core::sc_time start = std::max(sc_core::sc_time_stamp() + delay, free_);
  taken_[count_ & ring_mask_] = start;
  ++count_;
  ++jobs_;
  for (JobFault* fault : faults_) fault->apply(f.w);  // as it arrived
  if (!dead_) compute(f);
  busy_.record(start, timing_.work);
  // D(j), then O(j): the next buffer has room once the next substage took job j - depth.
  const sc_core::sc_time ready = plus(start, timing_.latency);
  sc_core::sc_time handed = ready;
  if (next_) handed = std::max(ready, next_->taken_ago(depth_));
  blocked_ += handed - ready;
  free_ = std::max(plus(start, timing_.issue), handed - (timing_.latency - timing_.issue));
  // The same transaction goes on, carrying what the next substage reads, over its link if it
  // has one.
  const std::uint64_t words = words_after(work_);
  const unsigned bytes = static_cast<unsigned>(4 * words);
  gp.set_data_length(bytes);
  gp.set_streaming_width(bytes);
  const sc_core::sc_time arrives = link_ ? link_->transfer(32 * words, handed) : handed;
  delay = arrives - sc_core::sc_time_stamp();
  out->b_transport(gp, delay);
}

}  // namespace rtsim::platform::wang_bezier
