// modules::TokenRing: a message's path round an idle ring, packets, the three service
// disciplines, and the mean waiting time of a symmetric ring under Poisson load against
// polling-system theory (Takagi, "Queuing analysis of polling models", ACM Computing Surveys
// 20(1), 1988: symmetric systems, constant switchover times).
#include "modules/token_ring.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <systemc>
#include <vector>

#include "modules/module_params.hpp"
#include "modules/statistics.hpp"
#include "params/registry.hpp"
#include "tests/systemc_test_support.hpp"

namespace {

using rtsim::modules::ModuleParams;
using rtsim::modules::ParamDecls;
using rtsim::modules::TokenRing;
using sc_core::SC_NS;
using sc_core::sc_time;

/// A registry holding one ring's parameters under "ring".
rtsim::params::ParamRegistry ring_params(const std::string& hop, const std::string& service,
                                         const std::string& max_packet = "1024",
                                         const std::string& header = "8") {
  rtsim::params::ParamRegistry r;
  TokenRing::declare_params(ParamDecls(r, "ring"), {.bandwidth = "5 Gbit/s",
                                                    .bandwidth_source = "seed 004 L284",
                                                    .hop_latency = hop,
                                                    .max_packet_bytes = max_packet,
                                                    .header_bytes = header,
                                                    .service = service,
                                                    .source = "test"});
  return r;
}

struct Arrival {
  std::uint64_t id;
  std::size_t destination;
  sc_time at;
};

/// Sends the messages given at their times from one thread.
struct Script : sc_core::sc_module {
  struct Send {
    sc_time at;
    std::size_t from, to;
    std::uint64_t bytes;
  };
  TokenRing& ring;
  std::vector<Send> sends;
  SC_HAS_PROCESS(Script);
  Script(sc_core::sc_module_name n, TokenRing& r, std::vector<Send> s)
      : sc_core::sc_module(n), ring(r), sends(std::move(s)) {
    SC_THREAD(run);
  }
  void run() {
    for (const Send& s : sends) {
      if (s.at > sc_core::sc_time_stamp()) sc_core::wait(s.at - sc_core::sc_time_stamp());
      ring.send(s.from, s.to, s.bytes, s.at);
    }
  }
};

TEST(TokenRing, OneMessageRoundAnIdleRing) {
  EXPECT_EQ(rtsim::test::run_in_child([] {
              const auto r = ring_params("10 ns", "exhaustive");
              TokenRing ring("ring", TokenRing::read_config(ModuleParams(r, "ring")), 8);
              std::vector<Arrival> got;
              ring.on_delivery([&](std::uint64_t id, std::size_t d, const sc_time& at) {
                got.push_back({id, d, at});
              });
              // Sent at 1 us from node 2 to node 5. The token, circulating idle since 0 at
              // 10 ns a hop, is at node 4 at 1 us (100 hops) and at node 2 at 1.060 us; 1000 +
              // 8 bytes at 5 Gbit/s take 1612.8 ns; then 3 hops to node 5.
              Script s("script", ring, {{sc_time(1000, SC_NS), 2, 5, 1000}});
              sc_core::sc_start();
              EXPECT_EQ(got.size(), 1u);
              EXPECT_EQ(got.at(0).destination, 5u);
              EXPECT_EQ(got.at(0).at, sc_time(1060 + 1612.8 + 30, SC_NS));
              EXPECT_EQ(ring.transmission(1008), sc_time(1612.8, SC_NS));
              EXPECT_EQ(ring.busy(), sc_time(1612.8, SC_NS));
              EXPECT_NEAR(ring.mean_wait_s(2), 60e-9, 1e-15);
              // Its passes at node 0 all came while it went round idle: 80 ns a rotation.
              EXPECT_NEAR(ring.mean_rotation_s(), 80e-9, 1e-15);
              // The holder signal: node 2 (level 3) while it sent.
              const auto& h = ring.holder_changes();
              EXPECT_EQ(h.size(), 2u);
              EXPECT_EQ(h.at(0).level, 3);
              EXPECT_EQ(h.at(0).t, sc_time(1060, SC_NS).value());
              EXPECT_EQ(h.at(1).level, 0);
              return 0;
            }),
            0);
}

/// Three messages queued at once at node 1 of a 4-node ring, 2500 bytes each (3 packets of at
/// most 1024 bytes): when does each arrive under a discipline?
std::vector<sc_time> three_long_messages(const std::string& service) {
  const auto r = ring_params("100 ns", service);
  TokenRing ring("ring", TokenRing::read_config(ModuleParams(r, "ring")), 4);
  std::vector<sc_time> at;
  ring.on_delivery([&](std::uint64_t, std::size_t, const sc_time& t) { at.push_back(t); });
  Script s("script", ring,
           {{sc_time(50, SC_NS), 1, 1, 2500},
            {sc_time(50, SC_NS), 1, 1, 2500},
            {sc_time(50, SC_NS), 1, 1, 2500}});
  sc_core::sc_start();
  EXPECT_EQ(ring.packets(), 9u);
  return at;
}

TEST(TokenRing, ExhaustiveSendsEveryPacketInOneVisit) {
  EXPECT_EQ(rtsim::test::run_in_child([] {
              const auto at = three_long_messages("exhaustive");
              // The token reaches node 1 at 100 ns; the 9 packets (2 x (1024 + 8) + 460 bytes
              // a message) go back to back: 2524 bytes = 4038.4 ns a message.
              EXPECT_EQ(at, (std::vector<sc_time>{sc_time(100 + 4038.4, SC_NS),
                                                  sc_time(100 + 2 * 4038.4, SC_NS),
                                                  sc_time(100 + 3 * 4038.4, SC_NS)}));
              return 0;
            }),
            0);
}

TEST(TokenRing, OnePacketAVisitWaitsARotationBetweenPackets) {
  EXPECT_EQ(rtsim::test::run_in_child([] {
              const auto at = three_long_messages("one_packet");
              // A packet a visit, then 4 hops (400 ns) round the otherwise idle ring.
              EXPECT_EQ(at.size(), 3u);
              if (at.size() != 3) return 1;
              const double first = at[0].to_seconds() * 1e9;
              // Packets 1-3 of message 0: 100 + 2 x (1651.2 + 400) + 736 ns.
              EXPECT_NEAR(first, 100 + 2 * (1651.2 + 400) + 736, 1e-3);
              EXPECT_NEAR(at[2].to_seconds() * 1e9 - first, 2 * (2 * (1651.2 + 400) + (736 + 400)),
                          1e-3);
              return 0;
            }),
            0);
}

// --- Against polling-system theory ----------------------------------------------------------

constexpr std::size_t kNodes = 8;
constexpr double kHopNs = 50;           ///< r: R = N r = 400 ns a rotation of switchovers
constexpr std::uint64_t kPacket = 250;  ///< 242 bytes + 8 header = 2000 bits = b = 400 ns

/// Symmetric polling system, constant service time b and switchover r (so R = N r, delta^2 = 0),
/// Poisson arrivals at rate lambda per node, rho = N lambda b. Mean wait (Takagi 1988):
///   exhaustive  W = (N lambda b^2 + R (1 - rho / N)) / (2 (1 - rho))
///   gated       W = (N lambda b^2 + R (1 + rho / N)) / (2 (1 - rho))
///   one packet  W = (N lambda b^2 + R (1 + rho / N)) / (2 (1 - rho - lambda R))
/// (the last from the pseudo-conservation law for 1-limited service, Boxma & Groenendijk 1987,
/// which for a symmetric system gives every node's wait).
double theory_wait_s(rtsim::modules::RingService s, double rho, double b, double r) {
  const double n = static_cast<double>(kNodes);
  const double big_r = n * r;
  const double lambda = rho / (n * b);
  switch (s) {
    case rtsim::modules::RingService::kExhaustive:
      return (n * lambda * b * b + big_r * (1 - rho / n)) / (2 * (1 - rho));
    case rtsim::modules::RingService::kGated:
      return (n * lambda * b * b + big_r * (1 + rho / n)) / (2 * (1 - rho));
    case rtsim::modules::RingService::kOnePacket:
      return (n * lambda * b * b + big_r * (1 + rho / n)) / (2 * (1 - rho - lambda * big_r));
  }
  return 0;
}

/// Poisson arrivals at every node (all queued at time 0 with their future stamps), `packets` in
/// all; returns the ring's mean wait over the packets that arrived after a warm-up of 2% of
/// them, and checks the ring's own statistics on the way.
struct Measured {
  double wait_s = 0, rotation_s = 0, utilisation = 0;
};

Measured simulate(const std::string& service, double rho, std::uint64_t packets,
                  std::uint64_t seed) {
  const auto r = ring_params("50 ns", service, "1024", "8");
  TokenRing ring("ring", TokenRing::read_config(ModuleParams(r, "ring")), kNodes);
  const double b = ring.transmission(kPacket).to_seconds();
  const double lambda = rho / (kNodes * b);
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Script::Send> sends;
  std::vector<double> t(kNodes, 0.0);
  for (std::uint64_t i = 0; i < packets; ++i) {
    // Node k = i mod N: every node its own Poisson stream of rate lambda.
    const std::size_t k = i % kNodes;
    t[k] += -std::log1p(-u(rng)) / lambda;
    sends.push_back({sc_time::from_value(static_cast<std::uint64_t>(t[k] * 1e12)), k,
                     (k + kNodes / 2) % kNodes, kPacket - 8});
  }
  std::sort(sends.begin(), sends.end(),
            [](const Script::Send& a, const Script::Send& c) { return a.at < c.at; });
  const double warm = sends[packets / 50].at.to_seconds();
  double sum = 0;
  std::uint64_t count = 0;
  // Each message is one packet: its wait = arrival - transmission - hops - ready.
  std::vector<double> ready(packets);
  std::vector<std::size_t> from(packets);
  for (std::uint64_t i = 0; i < packets; ++i) {
    ready[i] = sends[i].at.to_seconds();
    from[i] = sends[i].from;
  }
  ring.on_delivery([&](std::uint64_t id, std::size_t d, const sc_time& at) {
    if (ready[id] < warm) return;
    const double start =
        at.to_seconds() - b - static_cast<double>(ring.hops(from[id], d)) * kHopNs * 1e-9;
    sum += start - ready[id];
    ++count;
  });
  // Sent in time order from one thread (the script waits for each send's time).
  Script s("script", ring, std::move(sends));
  sc_core::sc_start();
  EXPECT_EQ(ring.packets(), packets);
  Measured m;
  m.wait_s = sum / static_cast<double>(count);
  m.rotation_s = ring.mean_rotation_s();
  m.utilisation = ring.busy().to_seconds() / sc_core::sc_time_stamp().to_seconds();
  return m;
}

void check_against_theory(const std::string& service, rtsim::modules::RingService kind,
                          const std::vector<double>& loads) {
  const double b = 400e-9, r = kHopNs * 1e-9;
  std::printf("%-10s %5s %12s %12s %8s %14s %14s\n", "service", "rho", "W theory", "W model",
              "error", "cycle theory", "cycle model");
  for (double rho : loads) {
    ASSERT_EQ(rtsim::test::run_in_child([&] {
                const Measured m = simulate(service, rho, 400000, 1995);
                const double w = theory_wait_s(kind, rho, b, r);
                // Mean cycle (token rotation) R / (1 - rho) for each discipline.
                const double cycle = kNodes * r / (1 - rho);
                std::printf("%-10s %5.2f %9.1f ns %9.1f ns %+7.2f%% %11.1f ns %11.1f ns\n",
                            service.c_str(), rho, w * 1e9, m.wait_s * 1e9, 100 * (m.wait_s / w - 1),
                            cycle * 1e9, m.rotation_s * 1e9);
                EXPECT_NEAR(m.wait_s, w, 0.03 * w) << service << " rho " << rho;
                EXPECT_NEAR(m.rotation_s, cycle, 0.03 * cycle) << service << " rho " << rho;
                EXPECT_NEAR(m.utilisation, rho, 0.02) << service << " rho " << rho;
                return 0;
              }),
              0)
        << service << " at load " << rho;
  }
}

const std::vector<double> kLoads = {0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9};

TEST(TokenRingTheory, ExhaustiveServiceMeanWait) {
  check_against_theory("exhaustive", rtsim::modules::RingService::kExhaustive, kLoads);
}

TEST(TokenRingTheory, GatedServiceMeanWait) {
  check_against_theory("gated", rtsim::modules::RingService::kGated, kLoads);
}

// One packet a visit is stable only while rho + lambda R < 1, here rho < 8/9.
TEST(TokenRingTheory, OnePacketServiceMeanWait) {
  check_against_theory("one_packet", rtsim::modules::RingService::kOnePacket,
                       {0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8});
}

}  // namespace
