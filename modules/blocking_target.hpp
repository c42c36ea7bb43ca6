#pragma once
// The forward interface of a target that serves blocking transport only (b_transport: the one
// call the kit's loosely timed modules make). Non-blocking transport, DMI and debug access are
// declined here, once. A module that derives from it binds a plain tlm::tlm_target_socket to
// itself instead of using a simple_target_socket, whose machinery for converting between
// blocking and non-blocking calls costs three sc_events a socket, each an entry in SystemC's
// name tables: a 32 x 32 ullner-array has 6,000 queues and memories, and their events were
// 0.3 G of the 0.75 G instructions building its processors took. Used by MessageQueue
// (modules/message_channel.hpp), Memory (modules/memory.hpp) and ChainHop (modules/chain_hop.hpp).
#include <systemc>
#include <tlm>

namespace rtsim::modules {

class BlockingTarget : public tlm::tlm_fw_transport_if<> {
 private:
  tlm::tlm_sync_enum nb_transport_fw(tlm::tlm_generic_payload&, tlm::tlm_phase&,
                                     sc_core::sc_time&) override {
    return tlm::TLM_COMPLETED;
  }
  bool get_direct_mem_ptr(tlm::tlm_generic_payload&, tlm::tlm_dmi&) override { return false; }
  unsigned int transport_dbg(tlm::tlm_generic_payload&) override { return 0; }
};

}  // namespace rtsim::modules
