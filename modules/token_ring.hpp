#pragma once
// A token ring of the kit (DESIGN.md "The three layers"): N nodes in a ring share one medium;
// the token, the right to transmit, goes from node k to node k + 1 (mod N) in `hop_latency`;
// the node that holds it sends packets, one at a time at the ring's bandwidth, and then passes
// it on. How long a node keeps the token is the service discipline (Takagi's polling models):
//   exhaustive  until its queue is empty, packets queued meanwhile included;
//   gated       only the packets that were queued when the token arrived;
//   one_packet  at most one packet a visit.
// A message longer than `max_packet_bytes` is cut into packets, each with `header_bytes` of
// header; it arrives when its last packet has gone round to its destination: the end of that
// packet's transmission + hop_latency x the hops from sender to destination.
//
// Senders hand over messages and go on computing (compute and communication overlap, seed 004
// L120, L284): send() returns at once. A message may be stamped ahead of SystemC time (a sender
// running ahead); the ring takes it into account once its stamp has come.
//
// One thread walks the token in time order. It does not step through idle hops: with nothing
// eligible anywhere it computes where the token will find the next packet (or, woken by a new
// message, where the token is by then), so a run costs a few SystemC events per packet, not per
// hop.
//
// Pixel-Planes 5's ring (seed 004 L284: "the system's internal 5 Gigabit/sec token ring
// network") gives only the bandwidth; every other default is a documented assumption.
// Validated against polling-system theory (tests/token_ring_test.cpp). Used by pxpl5-raytrace
// and, as an alternative to its mesh links, ullner-array.
#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <string>
#include <systemc>
#include <vector>

#include "modules/level_steps.hpp"
#include "modules/module_params.hpp"
#include "modules/slice_sink.hpp"
#include "modules/statistics.hpp"

namespace rtsim::modules {

/// How long a node keeps the token.
enum class RingService { kExhaustive, kGated, kOnePacket };

/// The statistics group of its name: busy while transmitting (utilisation), messages, packets,
/// the mean token rotation, the mean wait over all packets and per node, bytes per traffic
/// class; and the holder signal for the traces.
class TokenRing : public sc_core::sc_module, public StatGroup {
 public:
  /// A machine preset's defaults, with where they come from.
  struct Defaults {
    std::string bandwidth{};         ///< "5 Gbit/s"
    std::string bandwidth_source{};  ///< "seed 004 L284"
    std::string hop_latency{};       ///< "10 ns"
    std::string max_packet_bytes{};  ///< "1024"
    std::string header_bytes{};      ///< "8"
    std::string service{};           ///< "exhaustive", "gated" or "one_packet"
    std::string source{};            ///< why the other defaults (an assumption)
  };
  /// Declares bandwidth, hop_latency, max_packet_bytes, header_bytes and service under the
  /// ring's path.
  static void declare_params(const ParamDecls& ring, const Defaults& d);

  /// Its parameters as read (a machine that may not build its ring reads them anyway, so a
  /// bad value is an error whichever interconnect is chosen).
  struct Config {
    sc_core::sc_time bit_time;
    sc_core::sc_time hop_latency;
    std::uint64_t max_payload = 0;
    std::uint64_t header = 0;
    RingService service = RingService::kExhaustive;
  };
  static Config read_config(const ModuleParams& params);

  /// Called once per message when it arrives: (its id, its destination, when).
  using Delivery =
      std::function<void(std::uint64_t id, std::size_t destination, const sc_core::sc_time& at)>;

  SC_HAS_PROCESS(TokenRing);
  /// `nodes` >= 1 in ring order; `classes`: names of the traffic classes whose bytes are
  /// counted apart (class k of send()); at least one.
  /// (config: read_config(ModuleParams(registry, "ring")).)
  TokenRing(sc_core::sc_module_name name, const Config& config, std::size_t nodes,
            std::vector<std::string> classes = {"data"});

  /// Who hears of arrivals (set before the simulation starts).
  void on_delivery(Delivery delivery) { delivery_ = std::move(delivery); }
  /// Traces each packet it transmits into `sink` (the run's traces): a slice on its track named
  /// by the traffic class, with the message's id, its source and destination nodes and the
  /// packet's bytes, and a step of the message's flow ("ring message").
  void trace_to(SliceSink& sink) { trace_ = &sink; }
  /// Where it traces (nullptr: nowhere).
  SliceSink* trace() const { return trace_; }

  /// Queues a message of `bytes` (>= 1) from node `source` to node `destination`, ready at
  /// `ready` (its sender's local time, not before SystemC's). Returns its id (0, 1, ...).
  std::uint64_t send(std::size_t source, std::size_t destination, std::uint64_t bytes,
                     const sc_core::sc_time& ready, std::size_t traffic_class = 0);

  std::size_t nodes() const { return queues_.size(); }
  RingService service() const { return service_; }
  const sc_core::sc_time& hop_latency() const { return hop_; }
  /// Time to transmit a packet of `wire_bytes` (header included) at the ring's bandwidth.
  sc_core::sc_time transmission(std::uint64_t wire_bytes) const;
  /// Bytes on the wire of a message of `bytes`: cut into packets, a header each.
  std::uint64_t wire_bytes(std::uint64_t bytes) const {
    const std::uint64_t packets = bytes == 0 ? 1 : (bytes + max_payload_ - 1) / max_payload_;
    return bytes + packets * header_;
  }
  /// Hops from node `a` to node `b` in ring order (0 for a == b).
  std::size_t hops(std::size_t a, std::size_t b) const;

  // --- statistics ------------------------------------------------------------------------
  std::uint64_t messages() const { return messages_.value(); }
  std::uint64_t packets() const { return packets_sent_.value(); }
  sc_core::sc_time busy() const { return busy_.total(); }
  const BusyTimeline& timeline() const { return busy_.timeline(); }
  /// Mean time between the token's passes at node 0 (0 before it came round twice).
  double mean_rotation_s() const;
  /// Mean wait of node k's packets, from being queued to the start of their transmission.
  double mean_wait_s(std::size_t node) const;
  /// Over every packet.
  double mean_wait_s() const;
  std::uint64_t packets_sent(std::size_t node) const { return node_[node].packets; }
  /// Who transmits: node index + 1 while a node sends, 0 while none does (VCD `NAME.holder`).
  const std::vector<LevelChange>& holder_changes() const { return holder_.changes(); }

 private:
  struct Packet {
    std::uint64_t message = 0;
    std::size_t destination = 0;
    std::uint64_t wire_bytes = 0;
    std::size_t traffic_class = 0;
    bool last = false;  ///< the message's last packet
    sc_core::sc_time ready;
  };
  struct NodeStats {
    std::uint64_t packets = 0;
    double wait_s = 0;
  };

  void run();
  /// Whether node k has a packet queued by `t`.
  bool eligible(std::size_t k, const sc_core::sc_time& t) const;
  /// Serves the node the token is at, at time_; returns with time_ after its last packet.
  void serve();
  /// Moves the token on by `n` hops (counting its passes at node 0).
  void advance(std::uint64_t n);
  void set_holder(long level, const sc_core::sc_time& t);

  sc_core::sc_time bit_time_;
  sc_core::sc_time hop_;
  std::uint64_t max_payload_ = 0;
  std::uint64_t header_ = 0;
  RingService service_ = RingService::kExhaustive;
  std::vector<std::string> classes_;
  Delivery delivery_;
  SliceSink* trace_ = nullptr;

  std::vector<std::deque<Packet>> queues_;
  std::size_t queued_ = 0;  ///< packets in all queues
  sc_core::sc_event put_event_;

  std::size_t at_ = 0;                             ///< the node the token is at (or last passed)
  sc_core::sc_time time_ = sc_core::SC_ZERO_TIME;  ///< when it got there

  std::uint64_t passes_at_0_ = 0;
  sc_core::sc_time first_pass_at_0_, last_pass_at_0_;
  std::vector<NodeStats> node_;

  Busy busy_{*this, "time transmitting (its utilisation)"};
  Counter messages_{*this, "messages", "messages sent"};
  Counter packets_sent_{*this, "packets", "packets transmitted"};
  Computed nodes_{*this, "nodes", StatUnit::count, "nodes on the ring",
                  [this] { return queues_.size(); }};
  Computed rotation_{*this, "token_rotation_s", StatUnit::seconds,
                     "mean time between the token's passes at node 0",
                     [this] { return mean_rotation_s(); }};
  Computed mean_wait_{*this, "mean_wait_s", StatUnit::seconds,
                      "mean wait of a packet from being queued to its transmission",
                      [this] { return mean_wait_s(); }};
  Computed node_waits_{*this, "wait_s_by_node", StatUnit::seconds,
                       "mean wait of each node's packets, in ring order", [this] {
                         nlohmann::ordered_json waits = nlohmann::ordered_json::array();
                         for (std::size_t k = 0; k < node_.size(); ++k)
                           waits.push_back(mean_wait_s(k));
                         return waits;
                       }};
  CounterArray class_bytes_{*this, "bytes.", classes_, "bytes of a traffic class, headers in",
                            StatUnit::bytes};
  LevelSignal holder_{*this, "holder", "node index + 1 while a node transmits, 0 while none"};
};

/// "exhaustive", "gated", "one_packet".
const char* to_string(RingService s);

}  // namespace rtsim::modules
