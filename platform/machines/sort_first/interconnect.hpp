#pragma once
// What sort-first's nodes talk over (`interconnect`): Pixel-Planes 5's token ring, every node a
// stop on it (L284; the study's traces came from that machine, L554), or a mesh of the renderers
// with the host on a bus of its own (mesh_channel.hpp). A node is a kit Processor with its queue
// of arrived messages; sending does not stop it computing, receiving waits for the next message
// (L120, L284: computation and communication overlap). Each node counts the bytes it hands over,
// frame by frame and kind by kind.
#include <array>
#include <cstdint>
#include <map>
#include <systemc>

#include "modules/inbox_processor.hpp"
#include "modules/ring_channel.hpp"
#include "platform/machines/machine_trace.hpp"
#include "platform/machines/sort_first/mesh_channel.hpp"
#include "platform/machines/sort_first/messages.hpp"

namespace rtsim::platform::sort_first {

/// The ring's channel or the mesh's, whichever the run built.
class Interconnect {
 public:
  explicit Interconnect(modules::RingChannel<Message>& ring) : ring_(&ring) {}
  explicit Interconnect(MeshChannel& mesh) : mesh_(&mesh) {}

  void attach(std::size_t node, modules::MessageQueue<Message>& inbox) {
    if (ring_)
      ring_->attach(node, inbox);
    else
      mesh_->attach(node, inbox);
  }
  void send(std::size_t from, std::size_t to, Message m, std::uint64_t bytes,
            const sc_core::sc_time& ready) {
    const auto cls = static_cast<std::size_t>(m.kind);
    if (ring_)
      ring_->send(from, to, std::move(m), bytes, ready, cls);
    else
      mesh_->send(from, to, std::move(m), bytes, ready);
  }

 private:
  modules::RingChannel<Message>* ring_ = nullptr;
  MeshChannel* mesh_ = nullptr;
};

/// Bytes a node handed to the interconnect in one frame, by message kind.
using FrameBytes = std::array<std::uint64_t, kMessageKinds>;

class InterconnectNode : public modules::InboxProcessor<Message> {
 public:
  const std::map<int, FrameBytes>& bytes_by_frame() const { return bytes_; }

 protected:
  InterconnectNode(const sc_core::sc_module_name& name, MachineTrace& trace, Interconnect& net,
                   int node)
      : modules::InboxProcessor<Message>(name, trace), net_(net), node_(node) {
    net.attach(static_cast<std::size_t>(node), inbox);
  }

  /// Hands `m` to the interconnect for node `to`, at this node's time.
  void send(int to, Message m) {
    m.from = node_;
    m.sent = clock_.now();
    const std::uint64_t bytes = m.bytes();
    bytes_[m.frame][static_cast<std::size_t>(m.kind)] += bytes;
    net_.send(static_cast<std::size_t>(node_), static_cast<std::size_t>(to), std::move(m), bytes,
              clock_.now());
  }

 private:
  Interconnect& net_;
  int node_;
  std::map<int, FrameBytes> bytes_;
};

}  // namespace rtsim::platform::sort_first
