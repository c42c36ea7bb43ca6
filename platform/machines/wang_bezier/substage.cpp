#include "platform/machines/wang_bezier/substage.hpp"

#include <algorithm>
#include <bit>
#include <type_traits>

#include "modules/message_channel.hpp"
#include "modules/sim_time.hpp"

namespace rtsim::platform::wang_bezier {

using modules::plus;

Substage::Substage(const sc_core::sc_module_name& name, SubstageWork work, const Pool& pool,
                   const Timing& timing, const Shared& shared)
    : modules::ChainHop(name),
      modules::StatGroup(sc_core::sc_module::name()),
      work_(work),
      pool_(pool),
      timing_(timing),
      culler_(shared.culler),
      arithmetic_(shared.arithmetic),
      depth_(std::max<std::size_t>(1, shared.buffer_depth)),
      taken_(std::bit_ceil(depth_), sc_core::SC_ZERO_TIME),
      ring_mask_(taken_.size() - 1) {
  if (shared.link) link_ = std::make_unique<modules::Link>(stat_path() + ".link", *shared.link);
  if (work_ == SubstageWork::kCull)
    kept_ = std::make_unique<modules::Counter>(*this, "kept",
                                               "candidates it kept (at most 4 a job, L256)");
}

sc_core::sc_time Substage::taken_ago(std::size_t ago) const {
  if (ago == 0 || ago > count_ || ago > depth_) return sc_core::SC_ZERO_TIME;
  return taken_[(count_ - ago) & ring_mask_];
}

template <typename T>
void Substage::compute(const PatchJob& in, kernels::WangJob<T>& w,
                       kernels::WangStageWork<T>& work) {
  using namespace kernels;
  const FixedWords* words = arithmetic_.words();
  // Stage 0 takes the job's single-precision words into the arithmetic.
  const auto planes = [&] {
    if constexpr (std::is_same_v<T, float>)
      w = wang_planes(in.net, in.o, in.d, counters_, words);
    else
      w = wang_planes(convert_net<T>(in.net), Vec3T<T>(in.o), Vec3T<T>(in.d), counters_, words);
  };
  switch (work_) {
    case SubstageWork::kPlanesSplitU:
      planes();
      wang_split_u(w, work, words);
      return;
    case SubstageWork::kSplitVOutput:
      wang_split_v(w, work, counters_, words);
      wang_stage0_output(w, work);
      return;
    case SubstageWork::kSubdivider:
      planes();
      wang_split_u(w, work, words);
      wang_split_v(w, work, counters_, words);
      wang_stage0_output(w, work);
      return;
    case SubstageWork::kSplitU:
      wang_split_u(w, work, words);
      return;
    case SubstageWork::kSplitV:
      wang_split_v(w, work, counters_, words);
      return;
    case SubstageWork::kHull:
      wang_hull(w, work, counters_);
      return;
    case SubstageWork::kCenterDistance:
      wang_center_distance(w, work, words);
      return;
    case SubstageWork::kCull:
      wang_cull(w, work, counters_, culler_);
      *kept_ += static_cast<std::uint64_t>(w.n1);
      return;
  }
}

void Substage::b_transport(tlm::tlm_generic_payload& gp, sc_core::sc_time& delay) {
  JobInFlight& f = *gp.get_extension<modules::MessageExtension<JobInFlight>>()->message();
  // S(j): the job is in its input buffer `delay` from now; it takes it once free.
  const sc_core::sc_time start = std::max(modules::sim_now() + delay, free_);
  taken_[count_ & ring_mask_] = start;
  ++count_;
  ++jobs_;
  // The data, in the pipeline's arithmetic, as it arrived.
  if (arithmetic_.wide()) {
    for (JobFault* fault : faults_) fault->apply(f.wide);
    if (!dead_) compute(f.job, f.wide, f.wide_work);
  } else {
    for (JobFault* fault : faults_) fault->apply(f.w);
    if (!dead_) compute(f.job, f.w, f.work);
  }
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
  delay = arrives - modules::sim_now();
  out->b_transport(gp, delay);
}

}  // namespace rtsim::platform::wang_bezier
