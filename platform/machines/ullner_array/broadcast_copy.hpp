#pragma once
// One hop of the host's broadcast (seed 000 L785-L797, L854): a port copies a record from the
// sender's memory (or the host) into a buffer the receiving processor has set aside, over the
// link between them. The copy needs the link, the sender's memory and the receiver's memory and
// its buffer at once (a port copy costs memory time at both ends), so sender and receiver agree
// its start: the sender offers the earliest time it can (b_transport's annotated delay), the
// receiver answers with the time the copy starts (no earlier than its buffer and memory are
// free) and, within the same call, handles the record and passes it on. The load runs in
// annotated time at the start of simulation, one record after the other: every resource is
// taken in record order, so the times are exact without a thread per hop.
#include <tlm_utils/simple_initiator_socket.h>

#include <cstdint>
#include <span>
#include <systemc>
#include <tlm>

#include "modules/extension_guard.hpp"
#include "modules/payload_pool.hpp"
#include "modules/sim_time.hpp"

namespace rtsim::platform::ullner_array {

/// How long the offered copy takes (serialisation and latency of the sender's link).
class BroadcastCopy : public tlm::tlm_extension<BroadcastCopy> {
 public:
  sc_core::sc_time duration;
  tlm::tlm_extension_base* clone() const override { return new BroadcastCopy(*this); }
  void copy_from(const tlm::tlm_extension_base& other) override {
    duration = static_cast<const BroadcastCopy&>(other).duration;
  }
};

/// Offers `record` through `socket` from `offered` for `duration`; returns when the copy starts.
template <class Socket>
sc_core::sc_time offer_record(Socket& socket, std::span<const std::uint32_t> record,
                              const sc_core::sc_time& offered, const sc_core::sc_time& duration) {
  const modules::PooledPayload pooled;  // one record a hop of the tree: no payload made each
  tlm::tlm_generic_payload& gp = *pooled;
  BroadcastCopy copy;
  copy.duration = duration;
  gp.set_extension(&copy);
  const modules::ClearExtensionOnExit<BroadcastCopy> guard(gp, copy);
  gp.set_command(tlm::TLM_WRITE_COMMAND);
  gp.set_address(0);
  gp.set_data_ptr(reinterpret_cast<unsigned char*>(const_cast<std::uint32_t*>(record.data())));
  gp.set_data_length(static_cast<unsigned>(record.size() * 4));
  gp.set_streaming_width(static_cast<unsigned>(record.size() * 4));
  gp.set_byte_enable_ptr(nullptr);
  gp.set_dmi_allowed(false);
  gp.set_response_status(tlm::TLM_INCOMPLETE_RESPONSE);
  const sc_core::sc_time now = modules::sim_now();
  sc_core::sc_time delay = offered > now ? offered - now : sc_core::SC_ZERO_TIME;
  socket->b_transport(gp, delay);
  if (gp.is_response_error())
    SC_REPORT_ERROR("rtsim/ullner-array", "a processor refused a broadcast record");
  return modules::plus(now, delay);
}

/// The array's ready line (a wired AND of every processor's flag; assumption: the thesis does
/// not say how the host learns that the scene is loaded, L795): it rises when the last processor
/// has sorted its polygons into its subvolume lists.
struct ReadyLine {
  int raised = 0;
  sc_core::sc_time at = sc_core::SC_ZERO_TIME;
  void raise(const sc_core::sc_time& t) {
    ++raised;
    at = std::max(at, t);
  }
};

}  // namespace rtsim::platform::ullner_array
