#include "platform/machines/ullner_pipeline/polygon_engine.hpp"

#include <algorithm>

#include "modules/message_channel.hpp"
#include "modules/sim_time.hpp"

namespace rtsim::platform::ullner_pipeline {

using modules::plus;

namespace {
DescriptionInFlight& carried(tlm::tlm_generic_payload& gp) {
  return *gp.get_extension<modules::MessageExtension<DescriptionInFlight>>()->message();
}
}  // namespace

PolygonEngine::PolygonEngine(const sc_core::sc_module_name& name, std::uint64_t index,
                             const EngineTiming& timing, const sc_core::sc_time& serialisation,
                             const sc_core::sc_time& link_latency, const HeldPolygons& held)
    : modules::ChainHop(name),
      load_in("load_in"),
      load_out("load_out"),
      index_(index),
      timing_(timing),
      serialisation_(serialisation),
      link_latency_(link_latency),
      held_(held) {
  load_in.register_b_transport(this, &PolygonEngine::load_transport);
}

void PolygonEngine::load_transport(tlm::tlm_generic_payload& gp, sc_core::sc_time& delay) {
  // "This first processor passes its current polygon to the second processor before accepting
  // the new polygon. Every processor in the pipeline behaves in a similar manner" (L717-L719):
  // its link carries its polygon on (one polygon time), then it takes the new one in its place.
  auto* ext = gp.get_extension<modules::MessageExtension<LoadWave>>();
  if (!ext || !ext->message() || !registers_) {
    gp.set_response_status(tlm::TLM_GENERIC_ERROR_RESPONSE);
    return;
  }
  LoadWave& w = *ext->message();
  const sc_core::sc_time start = std::max(w.at, load_link_free_);
  load_link_free_ = plus(start, polygon_time_);
  w.accepted = load_link_free_;
  w.at = plus(load_link_free_, link_latency_);  // where its previous polygon arrives next
  registers_->exchange(index_, w.description);
  (void)delay;  // the time travels in the wave (LoadWave::at)
  gp.set_response_status(tlm::TLM_OK_RESPONSE);
}

void PolygonEngine::shift_on(tlm::tlm_generic_payload& gp) {
  sc_core::sc_time none = sc_core::SC_ZERO_TIME;
  load_out->b_transport(gp, none);
}

sc_core::sc_time PolygonEngine::accept_bound() const {
  if (!any_) return sc_core::SC_ZERO_TIME;
  return std::max(plus(last_accept_, timing_.issue_interval), last_start_);
}

void PolygonEngine::b_transport(tlm::tlm_generic_payload& gp, sc_core::sc_time& delay) {
  // The description is in its input register at its `at`; it accepts it an issue interval after
  // the previous one at the earliest, and once it has started passing that one on (it holds one,
  // chain_timing.hpp: E).
  DescriptionInFlight& d = carried(gp);
  const sc_core::sc_time accepted = std::max(d.at, accept_bound());
  if (!any_) first_accept_ = accepted;
  last_accept_ = accepted;
  any_ = true;
  if (timeline_) timeline_->add(accepted, timing_.issue_interval);

  // The data: its polygon against the description it received (L702-L713), as it received it.
  for (DescriptionFault* f : faults_) f->apply(d);
  if (!dead_ && tasks::pass_ray_description(d.description, d.ray, (*held_.polygon)[index_],
                                            (*held_.identity)[index_])) {
    ++(*held_.overwrites)[index_];
    d.last_writer = index_;
  }
  d.at = plus(accepted, timing_.hop_latency);
  (void)delay;  // the time travels in the description (DescriptionInFlight::at)
  gp.set_response_status(tlm::TLM_OK_RESPONSE);
}

void PolygonEngine::start(tlm::tlm_generic_payload& gp) {
  DescriptionInFlight& d = carried(gp);
  const sc_core::sc_time ready = d.at;
  sc_core::sc_time start;
  if (next_) {
    // Its link starts when the description is ready, the next processor's register is free
    // (that processor accepted the previous one) and the link has carried the previous one.
    // The next register must be free when the first bit reaches it, the link's latency after
    // the link starts. A description held by both the link and that register waits for the link.
    const sc_core::sc_time& reg_free = next_->register_free();
    const sc_core::sc_time reg_allows =
        next_->any_ && reg_free > link_latency_ ? reg_free - link_latency_ : sc_core::SC_ZERO_TIME;
    const sc_core::sc_time handed = reg_allows > link_free_ ? std::max(ready, reg_allows) : ready;
    start = std::max(handed, link_free_);
    if (index_ == 0) d.first_handed = handed;  // the first link counts it from here (leave)
    d.at = plus(plus(start, serialisation_), link_latency_);
  } else {
    // The last: a slot of the host's result queue must be free when its link starts.
    const sc_core::sc_time unheld = std::max(ready, link_free_);
    start = std::max(unheld, far_end_room_);
    far_end_held_ += start - unheld;
    d.at = start;
  }
  waited_ += start - ready;
  last_start_ = start;
  link_free_ = plus(start, serialisation_);
}

void PolygonEngine::hand_on(tlm::tlm_generic_payload& gp) {
  sc_core::sc_time none = sc_core::SC_ZERO_TIME;
  out->b_transport(gp, none);
}

}  // namespace rtsim::platform::ullner_pipeline
