#include "platform/machines/pixelflow/composition_network.hpp"

#include <algorithm>

#include "modules/sim_time.hpp"
#include "platform/machines/machine_run.hpp"

namespace rtsim::platform::pixelflow {

namespace {
/// XORs `mask` into the 4 bytes at byte `offset` of the records (little-endian; a word may
/// straddle two records).
void corrupt(raster::RegionSamples& s, std::uint64_t offset, std::uint32_t mask) {
  for (int b = 0; b < 4; ++b) {
    const std::uint64_t at = offset + static_cast<std::uint64_t>(b);
    auto& rec = s.words[static_cast<std::size_t>(at / raster::kAppearanceBytes)];
    rec[static_cast<std::size_t>(at % raster::kAppearanceBytes)] ^=
        static_cast<std::uint8_t>((mask >> (8 * b)) & 0xFFu);
  }
}
}  // namespace

/// One end of the network's link: what both directions do with a region once they have it.
class CompositionNetwork::Port : public modules::Processor {
 protected:
  Port(sc_core::sc_module_name name, MachineRun& run, CompositionNetwork& net)
      : modules::Processor(name, run.trace()), net_(net) {}

  /// Carries `bits` of pass `pass` over the link from now; when they arrive.
  sc_core::sc_time carry(std::size_t pass, std::uint64_t bits) {
    net_.bytes_by_pass_[pass] += bits / 8;
    return net_.link.transfer(bits, clock_.now());
  }

  /// A map's region to every table memory at once, when each has room (L120, L122).
  void to_tables(TableRegion region, std::uint64_t bits) {
    for (const auto* t : net_.ends_.tables) wait_for_room(*t);
    const sc_core::sc_time arrived = carry(static_cast<std::size_t>(region.pass), bits);
    for (auto& s : net_.to_table) modules::send_message(*s, region, arrived, bits);
  }

  /// `msg` to the one queue behind `socket` when it has room; its journey's wait and transfer.
  template <class Message, class Socket>
  void to_one(const modules::TimedFifo<Message>& queue, Socket& socket, Message msg,
              std::uint64_t bits) {
    const sc_core::sc_time ready = clock_.now();
    wait_for_room(queue);
    const sc_core::sc_time sending = clock_.now();
    const sc_core::sc_time arrived = carry(static_cast<std::size_t>(msg.pass), bits);
    net_.probe_.add(msg.journey, net_.stages_.network, modules::LatencyPart::kQueueing,
                    sending - ready);
    net_.probe_.add(msg.journey, net_.stages_.link, modules::LatencyPart::kTransfer,
                    arrived - sending);
    msg.arrived = arrived;
    modules::send_message(socket, msg, arrived, bits);
  }

  CompositionNetwork& net_;
};

/// Rasterizers to shaders and table memories, region-sample by region-sample in pass order.
class CompositionNetwork::Compositor : public Port {
 public:
  SC_HAS_PROCESS(Compositor);
  Compositor(sc_core::sc_module_name name, MachineRun& run, CompositionNetwork& net)
      : Port(name, run, net) {
    SC_THREAD(run);
  }

 private:
  void run() {
    const PassPlan& plan = net_.plan_;
    for (std::size_t pi = 0; pi < plan.passes.size(); ++pi) {
      const Pass& pass = plan.passes[pi];
      for (int k = 0; k < pass.region_samples(); ++k) {
        // Every rasterizer's buffer of this region-sample.
        std::vector<RasterRegion> parts;
        for (auto& q : net_.from_rasterizer) {
          const sc_core::sc_time since = clock_.now();
          modules::wait_for_item(q->fifo, clock_);
          sc_core::sc_time taken;
          parts.push_back(q->fifo.get(clock_.now(), taken));
          clock_.catch_up(taken);
          waited_since(since, Wait::kData);
        }
        // A camera region-sample's journey begins with the first rasterizer's work on it.
        modules::LatencyProbe& probe = net_.probe_;
        modules::LatencyProbe::Journey journey = modules::LatencyProbe::kNoJourney;
        if (pass.kind == PassKind::Camera && probe.enabled()) {
          sc_core::sc_time begun = parts.front().begun, finished = parts.front().finished;
          for (const auto& p : parts) {
            begun = std::min(begun, p.begun);
            finished = std::max(finished, p.finished);
          }
          const ProbeStages& st = net_.stages_;
          journey = probe.begin(begun);
          probe.add(journey, st.rasterizer, modules::LatencyPart::kService, finished - begun);
          probe.add(journey, st.from_rasterizer, modules::LatencyPart::kQueueing,
                    clock_.now() - finished);
        }
        // Z-composite (L21, L120): the first buffer takes the nearer of every other's samples.
        RasterRegion merged = parts.front();
        for (std::size_t i = 1; i < parts.size(); ++i) {
          if (merged.depths) raster::z_composite(*merged.depths, *parts[i].depths);
          if (merged.samples) raster::z_composite(*merged.samples, *parts[i].samples);
        }
        if (pass.kind == PassKind::Camera) apply_faults(merged, k);
        const std::uint64_t bits = region_bits(pass.bytes_per_pixel());
        if (pass.kind == PassKind::Shadow) {
          to_tables({static_cast<int>(pi), merged.depths->at, merged.depths, nullptr}, bits);
        } else {
          const auto shader = static_cast<std::size_t>(k % net_.shaders_);  // one of every s (L23)
          merged.journey = journey;
          to_one(*net_.ends_.shaders[shader], *net_.to_shader[shader], std::move(merged), bits);
        }
      }
    }
    clock_.sync();
  }

  void apply_faults(RasterRegion& r, int k) {
    for (auto& f : net_.faults_) {
      if (f.word / CompositionNetwork::kWordsPerRegion != static_cast<std::uint64_t>(k)) continue;
      corrupt(*r.samples, (f.word % CompositionNetwork::kWordsPerRegion) * 4, f.xor_mask);
      f.applied = true;
    }
  }
};

/// Shaders to the frame buffer and the table memories, in the order their colours are ready.
class CompositionNetwork::Collector : public Port {
 public:
  SC_HAS_PROCESS(Collector);
  Collector(sc_core::sc_module_name name, MachineRun& run, CompositionNetwork& net)
      : Port(name, run, net) {
    for (auto& q : net_.from_shader) puts_ |= q->fifo.put_event();
    SC_THREAD(run);
  }

 private:
  /// The shader queue whose colours came first (ties: the lower shader), waiting for one.
  std::size_t next() {
    for (;;) {
      std::size_t best = net_.from_shader.size();
      sc_core::sc_time best_at;
      for (std::size_t i = 0; i < net_.from_shader.size(); ++i) {
        const auto at = net_.from_shader[i]->fifo.next_item_time();
        if (at && (best == net_.from_shader.size() || *at < best_at)) {
          best = i;
          best_at = *at;
        }
      }
      if (best < net_.from_shader.size()) return best;
      const sc_core::sc_time since = clock_.now();
      clock_.sync();
      modules::sim_wait(puts_);
      clock_.resync();
      waited_since(since, Wait::kWork);
    }
  }

  void run() {
    const PassPlan& plan = net_.plan_;
    std::uint64_t expected = 0;
    for (const auto& p : plan.passes)
      if (p.kind != PassKind::Shadow) expected += static_cast<std::uint64_t>(p.region_samples());
    for (std::uint64_t n = 0; n < expected; ++n) {
      auto& q = net_.from_shader[next()]->fifo;
      sc_core::sc_time taken;
      const ShadedRegion r = q.get(clock_.now(), taken);
      clock_.catch_up(taken);
      const Pass& pass = plan.passes[static_cast<std::size_t>(r.pass)];
      const std::uint64_t bits = region_bits(kColourBytes);
      if (pass.kind == PassKind::Reflection) {
        to_tables({r.pass, r.at, nullptr, r.colours}, bits);  // the map goes to every table
      } else {
        net_.probe_.add(r.journey, net_.stages_.from_shader, modules::LatencyPart::kQueueing,
                        clock_.now() - r.sent);
        to_one(*net_.ends_.frame_buffer, net_.to_frame_buffer, r, bits);
      }
    }
    clock_.sync();
  }

  sc_core::sc_event_or_list puts_;
};

void CompositionNetwork::declare_params(const modules::ParamDecls& d) {
  // 8K depth words of 4 bytes in 5 us (L120): 52.43 Gbit/s, as 256 lanes of 204.8 Mbit/s.
  modules::Link::declare_params(
      d.sub("link"),
      {.latency = "0 s",
       .lanes = "256",
       .bit_rate = "204.8 Mbit/s",
       .source = "derived: seed 004 L120, a region's depths (8192 x 4 bytes) composited in 5 us; "
                 "the lanes are an assumption (the seed gives no width), the rate per lane "
                 "follows; no latency (assumption: transfer and computation overlap, L120)"});
}

CompositionNetwork::CompositionNetwork(sc_core::sc_module_name name, MachineRun& run,
                                       const PassPlan& plan, int shaders,
                                       std::size_t rasterizer_buffers, NetworkEnds ends,
                                       std::vector<CompositionFault> faults,
                                       const ProbeStages& stages)
    : sc_core::sc_module(name),
      to_frame_buffer("to_frame_buffer"),
      params_(run.registry(), this->name()),
      link(params_.sub("link")),
      plan_(plan),
      shaders_(shaders),
      ends_(std::move(ends)),
      faults_(std::move(faults)),
      bytes_by_pass_(plan.passes.size(), 0),
      probe_(run.probe()),
      stages_(stages) {
  link.trace_to(run.trace());
  for (int r = 0; r < plan.rasterizers; ++r)
    from_rasterizer.push_back(std::make_unique<modules::MessageQueue<RasterRegion>>(
        ("from_rasterizer" + std::to_string(r)).c_str(), rasterizer_buffers));
  for (int s = 0; s < shaders; ++s) {
    from_shader.push_back(std::make_unique<modules::MessageQueue<ShadedRegion>>(
        ("from_shader" + std::to_string(s)).c_str(), 1));
    to_shader.push_back(std::make_unique<tlm_utils::simple_initiator_socket<CompositionNetwork>>(
        ("to_shader" + std::to_string(s)).c_str()));
    to_table.push_back(std::make_unique<tlm_utils::simple_initiator_socket<CompositionNetwork>>(
        ("to_table" + std::to_string(s)).c_str()));
  }
  compositor_ = std::make_unique<Compositor>("compositor", run, *this);
  collector_ = std::make_unique<Collector>("collector", run, *this);
}

}  // namespace rtsim::platform::pixelflow

namespace rtsim::platform::pixelflow {
CompositionNetwork::~CompositionNetwork() = default;
}  // namespace rtsim::platform::pixelflow
