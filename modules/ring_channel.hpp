#pragma once
// Typed messages over a token ring (modules/token_ring.hpp): a sender hands a message of type M
// to the ring at its node; when the ring has carried it round to the destination node, the
// channel puts it into that node's MessageQueue<M> by TLM b_transport
// (modules/message_channel.hpp), stamped with its arrival. The ring carries sizes and times; the
// message itself waits here between the two, and is what the destination receives.
//
// Used by ullner-array (array.interconnect = ring) and pxpl5-raytrace.
#include <tlm_utils/simple_initiator_socket.h>

#include <cstdint>
#include <memory>
#include <string>
#include <systemc>
#include <unordered_map>
#include <vector>

#include "modules/message_channel.hpp"
#include "modules/token_ring.hpp"
#include "modules/wiring.hpp"

namespace rtsim::modules {

template <class M>
class RingChannel : public sc_core::sc_module {
 public:
  /// One output per node of `ring`; bind each with attach() before the simulation.
  RingChannel(sc_core::sc_module_name name, TokenRing& ring)
      : sc_core::sc_module(name), ring_(ring) {
    connect(this->name(), ring.name(), "sends over");
    for (std::size_t k = 0; k < ring.nodes(); ++k)
      out_.push_back(std::make_unique<tlm_utils::simple_initiator_socket<RingChannel<M>>>(
          ("to_node" + std::to_string(k)).c_str()));
    ring_.on_delivery([this](std::uint64_t id, std::size_t node, const sc_core::sc_time& at) {
      auto it = pending_.find(id);
      if (it == pending_.end()) return;
      M msg = std::move(it->second.message);
      const std::uint64_t bits = it->second.bits;
      pending_.erase(it);
      // The message's flow ends where it is delivered: on the track of the node's module.
      if (ring_.trace() && ring_.trace()->records() && node < stops_.size())
        ring_.trace()->hop(stops_[node], "ring message", id, at);
      send_message(*out_[node], msg, at, bits);
    });
  }

  /// Node `node` receives into `inbox` (the module that owns it is the ring's node `node`).
  void attach(std::size_t node, MessageQueue<M>& inbox) {
    out_.at(node)->bind(inbox.socket);
    const std::string queue = inbox.name();
    if (stops_.size() <= node) stops_.resize(node + 1);
    stops_[node] = queue.substr(0, queue.rfind('.'));
    ring_stop(ring_.name(), node, stops_[node]);
  }

  /// Sends `msg` (`bytes` on the ring) from node `from` to node `to`, ready at `ready`.
  void send(std::size_t from, std::size_t to, M msg, std::uint64_t bytes,
            const sc_core::sc_time& ready, std::size_t traffic_class = 0) {
    const std::uint64_t id = ring_.send(from, to, bytes, ready, traffic_class);
    pending_.emplace(id, Pending{std::move(msg), 8 * bytes});
  }

  TokenRing& ring() { return ring_; }

 private:
  struct Pending {
    M message;
    std::uint64_t bits = 0;
  };
  TokenRing& ring_;
  std::vector<std::unique_ptr<tlm_utils::simple_initiator_socket<RingChannel<M>>>> out_;
  std::unordered_map<std::uint64_t, Pending> pending_;
  std::vector<std::string> stops_;  ///< the module at each node (attach)
};

}  // namespace rtsim::modules
