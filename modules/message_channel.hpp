#pragma once
// Message passing over TLM-2.0: the initiator sends a message object by b_transport with its
// local time offset as the annotated delay (loosely-timed style); the target queues it in a
// TimedFifo stamped with sc_time_stamp() + delay, blocking the caller while the FIFO is full
// (back-pressure), and returns the delay actually incurred.
#include <tlm_utils/simple_initiator_socket.h>
#include <tlm_utils/simple_target_socket.h>

#include <string>
#include <systemc>
#include <tlm>

#include "modules/timed_fifo.hpp"

namespace rtsim::modules {

/// The receiving end: a target socket in front of a bounded FIFO of T.
template <class T>
class MessageQueue : public sc_core::sc_module {
 public:
  tlm_utils::simple_target_socket<MessageQueue<T>> socket;
  TimedFifo<T> fifo;

  MessageQueue(sc_core::sc_module_name name, std::size_t depth)
      : sc_core::sc_module(name), socket("socket"), fifo(this->name(), depth) {
    socket.register_b_transport(this, &MessageQueue::b_transport);
  }

 private:
  void b_transport(tlm::tlm_generic_payload& gp, sc_core::sc_time& delay) {
    T* msg = reinterpret_cast<T*>(gp.get_data_ptr());
    const sc_core::sc_time stamp = fifo.put(*msg, sc_core::sc_time_stamp() + delay);
    const sc_core::sc_time now = sc_core::sc_time_stamp();
    delay = stamp > now ? stamp - now : sc_core::SC_ZERO_TIME;
    gp.set_response_status(tlm::TLM_OK_RESPONSE);
  }
};

/// Send `msg` through `socket` at absolute local time `t`; returns the absolute time it was
/// accepted (later than t if the receiving FIFO was full). `wire_bytes` is the size of the
/// message on the hardware link (for statistics and traces).
template <class Socket, class T>
sc_core::sc_time send_message(Socket& socket, T& msg, const sc_core::sc_time& t,
                              unsigned wire_bytes) {
  tlm::tlm_generic_payload gp;
  gp.set_command(tlm::TLM_WRITE_COMMAND);
  gp.set_address(0);
  gp.set_data_ptr(reinterpret_cast<unsigned char*>(&msg));
  gp.set_data_length(wire_bytes);
  gp.set_streaming_width(wire_bytes);
  gp.set_byte_enable_ptr(nullptr);
  gp.set_dmi_allowed(false);
  gp.set_response_status(tlm::TLM_INCOMPLETE_RESPONSE);
  const sc_core::sc_time now = sc_core::sc_time_stamp();
  sc_core::sc_time delay = t > now ? t - now : sc_core::SC_ZERO_TIME;
  socket->b_transport(gp, delay);
  return sc_core::sc_time_stamp() + delay;
}

}  // namespace rtsim::modules
