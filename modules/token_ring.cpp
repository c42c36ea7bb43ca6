#include "modules/token_ring.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "modules/activations.hpp"
#include "modules/sim_time.hpp"

namespace rtsim::modules {

const char* to_string(RingService s) {
  switch (s) {
    case RingService::kExhaustive:
      return "exhaustive";
    case RingService::kGated:
      return "gated";
    case RingService::kOnePacket:
      return "one_packet";
  }
  return "?";
}

namespace {
// Its parameters' names, each written once: declared with the preset's defaults, read below.
constexpr const char* kBandwidth = "bandwidth";
constexpr const char* kHopLatency = "hop_latency";
constexpr const char* kMaxPacketBytes = "max_packet_bytes";
constexpr const char* kHeaderBytes = "header_bytes";
constexpr const char* kService = "service";
}  // namespace

void TokenRing::declare_params(const ParamDecls& ring, const Defaults& d) {
  const std::string& who = ring.path();
  ring.declare({.name = kBandwidth,
                .kind = params::ParamKind::kBitRate,
                .default_value = d.bandwidth,
                .min = "1 bit/s",
                .description = "Token ring " + who + ": bits per second on the ring (shared)",
                .source = d.bandwidth_source});
  ring.declare({.name = kHopLatency,
                .kind = params::ParamKind::kTime,
                .default_value = d.hop_latency,
                .min = "1 ps",
                .max = "1 s",
                .description = "Token ring " + who +
                               ": time for the token, or a packet's bits, to go from one node "
                               "to the next",
                .source = d.source});
  ring.count(kMaxPacketBytes, d.max_packet_bytes, "1", "1073741824", "bytes",
             "Token ring " + who + ": most payload bytes in one packet; longer messages are cut",
             d.source);
  ring.count(kHeaderBytes, d.header_bytes, "0", "65536", "bytes",
             "Token ring " + who + ": bytes of header on every packet", d.source);
  ring.declare({.name = kService,
                .kind = params::ParamKind::kString,
                .default_value = d.service,
                .allowed = {"exhaustive", "gated", "one_packet"},
                .description = "Token ring " + who +
                               ": how long a node keeps the token: until its queue is empty, "
                               "the packets queued when the token came, or one packet",
                .source = d.source});
}

namespace {
RingService read_service(const std::string& s) {
  if (s == "gated") return RingService::kGated;
  if (s == "one_packet") return RingService::kOnePacket;
  return RingService::kExhaustive;
}
}  // namespace

TokenRing::Config TokenRing::read_config(const ModuleParams& params) {
  return {.bit_time = from_ps(static_cast<std::int64_t>(
              std::max(1.0, std::round(1e12 / params.get_bitrate_bps(kBandwidth))))),
          .hop_latency = std::max(from_ps(1), params.get_time(kHopLatency)),
          .max_payload = std::max<std::uint64_t>(1, params.get_count(kMaxPacketBytes)),
          .header = params.get_count(kHeaderBytes),
          .service = read_service(params.get_string(kService))};
}

TokenRing::TokenRing(sc_core::sc_module_name name, const Config& c, std::size_t nodes,
                     std::vector<std::string> classes)
    : sc_core::sc_module(name),
      StatGroup(sc_core::sc_module::name()),
      bit_time_(c.bit_time),
      hop_(c.hop_latency),
      max_payload_(c.max_payload),
      header_(c.header),
      service_(c.service),
      classes_(classes.empty() ? std::vector<std::string>{"data"} : std::move(classes)),
      queues_(std::max<std::size_t>(1, nodes)),
      node_(queues_.size()) {
  SC_THREAD(run);
}

sc_core::sc_time TokenRing::transmission(std::uint64_t wire_bytes) const {
  return times(bit_time_, 8 * wire_bytes);
}

std::size_t TokenRing::hops(std::size_t a, std::size_t b) const {
  const std::size_t n = queues_.size();
  return (b + n - a % n) % n;
}

std::uint64_t TokenRing::send(std::size_t source, std::size_t destination, std::uint64_t bytes,
                              const sc_core::sc_time& ready, std::size_t traffic_class) {
  if (source >= queues_.size() || destination >= queues_.size())
    throw std::out_of_range(std::string(name()) + ": no node " +
                            std::to_string(std::max(source, destination)) + " on a ring of " +
                            std::to_string(queues_.size()));
  const std::uint64_t id = messages_.value();
  ++messages_;
  const sc_core::sc_time stamp = std::max(ready, modules::sim_now());
  const std::size_t cls = std::min(traffic_class, classes_.size() - 1);
  std::uint64_t left = std::max<std::uint64_t>(1, bytes);
  while (left > 0) {
    const std::uint64_t payload = std::min(left, max_payload_);
    left -= payload;
    queues_[source].push_back({.message = id,
                               .destination = destination,
                               .wire_bytes = payload + header_,
                               .traffic_class = cls,
                               .last = left == 0,
                               .ready = stamp});
    ++queued_;
  }
  put_event_.notify(sc_core::SC_ZERO_TIME);
  return id;
}

bool TokenRing::eligible(std::size_t k, const sc_core::sc_time& t) const {
  return !queues_[k].empty() && queues_[k].front().ready <= t;
}

void TokenRing::set_holder(long level, const sc_core::sc_time& t) {
  std::vector<LevelChange>& h = holder_.changes();
  const std::uint64_t v = t.value();
  if (!h.empty() && h.back().t == v) {
    h.back().level = level;
    const long before = h.size() > 1 ? h[h.size() - 2].level : 0;
    if (before == level) h.pop_back();
    return;
  }
  const long now = h.empty() ? 0 : h.back().level;
  if (now != level) h.push_back({v, level});
}

void TokenRing::advance(std::uint64_t n) {
  if (n == 0) return;
  const std::size_t size = queues_.size();
  // Passes at node 0 among the positions at_ + 1 .. at_ + n.
  const std::uint64_t passes = (at_ + n) / size;
  if (passes > 0) {
    const std::uint64_t last_k = n - (at_ + n) % size;
    last_pass_at_0_ = plus(time_, times(hop_, last_k));
    passes_at_0_ += passes;
  }
  at_ = static_cast<std::size_t>((at_ + n) % size);
  time_ = plus(time_, times(hop_, n));
}

void TokenRing::serve() {
  std::deque<Packet>& q = queues_[at_];
  const sc_core::sc_time gate = time_;  // gated: what was queued when the token came
  std::uint64_t sent = 0;
  for (;;) {
    // Exhaustive service takes packets queued while it sends: let their senders run first.
    if (service_ == RingService::kExhaustive && modules::sim_now() < time_)
      modules::sim_wait(time_ - modules::sim_now());
    if (q.empty()) break;
    const sc_core::sc_time limit = service_ == RingService::kGated ? gate : time_;
    if (q.front().ready > limit) break;
    if (service_ == RingService::kOnePacket && sent == 1) break;
    const Packet p = q.front();
    q.pop_front();
    --queued_;
    ++sent;
    const sc_core::sc_time start = time_;
    const sc_core::sc_time length = transmission(p.wire_bytes);
    time_ = plus(start, length);
    busy_.record(start, length);
    set_holder(static_cast<long>(at_) + 1, start);
    ++packets_sent_;
    node_[at_].packets += 1;
    node_[at_].wait_s += (start - p.ready).to_seconds();
    class_bytes_.add(p.traffic_class, p.wire_bytes);
    if (trace_ && trace_->records()) {
      trace_->slice(
          name(), classes_[p.traffic_class], start, length,
          {{"message", p.message}, {"from", at_}, {"to", p.destination}, {"bytes", p.wire_bytes}});
      trace_->hop(name(), "ring message", p.message, start);
    }
    if (p.last && delivery_)
      delivery_(p.message, p.destination, plus(time_, times(hop_, hops(at_, p.destination))));
  }
  if (sent > 0) set_holder(0, time_);
}

void TokenRing::run() {
  const std::size_t n = queues_.size();
  at_ = 0;
  time_ = sc_core::SC_ZERO_TIME;
  passes_at_0_ = 1;
  first_pass_at_0_ = last_pass_at_0_ = time_;
  bool served = false;  // the token's visit to at_ at time_ has been served
  for (;;) {
    if (modules::sim_now() < time_) modules::sim_wait(time_ - modules::sim_now());
    if (!served) {
      served = true;
      if (eligible(at_, time_)) serve();
    }
    if (queued_ == 0) {
      // Nothing anywhere: wait for a message, then work out where the token is by then.
      modules::sim_wait(put_event_);
      const sc_core::sc_time now = modules::sim_now();
      const std::uint64_t h = now > time_ ? (now - time_).value() / hop_.value() : 0;
      advance(h);
      served = served && h == 0;
      continue;
    }
    // The next visit that finds a packet: for each node with one, the first time the token
    // reaches it at or after its packet is ready.
    std::uint64_t best = std::numeric_limits<std::uint64_t>::max();
    for (std::size_t j = 0; j < n; ++j) {
      if (queues_[j].empty()) continue;
      std::uint64_t k = hops(at_, j);
      if (k == 0) k = n;
      const sc_core::sc_time reach = plus(time_, times(hop_, k));
      const sc_core::sc_time ready = queues_[j].front().ready;
      if (ready > reach) {
        const std::uint64_t behind = (ready - reach).value();
        const std::uint64_t rotation = static_cast<std::uint64_t>(n) * hop_.value();
        k += (behind + rotation - 1) / rotation * n;
      }
      best = std::min(best, k);
    }
    const sc_core::sc_time target = plus(time_, times(hop_, best));
    const sc_core::sc_time now = modules::sim_now();
    if (target > now) modules::sim_wait(target - now, put_event_);
    const sc_core::sc_time woke = modules::sim_now();
    if (woke < target) {
      // A new message came before the token got there: where is the token now?
      const std::uint64_t h = woke > time_ ? (woke - time_).value() / hop_.value() : 0;
      advance(h);
      served = served && h == 0;
      continue;
    }
    advance(best);
    served = false;
  }
}

double TokenRing::mean_rotation_s() const {
  if (passes_at_0_ < 2) return 0.0;
  return (last_pass_at_0_ - first_pass_at_0_).to_seconds() / static_cast<double>(passes_at_0_ - 1);
}

double TokenRing::mean_wait_s(std::size_t node) const {
  const NodeStats& s = node_.at(node);
  return s.packets > 0 ? s.wait_s / static_cast<double>(s.packets) : 0.0;
}

double TokenRing::mean_wait_s() const {
  double sum = 0;
  std::uint64_t count = 0;
  for (const NodeStats& s : node_) {
    sum += s.wait_s;
    count += s.packets;
  }
  return count > 0 ? sum / static_cast<double>(count) : 0.0;
}

}  // namespace rtsim::modules
