#pragma once
// A module on a chain of loosely timed hops (the ray-tracing pipeline's polygon processors, the
// Bezier pipeline's substages): a transaction reaches it through `in` (b_transport, the one
// call a hop implements) and it passes the transaction on through `out`. The rest of TLM's
// forward (modules/blocking_target.hpp) and backward interfaces (non-blocking transport, DMI,
// debug) are declined.
#include <systemc>
#include <tlm>

#include "modules/blocking_target.hpp"

namespace rtsim::modules {

class ChainHop : public sc_core::sc_module,
                 public BlockingTarget,
                 public tlm::tlm_bw_transport_if<> {
 public:
  tlm::tlm_target_socket<> in;      ///< from the hop before (or the chain's entry)
  tlm::tlm_initiator_socket<> out;  ///< to the hop after (or the chain's far end)

  explicit ChainHop(const sc_core::sc_module_name& name)
      : sc_core::sc_module(name), in("in"), out("out") {
    in.bind(*this);
    out.bind(*this);
  }

 private:
  tlm::tlm_sync_enum nb_transport_bw(tlm::tlm_generic_payload&, tlm::tlm_phase&,
                                     sc_core::sc_time&) override {
    return tlm::TLM_COMPLETED;
  }
  void invalidate_direct_mem_ptr(sc_dt::uint64, sc_dt::uint64) override {}
};

}  // namespace rtsim::modules
