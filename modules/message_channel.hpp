#pragma once
// Message passing over TLM-2.0: the initiator sends a typed message by b_transport with its
// local time offset as the annotated delay (loosely-timed style); the target queues it in a
// TimedFifo stamped with sc_time_stamp() + delay, blocking the caller while the FIFO is full
// (back-pressure), and returns the delay actually incurred.
//
// The message travels as a typed TLM extension (MessageExtension<T>), never as bytes cast back
// to a type; the payload's data length is the message's size on the hardware, ceil(bits / 8),
// which the Link in front of the queue (modules/link.hpp) charges. Used by every machine.
#include <tlm_utils/simple_initiator_socket.h>

#include <cstdint>
#include <memory>
#include <string>
#include <systemc>
#include <tlm>
#include <vector>

#include "modules/blocking_target.hpp"
#include "modules/payload_pool.hpp"
#include "modules/sim_time.hpp"
#include "modules/timed_fifo.hpp"

namespace rtsim::modules {

/// A message of type T riding on a generic payload.
template <class T>
class MessageExtension : public tlm::tlm_extension<MessageExtension<T>> {
 public:
  explicit MessageExtension(T* message = nullptr, std::uint64_t bits = 0)
      : message_(message), bits_(bits) {}
  T* message() const { return message_; }
  /// Its size on the hardware (the payload's data length is this in whole bytes).
  std::uint64_t bits() const { return bits_; }
  tlm::tlm_extension_base* clone() const override { return new MessageExtension(message_, bits_); }
  void copy_from(const tlm::tlm_extension_base& other) override {
    message_ = static_cast<const MessageExtension&>(other).message_;
    bits_ = static_cast<const MessageExtension&>(other).bits_;
  }

 private:
  T* message_;
  std::uint64_t bits_;
};

/// The receiving end: a target socket in front of a bounded FIFO of T. Its statistics are its
/// FIFO's, and the bits its messages carried (their size on the hardware), under its name or
/// the name the machine's vocabulary gives the queue ("pert0.queue.shade_to_shell" for the
/// SystemC module pert0.shell.input).
template <class T>
class MessageQueue : public sc_core::sc_module, public BlockingTarget {
 public:
  tlm::tlm_target_socket<> socket;
  TimedFifo<T> fifo;

  MessageQueue(sc_core::sc_module_name name, std::size_t depth, std::string stats_name = {})
      : sc_core::sc_module(name),
        socket("socket"),
        fifo(stats_name.empty() ? std::string(this->name()) : std::move(stats_name), depth),
        bits_(fifo, "bits", "bits its messages carried (their sizes on the hardware)",
              StatUnit::bits) {
    socket.bind(*this);
  }

 private:
  void b_transport(tlm::tlm_generic_payload& gp, sc_core::sc_time& delay) override {
    const auto* ext = gp.get_extension<MessageExtension<T>>();
    if (!ext || !ext->message()) {
      gp.set_response_status(tlm::TLM_GENERIC_ERROR_RESPONSE);
      return;
    }
    bits_ += ext->bits();
    const sc_core::sc_time stamp = fifo.put(*ext->message(), modules::sim_now() + delay);
    const sc_core::sc_time now = modules::sim_now();
    delay = stamp > now ? stamp - now : sc_core::SC_ZERO_TIME;
    gp.set_response_status(tlm::TLM_OK_RESPONSE);
  }
  Counter bits_;
};

/// Puts `msg` into the queue behind `socket` at absolute time `t` (when it arrives there: after
/// its Link, if it crossed one); returns the absolute time it was accepted (later than t if the
/// FIFO was full). `bits`: its size on the hardware.
template <class Socket, class T>
sc_core::sc_time send_message(Socket& socket, T& msg, const sc_core::sc_time& t,
                              std::uint64_t bits) {
  MessageExtension<T> ext(&msg, bits);
  tlm::tlm_generic_payload& gp = *PayloadPool::take();
  gp.set_command(tlm::TLM_WRITE_COMMAND);
  gp.set_address(0);
  gp.set_data_ptr(nullptr);
  gp.set_data_length(static_cast<unsigned>((bits + 7) / 8));
  gp.set_streaming_width(static_cast<unsigned>((bits + 7) / 8));
  gp.set_byte_enable_ptr(nullptr);
  gp.set_dmi_allowed(false);
  gp.set_extension(&ext);
  gp.set_response_status(tlm::TLM_INCOMPLETE_RESPONSE);
  // The extension lives on this stack: cleared and the payload given back even when the
  // receiver throws (a time overflow deep in a chain of modules), so no pooled payload is left
  // pointing at it.
  struct GiveBack {
    tlm::tlm_generic_payload& gp;
    MessageExtension<T>& ext;
    ~GiveBack() {
      gp.clear_extension(&ext);
      PayloadPool::give_back(&gp);
    }
  };
  bool error = false;
  const sc_core::sc_time now = modules::sim_now();
  sc_core::sc_time delay = t > now ? t - now : sc_core::SC_ZERO_TIME;
  {
    const GiveBack give_back{gp, ext};
    socket->b_transport(gp, delay);
    error = gp.is_response_error();
  }
  if (error) SC_REPORT_ERROR("rtsim/message", "a message reached a queue of another type");
  return modules::sim_now() + delay;
}

}  // namespace rtsim::modules
