#pragma once
// Sort-first's renderers on a two-dimensional mesh (`interconnect = mesh`): a renderer a region,
// each joined to its four neighbours by a kit Link each way, messages routed dimension-order
// (modules/mesh_topology.hpp) and forwarded store-and-forward, a whole message a hop (an
// assumption: the seed gives no network, L503; migrations go mostly to neighbours, L538). The
// host and frame buffer are on a bus of their own (`host_bus`, one kit Link every renderer
// shares), not on the mesh.
//
// One thread moves every message hop by hop in time order (a heap of hops, ties by the order
// they were made), so each link carries its messages in the order they reach it, as the
// reference setting requires, at a few events a hop.
#include <tlm_utils/simple_initiator_socket.h>

#include <cstdint>
#include <memory>
#include <queue>
#include <string>
#include <systemc>
#include <unordered_map>
#include <vector>

#include "modules/link.hpp"
#include "modules/mesh_topology.hpp"
#include "modules/message_channel.hpp"
#include "modules/sim_time.hpp"
#include "modules/wiring.hpp"
#include "platform/machines/sort_first/messages.hpp"

namespace rtsim::platform::sort_first {

class MeshChannel : public sc_core::sc_module {
 public:
  static constexpr const char* kLinkClass = "mesh.link";
  static constexpr const char* kHostBus = "host_bus";
  /// Declares the mesh links' and the host bus's parameters.
  static void declare_params(const modules::ParamDecls& machine);
  /// Reads them without building the mesh (a ring run checks them too).
  static void check_params(const params::ParamRegistry& registry);

  SC_HAS_PROCESS(MeshChannel);
  /// A side x side mesh of renderers (node = region); node side * side is the host.
  MeshChannel(sc_core::sc_module_name name, int side, const params::ParamRegistry& registry);

  void attach(std::size_t node, modules::MessageQueue<Message>& inbox);
  void send(std::size_t from, std::size_t to, Message msg, std::uint64_t bytes,
            const sc_core::sc_time& ready);

 private:
  struct Hop {
    sc_core::sc_time at;
    std::uint64_t seq = 0;
    std::uint64_t id = 0;
    std::size_t node = 0;  ///< where the message is at `at`
  };
  struct Later {
    bool operator()(const Hop& a, const Hop& b) const {
      return a.at != b.at ? a.at > b.at : a.seq > b.seq;
    }
  };
  struct Pending {
    Message message;
    std::size_t to = 0;
    std::uint64_t bits = 0;
  };
  void run();
  void push(const sc_core::sc_time& at, std::uint64_t id, std::size_t node);

  modules::MeshTopology topology_;
  std::size_t host_;
  std::vector<std::unique_ptr<modules::Link>> links_;  ///< [node * 4 + direction]
  std::unique_ptr<modules::Link> host_bus_;
  std::vector<std::unique_ptr<tlm_utils::simple_initiator_socket<MeshChannel>>> out_;
  std::priority_queue<Hop, std::vector<Hop>, Later> hops_queue_;
  std::unordered_map<std::uint64_t, Pending> pending_;
  std::uint64_t next_id_ = 0, next_seq_ = 0;
  sc_core::sc_event put_event_;
};

}  // namespace rtsim::platform::sort_first
