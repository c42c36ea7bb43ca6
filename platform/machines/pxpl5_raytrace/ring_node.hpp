#pragma once
// A node of Pixel-Planes 5's ring (seed 004 L284): a kit Processor with its queue of arrived
// messages and its port on the ring. Sending does not stop it computing (the ring carries the
// message meanwhile, L120); receiving waits for the next message.
#include <cstdint>
#include <string>
#include <systemc>

#include "modules/inbox_processor.hpp"
#include "modules/ring_channel.hpp"
#include "params/registry.hpp"
#include "platform/machines/machine_trace.hpp"
#include "platform/machines/pxpl5_raytrace/messages.hpp"

namespace rtsim::platform::pxpl5 {

/// Bytes each kind of message occupies on the ring (the seed gives none, note 004 A: a
/// parameter each, wire.*).
struct WireSizes {
  std::uint64_t control = 16;  ///< start, request, assign, frame done
  std::uint64_t sample = 8;    ///< per sample (samples and band messages)
  std::uint64_t pixel = 4;     ///< per display pixel
  std::uint64_t header = 16;   ///< per sample, band or pixel message
  std::uint64_t bytes(const Message& m) const;

  static void declare_params(params::ParamRegistry& r);
  static WireSizes read(const params::ParamRegistry& r);
};

class RingNode : public modules::InboxProcessor<Message> {
 public:
  int index() const { return index_; }

 protected:
  RingNode(const sc_core::sc_module_name& name, MachineTrace& trace,
           modules::RingChannel<Message>& ring, int index, const WireSizes& sizes)
      : modules::InboxProcessor<Message>(name, trace), ring_(ring), index_(index), sizes_(sizes) {
    ring.attach(static_cast<std::size_t>(index), inbox);
  }

  /// Hands `m` to the ring for node `to`, at this node's time.
  void send(int to, Message m) {
    m.from = index_;
    const std::uint64_t bytes = sizes_.bytes(m);
    const auto cls = static_cast<std::size_t>(m.kind);
    ring_.send(static_cast<std::size_t>(index_), static_cast<std::size_t>(to), std::move(m), bytes,
               clock_.now(), cls);
  }

 private:
  modules::RingChannel<Message>& ring_;
  int index_;
  WireSizes sizes_;
};

}  // namespace rtsim::platform::pxpl5
