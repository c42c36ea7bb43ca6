// gaudet-pert: the image equals the functional twin for any PERT count, broadcast mode, order
// and quantum; stats.json carries the documented keys and consistent counts; the Broadcast
// Processor and BIC keep the thesis's timings (seed 001 L957-L962) and the hit rule (L920), and a
// streamed packet is read as it arrives (L920, L924);
// Gaudet's expected-latency formula (L1083-L1097).
#include <gtest/gtest.h>
#include <tlm_utils/simple_initiator_socket.h>

#include <cmath>
#include <functional>
#include <iostream>
#include <nlohmann/json.hpp>
#include <span>
#include <systemc>

#include "firmware/accel/gaudet_data_sets.hpp"
#include "platform/functional/scene_tracer.hpp"
#include "platform/machines/gaudet_pert/broadcast_processor.hpp"
#include "platform/machines/gaudet_pert/bus_interface.hpp"
#include "platform/machines/gaudet_pert/data_sets.hpp"
#include "platform/machines/gaudet_pert/expected_latency.hpp"
#include "tests/data_path_support.hpp"
#include "tests/hostile_table.hpp"
#include "tests/systemc_test_support.hpp"
#include "tests/test_support.hpp"

namespace fs = std::filesystem;
using rtsim::test::read_file;
using rtsim::test::read_json;
using rtsim::test::run_ok;
using rtsim::test::run_rtsim;
using rtsim::test::scratch_dir;
using sc_core::SC_NS;
using sc_core::sc_time;

namespace {

/// A Broadcast Processor with the bus's declared timings (1000 / 800 / 400 / 400 ns, seed 001
/// L959-L962) and 64 words of memory, and one BIC listening on it with `id_registers`
/// registers, `overrides` applied to their parameters ("bic.buffers=1"). With `stream_unit` words
/// the BIC streams its packets that many words a record (0: whole packets). Built in the child that
/// simulates (SystemC allows one simulation per process).
struct BusAndBic {
  BusAndBic(const std::string& id_registers, bool adaptive,
            const std::vector<std::string>& overrides = {}, std::uint32_t stream_unit = 0)
      : registry(declared(id_registers, overrides, stream_unit > 0)),
        bp("bp", rtsim::modules::ModuleParams(registry, "bp"), 64, sc_time(0, SC_NS), adaptive,
           /*on_queue=*/false),
        bic(rtsim::modules::ModuleParams(registry, "bic"), stream_unit) {
    bp.attach(bic);
  }
  static rtsim::params::ParamRegistry declared(const std::string& id_registers,
                                               const std::vector<std::string>& overrides,
                                               bool stream) {
    using namespace rtsim::platform::gaudet;
    using rtsim::modules::ParamDecls;
    rtsim::params::ParamRegistry r;
    BroadcastProcessor::declare_params(ParamDecls(r, "bp"));
    BusInterface::declare_params(ParamDecls(r, "bic"),
                                 {.value = id_registers, .description = "test", .source = "test"});
    if (stream) BusInterface::declare_stream_param(ParamDecls(r, "bic"), "true", "test");
    for (const auto& o : overrides) r.apply_override(o);
    return r;
  }
  rtsim::params::ParamRegistry registry;
  rtsim::platform::gaudet::BroadcastProcessor bp;
  rtsim::platform::gaudet::BusInterface bic;
};

/// Writes words[0 .. count) into a broadcast processor's memory through its load port, one
/// 32-bit word at a time (the ID list {ID, address, size} and the packets).
template <typename Socket>
void load_words(Socket& socket, const std::uint32_t* words, std::uint32_t count) {
  for (std::uint32_t a = 0; a < count; ++a) {
    tlm::tlm_generic_payload gp;
    std::uint32_t v = words[a];
    gp.set_command(tlm::TLM_WRITE_COMMAND);
    gp.set_address(a * 4);
    gp.set_data_ptr(reinterpret_cast<unsigned char*>(&v));
    gp.set_data_length(4);
    gp.set_streaming_width(4);
    gp.set_byte_enable_ptr(nullptr);
    sc_core::sc_time d = sc_core::SC_ZERO_TIME;
    socket->b_transport(gp, d);
  }
}

/// The bus tests' memory: IDs 0, 1 and 2, their packets of 2, 5 and 1 words, the ID list as the
/// control processor lays it out ({ID, address, size} an entry) and the packets after it.
constexpr std::uint32_t kThreePackets[] = {0, 9, 2, 1, 11, 5, 2, 16, 1};

/// A thread on a Broadcast Processor's memory port, as the control processor is: it loads
/// `words` (the ID list of 3-word entries {ID, address, size}, then the packets), starts the
/// loop at 0 on `ids` entries, then runs `script` (a test's requests, waits and looks).
struct BusDriver : sc_core::sc_module {
  SC_HAS_PROCESS(BusDriver);
  BusDriver(rtsim::platform::gaudet::BroadcastProcessor& bp, std::span<const std::uint32_t> words,
            std::size_t ids, std::function<void()> script)
      : sc_module("drv"), bp_(bp), words_(words), ids_(ids), script_(std::move(script)) {
    socket.bind(bp.memory.socket);
    SC_THREAD(run);
  }
  void run() {
    load_words(socket, words_.data(), static_cast<std::uint32_t>(words_.size()));
    bp_.start(sc_time(0, SC_NS), ids_, 3);
    script_();
  }
  tlm_utils::simple_initiator_socket<BusDriver> socket{"socket"};

 private:
  rtsim::platform::gaudet::BroadcastProcessor& bp_;
  std::span<const std::uint32_t> words_;
  std::size_t ids_;
  std::function<void()> script_;
};

}  // namespace

TEST(GaudetPert, ImageEqualsTheFunctionalTwinForAnyPertCountModeOrderAndQuantum) {
  const std::string scene = " --scene builtin:npp-412 --width 40 --height 32 --aov id";
  const auto render = run_ok("gp-render", "render --machine gaudet-pert" + scene);
  const std::vector<std::string> variants = {
      "-p pert_count=1",
      "-p pert_count=3 -p broadcast.mode=non-adaptive -p broadcast.order=depth",
      "-p pert_count=5 -p broadcast.mode=direct -p broadcast.order=random",
      "-p pert_count=2 -p broadcast.order=random --quantum \"10 us\"",
      "-p pert_count=7 -p pert.shell.bic.id_registers=1 -p pert.prim.bic.id_registers=1 "
      "-p pert.shade.bic.id_registers=1 -p pert.queue.shell_to_prim=1",
      // One buffer each: the PrimProcessor then asks one packet ahead, not two (a second
      // packet arriving first would take the only buffer for ever).
      "-p pert_count=2 -p pert.shell.bic.buffers=1 -p pert.prim.bic.buffers=1 "
      "-p pert.shade.bic.buffers=1 -p broadcast.order=random",
      // The root packet in the ShellProcessor's memory, one ray and one ID register; and
      // whole packets (no streaming) with the root local, on the bus and in direct memory.
      "-p pert_count=2 -p pert.shell.root_local=true -p pert.shell.rays_in_flight=1 "
      "-p pert.shell.bic.id_registers=1",
      "-p pert_count=3 -p pert.shell.bic.stream=false -p pert.shell.root_local=true",
      "-p pert_count=2 -p broadcast.mode=direct -p pert.shell.root_local=true",
  };
  int i = 0;
  for (const auto& v : variants) {
    const auto run =
        run_ok("gp-run-" + std::to_string(i++), "run --machine gaudet-pert" + scene + " " + v);
    EXPECT_EQ(read_file(run / "image.exr"), read_file(render / "image.exr")) << v;
    EXPECT_EQ(read_file(run / "id.exr"), read_file(render / "id.exr")) << v;
    const auto s = read_json(run / "stats.json");
    EXPECT_EQ(s["gaudet"]["shell"]["records_rejected"], 0) << v;
  }
}

TEST(GaudetPert, PolygonScenesRunAndPatchesAreRefused) {
  const std::string tetra = rtsim::test::shared_path("scenes/tetra-s3.nff");
  const std::string args = " --machine gaudet-pert --scene " + tetra + " --width 32 --height 32";
  const auto run = run_ok("gp-tetra", "run" + args + " -p pert_count=2");
  const auto render = run_ok("gp-tetra-r", "render" + args);
  EXPECT_EQ(read_file(run / "image.exr"), read_file(render / "image.exr"));
  const auto dir = scratch_dir("gp-patch");
  const auto bad =
      run_rtsim("run --machine gaudet-pert --scene " +
                rtsim::test::shared_path("scenes/teapot.bpt") + " -q --out " + dir.string());
  EXPECT_EQ(bad.exit_code, 2) << bad.output;
  EXPECT_NE(bad.output.find("spheres and polygons only"), std::string::npos) << bad.output;
  EXPECT_FALSE(fs::exists(dir / "stats.json"));
}

TEST(GaudetPert, StatsCarryTheDocumentedKeysAndConsistentCounts) {
  const auto run =
      run_ok("gp-stats",
             "run --machine gaudet-pert --scene builtin:npp-408 --width 32 --height 32 "
             "-p pert_count=2");
  const auto s = read_json(run / "stats.json");
  // Fig. 6-1 (seed 001 L980-L989) for scene 408.
  EXPECT_EQ(s["scene_stats"]["shells"], 84);
  EXPECT_EQ(s["scene_stats"]["shell_packets"], 21);
  EXPECT_EQ(s["scene_stats"]["prims"], 512);
  EXPECT_EQ(s["scene_stats"]["prim_packets"], 64);
  EXPECT_EQ(s["scene_stats"]["spheres"], 512);  // the app's own keys stay
  for (const char* bus : {"shade_bus", "shell_bus", "prim_bus"}) {
    ASSERT_TRUE(s["modules"].contains(bus)) << bus;
    const double u = s["modules"][bus]["utilization"];
    EXPECT_GT(u, 0.0) << bus;
    EXPECT_LE(u, 1.0) << bus;
  }
  for (const char* p : {"pert0.shade", "pert1.shell", "pert1.prim", "pert0.queue.shell_to_prim"})
    EXPECT_TRUE(s["modules"].contains(p)) << p;
  // Utilisation over time for every processor and bus: 100 windows whose mean is the frame's
  // utilisation (both cover the frame after the load).
  for (const char* m : {"pert0.shade", "pert1.shell", "pert0.prim", "shell_bus", "prim_bus"}) {
    const auto& mod = s["modules"][m];
    ASSERT_TRUE(mod.contains("utilization_windows")) << m;
    const auto& v = mod["utilization_windows"]["values"];
    ASSERT_EQ(v.size(), 100u) << m;
    double sum = 0;
    for (const auto& x : v) sum += x.get<double>();
    EXPECT_NEAR(sum / 100.0, mod["utilization"].get<double>(), 1e-6) << m;
  }
  // Every ray goes once through each processor; the ShellProcessors' box tests are the twin's.
  const auto& g = s["gaudet"];
  const double rays = s["rays"]["total"];
  EXPECT_EQ(g["shade"]["rays"].get<double>(), rays);
  EXPECT_EQ(g["shell"]["rays"].get<double>(), rays);
  EXPECT_EQ(g["prim"]["rays"].get<double>(), rays);
  EXPECT_NEAR(g["shell"]["box_tests_per_ray"].get<double>() * rays,
              s["accel"]["box_tests"].get<double>(), 1e-6 * rays);
  // Bus stats: mct of the prim data set is 64 IDs x 1 us + 0.4 us (L959, L962).
  EXPECT_NEAR(g["buses"]["prim"]["minimum_cycle_s"].get<double>(), 64.4e-6, 1e-12);
  EXPECT_GT(g["buses"]["prim"]["hit_packets"].get<double>(), 0);
  EXPECT_LT(s["simulated_time_s"].get<double>(), 100.0);
}

TEST(GaudetPert, RunsAreDeterministicAndBadParametersAreBadInput) {
  const std::string base =
      "run --machine gaudet-pert --scene builtin:npp-204 --width 24 --height 24 -p pert_count=3";
  const auto a = read_json(run_ok("gp-det-a", base) / "stats.json");
  const auto b = read_json(run_ok("gp-det-b", base) / "stats.json");
  EXPECT_EQ(a["simulated_time_s"], b["simulated_time_s"]);
  EXPECT_EQ(a["modules"], b["modules"]);
  EXPECT_EQ(a["gaudet"], b["gaudet"]);
  const auto dir = scratch_dir("gp-bad");
  const auto bad = run_rtsim(base + " -p broadcast.mode=adaptiv -q --out " + dir.string());
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.output.find("adaptive"), std::string::npos) << bad.output;
  EXPECT_FALSE(fs::exists(dir / "image.png"));
  // A Broadcast Processor whose idle cycle takes no time would never get past its first moment
  // (it ran for ever before it was refused).
  const auto zero =
      run_rtsim(base + " -p 'broadcast.id_time=0 ns' -p 'broadcast.loop_reset=0 ns' -q --out " +
                dir.string());
  EXPECT_EQ(zero.exit_code, 2) << zero.output;
  EXPECT_NE(zero.output.find("id_time and"), std::string::npos) << zero.output;
  EXPECT_FALSE(fs::exists(dir / "image.png"));
}

TEST(BroadcastProcessor, CycleTimingAndTheHitRule) {
  // Three packets of 2, 5 and 1 words; ID list in memory as the control processor lays it out.
  for (const bool adaptive : {true, false}) {
    EXPECT_EQ(rtsim::test::run_in_child([adaptive] {
                using namespace rtsim::platform::gaudet;
                // One buffer: a second packet must wait.
                BusAndBic rig("4", adaptive, {"bic.buffers=1"});
                BroadcastProcessor& bp = rig.bp;
                BusInterface& bic = rig.bic;
                std::optional<sc_time> got1, got0;
                sc_time released;
                BusDriver drv(bp, kThreePackets, 3, [&] {
                  EXPECT_TRUE(bic.request(1, sc_time(0, SC_NS)));
                  sc_core::wait(bic.changed_event());
                  got1 = bic.next_arrival(1);
                  // The only buffer holds packet 1: packet 0 matches but cannot be caught.
                  EXPECT_TRUE(bic.request(0, sc_core::sc_time_stamp()));
                  sc_core::wait(sc_time(100, sc_core::SC_US));
                  // Packet 0 matched but found no free buffer: not caught yet.
                  EXPECT_FALSE(bic.next_arrival(0).has_value());
                  EXPECT_GT(bic.missed_no_buffer(), 0u);
                  auto p = bic.take(sc_core::sc_time_stamp(), 1);
                  EXPECT_TRUE(p.has_value());
                  bic.release(*p, sc_core::sc_time_stamp());
                  released = sc_core::sc_time_stamp();
                  sc_core::wait(bic.changed_event());
                  got0 = bic.next_arrival(0);
                });
                sc_core::sc_start(sc_time(1, sc_core::SC_MS));
                // Packet 1 (5 words): ID 0's slot, then ID 1 at 1000 ns, the packet after its
                // 1000 ns slot: + 800 + 5 x 400 ns. Non-adaptive, packet 0 (2 words) goes first.
                const sc_time expect1 = adaptive ? sc_time(1000 + 1000 + 800 + 2000, SC_NS)
                                                 : sc_time(2600 + 1000 + 800 + 2000, SC_NS);
                EXPECT_TRUE(got1.has_value());
                if (got1) {
                  EXPECT_EQ(*got1, expect1) << adaptive;
                }
                // Packet 0 comes at its next slot after the buffer was freed at 100 us.
                EXPECT_TRUE(got0.has_value());
                if (got0) {
                  EXPECT_GT(*got0, released);
                  const sc_time cycle = adaptive ? sc_time(3400, SC_NS)
                                                 : sc_time(3000 + 3 * 800 + 8 * 400 + 400, SC_NS);
                  EXPECT_LE(*got0 - released, cycle + sc_time(1800, SC_NS));
                }
                EXPECT_EQ(bp.minimum_cycle(), sc_time(3400, SC_NS));
                return 0;
              }),
              0)
        << (adaptive ? "adaptive" : "non-adaptive");
  }
}

TEST(BusInterface, StreamedPacketIsTakenAtItsFirstRecordAndReadAsItArrives) {
  // Seed 001 L920, L924: the hit line starts the copy into a FIFO buffer, so with `stream` a
  // packet is taken once its first record (here 2 words) is in and word n is readable at
  // first word + (n + 1) x 400 ns; the ID register is still freed at full arrival (L912).
  EXPECT_EQ(rtsim::test::run_in_child([] {
              using namespace rtsim::platform::gaudet;
              BusAndBic rig("1", true, {}, 2);
              BroadcastProcessor& bp = rig.bp;
              BusInterface& bic = rig.bic;
              // Packet 0 (2 words) and packet 1 (5 words), ID list {ID, address, size}.
              const std::uint32_t words[] = {0, 6, 2, 1, 8, 5, 7, 7, 1, 2, 3, 4, 5};
              bool done = false;
              BusDriver drv(bp, words, 2, [&] {
                EXPECT_TRUE(bic.request(1, sc_time(0, SC_NS)));
                sc_core::wait(bic.changed_event());
                // ID 1's strobe at 1000 ns, its slot ends at 2000, the words start after the
                // 800 ns overhead (2800) and the last is in at 4800.
                EXPECT_EQ(bic.next_arrival(1), sc_time(2800 + 2 * 400, SC_NS));
                EXPECT_FALSE(bic.take(sc_time(3599, SC_NS)).has_value());
                const auto p = bic.take(sc_time(3600, SC_NS));
                EXPECT_TRUE(p.has_value());
                if (!p) return;
                EXPECT_EQ(p->arrival, sc_time(4800, SC_NS));
                EXPECT_EQ(p->words_in(1), sc_time(3200, SC_NS));
                EXPECT_EQ(p->words_in(4), sc_time(4400, SC_NS));
                EXPECT_EQ(p->words_in(5), sc_time(4800, SC_NS));
                EXPECT_EQ(p->words_in(9), sc_time(4800, SC_NS));
                EXPECT_EQ(p->words.size(), 5u);
                EXPECT_EQ(p->words[4], 5u);
                // The register is freed when the packet has been received (L912).
                EXPECT_FALSE(bic.register_free(sc_time(4799, SC_NS)));
                EXPECT_TRUE(bic.register_free(sc_time(4800, SC_NS)));
                bic.release(*p, sc_time(3600, SC_NS));
                done = true;
              });
              sc_core::sc_start(sc_time(1, sc_core::SC_MS));
              EXPECT_TRUE(done);
              return ::testing::Test::HasFailure() ? 1 : 0;
            }),
            0);
}

TEST(BusInterface, ARequestWithdrawnAtTheStrobesTimeIsStillMatched) {
  // A strobe sees the registers as they were just before it (bus_interface.hpp): a request
  // withdrawn at the very time of its ID's strobe is matched, its packet streams in and is
  // dropped, and the register is freed on receipt (L912) -- whether the processor withdraws it
  // before the Broadcast Processor strobes (a method, which SystemC runs before threads) or
  // after (a thread one delta later). ID 1's strobe is at 1000 ns: its 5-word packet is in at
  // 1000 + 1000 + 800 + 5 x 400 = 4800 ns.
  for (const bool before : {true, false}) {
    SCOPED_TRACE(before ? "withdrawn before the strobe" : "withdrawn after the strobe");
    EXPECT_EQ(rtsim::test::run_in_child([before] {
                using namespace rtsim::platform::gaudet;
                BusAndBic rig("1", true);
                BroadcastProcessor& bp = rig.bp;
                BusInterface& bic = rig.bic;
                const std::uint32_t words[] = {0, 6, 2, 1, 8, 5, 7, 7, 1, 2, 3, 4, 5};
                struct Driver : sc_core::sc_module {
                  SC_HAS_PROCESS(Driver);
                  Driver(sc_core::sc_module_name n, BroadcastProcessor& b, BusInterface& i,
                         const std::uint32_t* w, bool early)
                      : sc_module(n), bp(b), bic(i), words(w), early(early) {
                    SC_THREAD(run);
                    SC_METHOD(withdraw_early);
                    sensitive << at_strobe;
                    dont_initialize();
                  }
                  void run() {
                    load_words(socket, words, 13);
                    bp.start(sc_time(0, SC_NS), 2, 3);
                    EXPECT_TRUE(bic.request(1, sc_time(0, SC_NS)));
                    if (early) {
                      at_strobe.notify(sc_time(1000, SC_NS));
                      return;
                    }
                    sc_core::wait(sc_time(1000, SC_NS));
                    sc_core::wait(sc_core::SC_ZERO_TIME);
                    withdraw();
                  }
                  void withdraw_early() { withdraw(); }
                  void withdraw() {
                    EXPECT_EQ(sc_core::sc_time_stamp(), sc_time(1000, SC_NS));
                    bic.cancel(1, sc_core::sc_time_stamp());
                    EXPECT_FALSE(bic.pending(1));
                  }
                  tlm_utils::simple_initiator_socket<Driver> socket{"socket"};
                  sc_core::sc_event at_strobe;
                  BroadcastProcessor& bp;
                  BusInterface& bic;
                  const std::uint32_t* words;
                  bool early;
                } drv("drv", bp, bic, words, before);
                drv.socket.bind(bp.memory.socket);
                sc_core::sc_start(sc_time(1, sc_core::SC_MS));
                EXPECT_EQ(bp.stats().captures, 1u);
                EXPECT_EQ(bp.stats().hit_packets, 1u);
                // Dropped: nothing to take, and its buffer is free once the packet is in.
                EXPECT_FALSE(bic.next_arrival().has_value());
                EXPECT_FALSE(bic.take(sc_time(1, sc_core::SC_MS)).has_value());
                EXPECT_FALSE(bic.register_free(sc_time(4799, SC_NS)));
                EXPECT_TRUE(bic.register_free(sc_time(4800, SC_NS)));
                // Nothing is wanted any more: the loop went back to sleep.
                EXPECT_FALSE(bic.requested(1, sc_time(1001, SC_NS)));
                return ::testing::Test::HasFailure() ? 1 : 0;
              }),
              0);
  }
}

TEST(BroadcastProcessor, ARequestMadeWhileAPacketIsSentWaitsForItsEnd) {
  // The loop is busy while it sends a packet: a request made meanwhile is strobed at its first
  // slot after the packet, not during it. IDs 0,
  // 1, 2 with 2, 5 and 1 words: ID 1's strobe at 1000 ns, its packet on the bus until 1000 +
  // 1000 + 800 + 5 x 400 = 4800 ns; ID 2, asked for at 3000 ns, has the next slot, at 4800 ns:
  // in at 4800 + 1000 + 800 + 400 = 7000 ns.
  EXPECT_EQ(rtsim::test::run_in_child([] {
              using namespace rtsim::platform::gaudet;
              BusAndBic rig("2", true);
              BroadcastProcessor& bp = rig.bp;
              BusInterface& bic = rig.bic;
              std::optional<sc_time> got2;
              BusDriver drv(bp, kThreePackets, 3, [&] {
                EXPECT_TRUE(bic.request(1, sc_time(0, SC_NS)));
                sc_core::wait(sc_time(3000, SC_NS));
                EXPECT_EQ(bic.next_arrival(1), sc_time(4800, SC_NS));
                EXPECT_TRUE(bic.request(2, sc_core::sc_time_stamp()));
                sc_core::wait(sc_time(10, sc_core::SC_US));
                got2 = bic.next_arrival(2);
              });
              sc_core::sc_start(sc_time(1, sc_core::SC_MS));
              EXPECT_EQ(got2, std::optional<sc_time>(sc_time(7000, SC_NS)));
              EXPECT_EQ(bp.stats().hit_packets, 2u);
              return ::testing::Test::HasFailure() ? 1 : 0;
            }),
            0);
}

TEST(BroadcastProcessor, ItsCountsRunToTheFrameEnd) {
  // The loop sleeps while no BIC wants anything, and its IDs and cycles are worked out, not
  // passed one by one: at the frame's end (run_to) they count every slot begun by then, wherever
  // the loop last woke. IDs 0, 1, 2 (2, 5, 1 words), adaptive: ID 1 asked for at 0, strobed at
  // 1000 ns, its packet on the bus until 4800; ID 2's slot to 5800, the reset to 6200 (the first
  // cycle); then cycles of 3 x 1000 + 400 ns. By 100 us: 27 more cycles (to 98,000 ns) and the
  // slots of IDs 0 and 1 (98,000 and 99,000; ID 2's begins at 100,000): 86 IDs, 28 cycles.
  EXPECT_EQ(rtsim::test::run_in_child([] {
              using namespace rtsim::platform::gaudet;
              BusAndBic rig("2", true);
              BroadcastProcessor& bp = rig.bp;
              BusInterface& bic = rig.bic;
              BroadcastProcessor::Stats before;
              BusDriver drv(bp, kThreePackets, 3, [&] {
                EXPECT_TRUE(bic.request(1, sc_time(0, SC_NS)));
                sc_core::wait(sc_time(100, sc_core::SC_US));
                before = bp.stats();
                bp.run_to(sc_core::sc_time_stamp());
              });
              sc_core::sc_start(sc_time(1, sc_core::SC_MS));
              // Asleep since its packet: its counts stopped at ID 1's slot.
              EXPECT_EQ(before.ids, 2u);
              EXPECT_EQ(before.cycles, 0u);
              EXPECT_EQ(bp.stats().ids, 86u);
              EXPECT_EQ(bp.stats().cycles, 28u);
              EXPECT_EQ(bp.stats().hit_packets, 1u);
              return ::testing::Test::HasFailure() ? 1 : 0;
            }),
            0);
}

TEST(ExpectedLatency, GaudetsFormula) {
  using rtsim::platform::gaudet::EalInputs;
  using rtsim::platform::gaudet::expected_average_latency_s;
  // One processor, one packet a ray: half the minimum cycle plus the packet (L1091, i = 0).
  EXPECT_NEAR(expected_average_latency_s(EalInputs{1, 100, 100, 64.4e-6, 34.4e-6}),
              64.4e-6 / 2 + 34.4e-6, 1e-15);
  // The note's transcription (note 001 §4.3e) for n = 8, p/r = 1.45 (L1064's example).
  const EalInputs in{8, 145, 100, 64.4e-6, 34.4e-6};
  double ref = 0;
  for (int i = 0; i <= 8; ++i) {
    const double c = std::tgamma(9) / (std::tgamma(i + 1) * std::tgamma(9 - i));
    ref += c * std::pow(0.55, 8 - i) * std::pow(0.45, i) *
           ((64.4e-6 + (8 + i - 1) * 34.4e-6) / 2 + 34.4e-6);
  }
  EXPECT_NEAR(expected_average_latency_s(in), ref, 1e-12);
  std::cout << "eal(n=8, p/r=1.45, mct=64.4us, apt=34.4us) = "
            << expected_average_latency_s(in) * 1e6 << " us\n";
}

TEST(GaudetPert, ClassNamesSetEveryPertAndInstanceNamesOne) {
  // DESIGN.md "Configuration": pert.shell.bic.id_registers sets every PERT's BIC, the
  // instance's name one PERT's; the module reads its own under its SystemC name.
  const std::string base =
      "run --machine gaudet-pert --scene builtin:npp-412 --width 16 --height 16 -p pert_count=2";
  auto frame = [&](const std::string& tag, const std::string& extra) {
    const auto stats = read_json(run_ok(tag, base + extra) / "stats.json");
    return stats["simulated_time_s"].get<double>();
  };
  const double plain = frame("gp-inst-0", "");
  // The default is 1 register: 4 differs from it.
  const double one = frame("gp-inst-1", " -p pert1.shell.bic.id_registers=4");
  const double all = frame("gp-inst-2", " -p pert.shell.bic.id_registers=4");
  const double both =
      frame("gp-inst-3", " -p pert.shell.bic.id_registers=4 -p pert1.shell.bic.id_registers=1");
  std::cout << "frame time: default " << plain << " s, pert1 only " << one << " s, every PERT "
            << all << " s, every PERT but pert1 " << both << " s\n";
  EXPECT_NE(one, plain);
  EXPECT_NE(one, all);
  EXPECT_NE(both, all);
  // The stats name the modules as the parameters do.
  const auto stats = read_json(run_ok("gp-inst-4", base) / "stats.json");
  for (const char* m : {"pert1.shell", "pert1.shell.bic", "pert1.queue.shell_to_prim", "shell_bus"})
    EXPECT_TRUE(stats["modules"].contains(m)) << m;
  EXPECT_GT(stats["modules"]["pert0.shell.bic"]["requests"].get<double>(), 0.0);
  // An instance the run does not build is bad input.
  const auto dir = scratch_dir("gp-inst-bad");
  const auto bad = run_rtsim(base + " -p pert2.shell.clock=4MHz -q --out " + dir.string());
  EXPECT_EQ(bad.exit_code, 2) << bad.output;
  EXPECT_NE(bad.output.find("pert_count is 2"), std::string::npos) << bad.output;
}

// gaudet-pert's own hostile rows (tests/hostile_table.hpp): issue 30 item 2, corrupted ID list
// words, and faults that name no memory or a word past its end.
TEST(GaudetPertHostile, EveryRowExitsAsAllowedWithinItsMemory) {
  using rtsim::test::hostile_run;
  using rtsim::test::LimitedRun;
  std::vector<rtsim::test::HostileCase> c;
  for (const char* memory : {"shell_bus.memory", "prim_bus.memory"})
    for (const char* word : {"0", "1", "2", "3", "6", "9"})
      for (const char* mask : {"0xFFFFFFFF", "0x80000000"})
        c.push_back({std::string("--fault ") + memory + ":" + word + ":" + mask,
                     hostile_run("gaudet-pert", "builtin:npp-412",
                                 {"--fault", std::string(memory) + ":" + word + ":" + mask}),
                     {0, 2}});
  c.push_back(
      {"--fault past the memory's end",
       hostile_run("gaudet-pert", "builtin:npp-412", {"--fault", "prim_bus.memory:99999999:0x1"}),
       {2}});
  c.push_back(
      {"--fault on no memory",
       hostile_run("gaudet-pert", "builtin:npp-412", {"--fault", "prim_bus.memroy:0:0x1"}),
       {2},
       [](const fs::path&, const LimitedRun& r) { return rtsim::test::says(r, "did you mean"); }});
  rtsim::test::run_hostile_table(scratch_dir("gaudet-hostile"), c);
}

// The ShellProcessors box-test the SHELL records in the packets their BICs caught; emptying the
// box of the first SHELL in the Shell bus's memory hides its subtree. The PrimProcessors test
// the PRIM records of theirs: a sphere whose radius word is corrupted to a huge value is hit by
// every ray that reaches its leaf shell. A corrupted ID list stalls the machine: the run says so
// (exit 2), writing nothing.
TEST(GaudetPert, ShellBusMemoryWordChangesTheImage) {
  // The first SHELL of packet 0 (the root's children, L662) as the Shell bus's memory holds it:
  // flip the sign of one corner coordinate so that its box becomes empty; every ray then misses
  // that shell's subtree. The ShellProcessors must take packet 0 off the bus for that
  // (pert.shell.root_local=false; by default they read it from their own memory).
  const fs::path dir = rtsim::test::scratch_dir("data-path-gaudet");
  fs::create_directories(dir);
  auto m = rtsim::test::prepare_machine("gaudet-pert", "builtin:npp-412");
  const auto& twin = m->twin;
  const auto& scene = m->scene;
  const auto* search = dynamic_cast<const rtsim::functional::ShellSearch*>(twin.tracer.get());
  ASSERT_NE(search, nullptr);
  const auto sets = rtsim::platform::gaudet::make_pert_data_sets(
      search->tree(), *twin.geometry, scene, {}, rtsim::platform::gaudet::BroadcastOrder::kBreadth,
      1985);
  // ID list entry 0 is {ID 0, address, size} in breadth order.
  ASSERT_EQ(sets.shell.memory.at(0), 0u);
  const std::uint32_t address = sets.shell.memory.at(1);
  const auto shell = rtsim::accel::decode_shell(
      std::span<const std::uint32_t>(sets.shell.memory).subspan(address, 8));
  // max.x is word 2 of the record, min.x word 5: negating max.x empties the box if
  // max.x > -min.x, negating min.x if min.x < -max.x.
  const double lo = shell.box.lo.x, hi = shell.box.hi.x;
  ASSERT_TRUE(hi > -lo || lo < -hi) << lo << " " << hi;
  const std::uint64_t word = address + (hi > -lo ? 2u : 5u);
  const std::vector<std::string> two = {"pert_count=2", "pert.shell.root_local=false"};
  const rtsim::test::data_path::Frame clean = rtsim::test::data_path::simulate(
      "gaudet-pert", "builtin:npp-412", two, {}, dir / "clean.bin");
  const rtsim::test::data_path::Frame faulty = rtsim::test::data_path::simulate(
      "gaudet-pert", "builtin:npp-412", two, {{"shell_bus.memory", word, 0x80000000u}},
      dir / "faulty.bin");
  ASSERT_TRUE(clean.ok && faulty.ok);
  const std::size_t changed = rtsim::test::data_path::pixels_differing(clean, faulty);
  std::printf(
      "shell_bus.memory word %llu (SHELL 0 of packet 0, box x %g..%g) flipped: %zu of %d "
      "pixels changed\n",
      static_cast<unsigned long long>(word), lo, hi, changed,
      rtsim::test::data_path::kSize * rtsim::test::data_path::kSize);
  EXPECT_GT(changed, 0u);

  // The first PRIM record of packet 0 in the Prim bus's memory, a sphere: raising its radius's
  // exponent by 128 makes it enclose the whole scene, so every ray that reaches its leaf shell
  // (the boxes still cull) hits it.
  ASSERT_EQ(sets.prim.memory.at(0), 0u);
  const std::uint32_t prim_address = sets.prim.memory.at(1);
  ASSERT_EQ(sets.prim.memory.at(prim_address + 2),
            static_cast<std::uint32_t>(rtsim::accel::PrimType::Sphere));
  const std::uint64_t radius_word = prim_address + 6;  // prim_id, surface, type, centre[3], radius
  const rtsim::test::data_path::Frame big = rtsim::test::data_path::simulate(
      "gaudet-pert", "builtin:npp-412", two, {{"prim_bus.memory", radius_word, 0x40000000u}},
      dir / "big.bin");
  ASSERT_TRUE(big.ok);
  const std::size_t changed_prim = rtsim::test::data_path::pixels_differing(clean, big);
  std::printf(
      "prim_bus.memory word %llu (radius of the first sphere) corrupted: %zu of %d pixels "
      "changed\n",
      static_cast<unsigned long long>(radius_word), changed_prim,
      rtsim::test::data_path::kSize * rtsim::test::data_path::kSize);
  EXPECT_GT(changed_prim, 0u);
  fs::remove_all(dir);
}

TEST(GaudetPert, ACorruptedIdListStallsItWithAClearError) {
  // Word 0 of the Shell bus's memory is the ID of ID list entry 0 (packet 0): with it changed
  // no slot carries packet 0, every ShellProcessor waits for it for ever, and the run must say
  // so instead of writing a partial frame (or spinning through broadcast cycles).
  const fs::path dir = rtsim::test::scratch_dir("fault-stall");
  const auto r = run_rtsim(
      "run --machine gaudet-pert --scene builtin:npp-412 --width 16 "
      "--height 16 -q -p pert_count=2 --fault shell_bus.memory:0:0x1 --out " +
      dir.string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("stopped with work outstanding"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir));
}
