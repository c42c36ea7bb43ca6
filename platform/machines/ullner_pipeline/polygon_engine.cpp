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
                             const sc_core::sc_time& link_latency, const HeldPolygons& held,
                             modules::Link* recorded_link)
    : modules::ChainHop(name),
      index_(index),
      timing_(timing),
      serialisation_(serialisation),
      link_latency_(link_latency),
      held_(held),
      recorded_link_(recorded_link) {}

void PolygonEngine::b_transport(tlm::tlm_generic_payload& gp, sc_core::sc_time& delay) {
  // The description is in its input register `delay` from now; it accepts it an issue interval
  // after the previous one at the earliest (chain_timing.hpp: E).
  const sc_core::sc_time arrived = sc_core::sc_time_stamp() + delay;
  const sc_core::sc_time accepted =
      any_ ? std::max(arrived, plus(last_accept_, timing_.issue_interval)) : arrived;
  if (!any_) first_accept_ = accepted;
  last_accept_ = accepted;
  any_ = true;

  // The data: its polygon against the description it received (L702-L713), as it received it.
  DescriptionInFlight& d = carried(gp);
  for (DescriptionFault* f : faults_) f->apply(d);
  if (!dead_ && tasks::pass_ray_description(d.description, d.ray, (*held_.polygon)[index_],
                                            (*held_.identity)[index_])) {
    ++(*held_.overwrites)[index_];
    d.last_writer = index_;
  }
  delay = plus(accepted, timing_.hop_latency) - sc_core::sc_time_stamp();
  gp.set_response_status(tlm::TLM_OK_RESPONSE);
}

void PolygonEngine::pass_on(tlm::tlm_generic_payload& gp, sc_core::sc_time& delay) {
  if (next_) {
    // Its link starts when the description is ready, the next processor's register is free
    // (that processor accepted the previous one) and the link has carried the previous one.
    const sc_core::sc_time ready = sc_core::sc_time_stamp() + delay;
    // The next register must be free when the first bit reaches it, the link's latency after
    // the link starts. A description held by both the link and that register waits for the link.
    const sc_core::sc_time& reg_free = next_->register_free();
    const sc_core::sc_time reg_allows =
        next_->any_ && reg_free > link_latency_ ? reg_free - link_latency_ : sc_core::SC_ZERO_TIME;
    const sc_core::sc_time handed = reg_allows > link_free_ ? std::max(ready, reg_allows) : ready;
    const sc_core::sc_time start = std::max(handed, link_free_);
    waited_ += start - ready;
    link_free_ = plus(start, serialisation_);
    sc_core::sc_time arrives = plus(link_free_, link_latency_);
    // The kit link its output stands for counts the same message (its own wait from `handed`).
    if (recorded_link_ &&
        recorded_link_->transfer(tasks::RayDescription::kWireBits, handed) != arrives)
      SC_REPORT_ERROR("rtsim/ullner-pipeline", "a processor's link disagrees with its own");
    delay = arrives - sc_core::sc_time_stamp();
  }
  out->b_transport(gp, delay);
}

}  // namespace rtsim::platform::ullner_pipeline
