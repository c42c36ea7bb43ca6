// ullner-array (seed 000 §2.5): the router reaches every processor by neighbour hops; the
// subvolume mappings keep neighbouring subvolumes on neighbouring processors (L866); the image,
// summed from the contributions the result messages carry, equals the functional twin's for every
// array size and mapping; a lost result message or a corrupted polygon word changes it; the
// termination detector's credit comes back whole.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <string>
#include <vector>

#include "modules/mesh_topology.hpp"
#include "platform/machines/ullner_array/intersection_pipeline.hpp"
#include "platform/machines/ullner_array/subvolume_mapping.hpp"
#include "tests/child_processes.hpp"
#include "tests/hostile_table.hpp"
#include "tests/test_support.hpp"

namespace fs = std::filesystem;
using rtsim::modules::Direction;
using rtsim::modules::GridNode;
using rtsim::modules::MeshTopology;
using rtsim::platform::ullner_array::Mapping;
using rtsim::platform::ullner_array::SubvolumeMapping;
using rtsim::test::read_file;
using rtsim::test::read_json;
using rtsim::test::run_rtsim;
using rtsim::test::scratch_dir;

namespace {

TEST(MeshTopology, DimensionOrderRoutesReachEveryNodeInTheFewestHops) {
  for (const bool wrap : {false, true}) {
    const MeshTopology t(5, 7, wrap, wrap);
    for (int a = 0; a < t.nodes(); ++a)
      for (int b = 0; b < t.nodes(); ++b) {
        GridNode at = t.node(a);
        const GridNode to = t.node(b);
        const int hops = t.hops(at, to);
        int taken = 0;
        while (!(at == to)) {
          const auto next = t.neighbour(at, t.next_hop(at, to));
          ASSERT_TRUE(next.has_value()) << "routed off the array";
          at = *next;
          ASSERT_LE(++taken, hops);
        }
        EXPECT_EQ(taken, hops);
      }
  }
  const MeshTopology mesh(3, 3, false, false);
  EXPECT_FALSE(mesh.neighbour({0, 0}, Direction::kNorth).has_value());
  const MeshTopology torus(3, 3, true, true);
  EXPECT_EQ(*torus.neighbour({0, 0}, Direction::kNorth), (GridNode{2, 0}));
  EXPECT_EQ(torus.hops({0, 0}, {0, 2}), 1);  // the wrap link is shorter
  EXPECT_EQ(mesh.hops({0, 0}, {0, 2}), 2);
}

/// A mapping of `kind` of n^3 subvolumes onto rows x cols processors; `axes`: depth, column and
/// row axes.
SubvolumeMapping mapping_of(Mapping kind, int rows, int cols, int n, std::array<int, 3> axes) {
  SubvolumeMapping m;
  m.rows = rows;
  m.cols = cols;
  m.n = n;
  m.mapping = kind;
  m.depth_axis = axes[0];
  m.col_axis = axes[1];
  m.row_axis = axes[2];
  return m;
}

TEST(SubvolumeMapping, NeighbouringSubvolumesLandOnConnectedProcessors) {
  for (const Mapping kind : {Mapping::kStraight, Mapping::kSkew, Mapping::kTorus}) {
    for (const auto& [rows, cols, n] :
         {std::tuple{8, 8, 8}, std::tuple{8, 8, 16}, std::tuple{4, 6, 12}, std::tuple{3, 3, 9}}) {
      const SubvolumeMapping m = mapping_of(kind, rows, cols, n, {1, 0, 2});
      const MeshTopology t(rows, cols, m.wrap_rows(), m.wrap_cols());
      std::vector<int> owned(static_cast<std::size_t>(t.nodes()), 0);
      for (int x = 0; x < n; ++x)
        for (int y = 0; y < n; ++y)
          for (int z = 0; z < n; ++z) {
            const rtsim::accel::CellIndex c{x, y, z};
            const GridNode here = m.node_of(c);
            ++owned[static_cast<std::size_t>(t.index(here))];
            for (int axis = 0; axis < 3; ++axis) {
              rtsim::accel::CellIndex d = c;
              if (axis == 0) ++d.x;
              if (axis == 1) ++d.y;
              if (axis == 2) ++d.z;
              if (d[axis] >= n) continue;
              const GridNode there = m.node_of(d);
              EXPECT_TRUE(here == there || t.direction_to(here, there).has_value())
                  << "mapping " << static_cast<int>(kind) << " " << rows << "x" << cols << " n "
                  << n << ": (" << x << "," << y << "," << z << ") axis " << axis;
            }
          }
      // Every processor owns its share: n^3 / (rows cols) subvolumes.
      for (const int k : owned) EXPECT_EQ(k, n * n * n / (rows * cols));
    }
  }
}

// A processor's keep test looks only at its own block of each depth layer (owned_along_cols x
// owned_along_rows): that block must be exactly the cells node_of gives it, for every mapping,
// both flips, arrays larger and smaller than the subdivision, and subdivisions that do not
// divide evenly.
TEST(SubvolumeMapping, EachProcessorsBlockOfALayerIsExactlyTheCellsItOwns) {
  for (const Mapping kind : {Mapping::kStraight, Mapping::kSkew, Mapping::kTorus})
    for (const auto& [rows, cols, n] :
         {std::tuple{8, 8, 8}, std::tuple{8, 8, 16}, std::tuple{4, 6, 13}, std::tuple{5, 3, 2},
          std::tuple{1, 1, 3}})
      for (const bool flip : {false, true}) {
        SubvolumeMapping m = mapping_of(kind, rows, cols, n, {0, 2, 1});
        m.flip_cols = flip;
        m.flip_rows = !flip;
        for (int row = 0; row < rows; ++row)
          for (int col = 0; col < cols; ++col)
            for (int d = 0; d < n; ++d) {
              const auto a = m.owned_along_cols(col, d);
              const auto b = m.owned_along_rows(row, d);
              for (int j = 0; j < n; ++j)
                for (int i = 0; i < n; ++i) {
                  const GridNode owner = m.node_of({d, j, i});
                  const bool in_block = i >= a.lo && i < a.hi && j >= b.lo && j < b.hi;
                  EXPECT_EQ(in_block, (owner == GridNode{row, col}))
                      << "mapping " << static_cast<int>(kind) << " " << rows << "x" << cols << " n "
                      << n << " flip " << flip << ": processor (" << row << "," << col << ") layer "
                      << d << " cell (" << j << "," << i << ")";
                }
            }
      }
}

// The intersection unit's timing (intersection_pipeline.hpp, Fig. 2-28): 1 us a transfer and
// 0.1 us a stage here, so a polygon's fetches (two transfers a word) set the pace.
namespace pipeline_test {
using rtsim::platform::ullner_array::FetchPriority;
using rtsim::platform::ullner_array::PipelineTest;
using rtsim::platform::ullner_array::PipelineTiming;
using rtsim::platform::ullner_array::run_pipeline;
const sc_core::sc_time kCycle(1, sc_core::SC_US), kStage(100, sc_core::SC_NS);

/// A polygon of one list; `tests` so far give the bound the search itself had for it.
PipelineTest polygon(double t, bool first, bool u = true, bool v = true) {
  return {.t = t,
          .t_in_range = t < 10.0,
          .u_valid = u,
          .v_valid = v,
          .bound = 10.0,
          .immediate_bound = 10.0,
          .list = 0,
          .first_of_list = first,
          .any_hit = false};
}
/// The search's own bounds: each test's is the closest hit before it in its list.
std::vector<PipelineTest> searched(std::vector<PipelineTest> tests) {
  double best = 10.0;
  for (auto& T : tests) {
    T.immediate_bound = best;
    if (T.t_in_range && T.t < best && T.u_valid && T.v_valid) best = T.t;
  }
  return tests;
}
}  // namespace pipeline_test

TEST(IntersectionPipeline, PolygonsRejectedAtTCostTheirAddressAndTWordsBackToBack) {
  using namespace pipeline_test;
  // Four planes behind the ray: stage 3 has no output for any; the memory fetches each one's
  // list entry and t's 4 words (the list's count with the first), nothing of u or v.
  std::vector<PipelineTest> tests;
  for (int k = 0; k < 4; ++k) tests.push_back(polygon(20.0, k == 0));
  const sc_core::sc_time start(5, sc_core::SC_US);
  const auto run = run_pipeline(tests, start, {.memory_cycle = kCycle, .stage_time = kStage});
  EXPECT_EQ(run.words, 2u + 4u + 3u * (1u + 4u));
  EXPECT_EQ(run.memory_busy, kCycle * static_cast<double>(2 * run.words));
  // Later fetches first: each polygon's t words follow its entry at once; the last leaves stage
  // 3 one stage after its t words.
  EXPECT_EQ(run.memory_end, start + run.memory_busy);
  EXPECT_EQ(run.done, run.memory_end + kStage);
  EXPECT_EQ(run.wasted_words, 0u);
  const auto none = run_pipeline({}, start, {.memory_cycle = kCycle, .stage_time = kStage});
  EXPECT_EQ(none.done, start);
  EXPECT_EQ(none.words, 0u);
}

TEST(IntersectionPipeline, AHitStillInThePipeLetsFartherPolygonsFetchUAndVForNothing) {
  using namespace pipeline_test;
  // The closest polygon first, then three farther ones: had its t come back at once they would
  // stop at stage 3; it comes back from stage 9, after they have passed stage 3.
  const std::vector<PipelineTest> closest_first =
      searched({polygon(1.0, true), polygon(2.0, false), polygon(3.0, false), polygon(4.0, false)});
  // Farther first: each is the closest so far, so nothing is fetched for nothing.
  const std::vector<PipelineTest> farthest_first =
      searched({polygon(4.0, true), polygon(3.0, false), polygon(2.0, false), polygon(1.0, false)});
  const PipelineTiming timing{.memory_cycle = kCycle, .stage_time = kStage};
  const auto a = run_pipeline(closest_first, sc_core::SC_ZERO_TIME, timing);
  const auto b = run_pipeline(farthest_first, sc_core::SC_ZERO_TIME, timing);
  std::printf("closest first: %llu words, %llu wasted, done %s; farthest first: %llu words\n",
              static_cast<unsigned long long>(a.words),
              static_cast<unsigned long long>(a.wasted_words), a.done.to_string().c_str(),
              static_cast<unsigned long long>(b.words));
  EXPECT_GE(a.wasted_words, 16u);  // the second polygon's u and v at least
  EXPECT_EQ(b.wasted_words, 0u);
  EXPECT_EQ(b.words, 1u + 4u * (1u + 4u + 8u + 8u));  // the count, then each one's all
  // Every entry and t, the closest one's u and v, and what was fetched for nothing.
  EXPECT_EQ(a.words, 1u + 4u * (1u + 4u) + 16u + a.wasted_words);
}

TEST(IntersectionPipeline, LaterStagesFirstBringsTheClosestHitBackSooner) {
  using namespace pipeline_test;
  // The closest polygon first, then eleven farther ones. Serving the latest stage's fetch first
  // (L850) takes the closest through stages 5-9 before the others' t words, so its bound reaches
  // stage 3 sooner and fewer farther polygons fetch u and v for nothing; serving stage 1's next
  // address first fills the pipe with polygons that wait (L850's log jam).
  std::vector<PipelineTest> tests{polygon(1.0, true)};
  for (int k = 1; k < 12; ++k) tests.push_back(polygon(1.0 + 0.5 * k, false));
  tests = searched(tests);
  for (const auto& stage : {kStage, sc_core::sc_time(3, sc_core::SC_US)}) {
    const auto later = run_pipeline(
        tests, sc_core::SC_ZERO_TIME,
        {.memory_cycle = kCycle, .stage_time = stage, .priority = FetchPriority::kLaterStages});
    const auto earlier = run_pipeline(
        tests, sc_core::SC_ZERO_TIME,
        {.memory_cycle = kCycle, .stage_time = stage, .priority = FetchPriority::kEarlierStages});
    std::printf("stage %s: later stages first %s, %llu words wasted; earlier first %s, %llu\n",
                stage.to_string().c_str(), later.done.to_string().c_str(),
                static_cast<unsigned long long>(later.wasted_words),
                earlier.done.to_string().c_str(),
                static_cast<unsigned long long>(earlier.wasted_words));
    EXPECT_LT(later.wasted_words, earlier.wasted_words);
    EXPECT_LT(later.done, earlier.done);
  }
}

/// `rtsim run --machine ullner-array ARGS`; its stats.json (with the image's path added).
nlohmann::ordered_json run_array(const std::string& tag, const std::string& args) {
  return rtsim::test::run_machine("ullner-array", tag, args);
}

TEST(UllnerArray, ImageEqualsTheFunctionalRenderForEverySizeAndMapping) {
  const std::string size = " --width 24 --height 24";
  for (const std::string& scene :
       {std::string("builtin:ullner-cubes"), rtsim::test::shared_path("scenes/tetra-s3.nff")}) {
    for (const auto& [rows, cols, n] :
         {std::tuple{8, 8, 0}, std::tuple{2, 3, 0}, std::tuple{16, 16, 0}, std::tuple{8, 8, 16}}) {
      const std::string grid = " -p array.rows=" + std::to_string(rows) +
                               " -p array.cols=" + std::to_string(cols) +
                               " -p array.subvolumes=" + std::to_string(n);
      const fs::path golden = scratch_dir("array-golden");
      const auto g = run_rtsim("render --machine ullner-array --scene " + scene + size + grid +
                               " -q --out " + golden.string());
      ASSERT_EQ(g.exit_code, 0) << g.output;
      const std::string want = read_file(golden / "image.png");
      fs::remove_all(golden);
      for (const char* mapping : {"straight", "skew", "torus"}) {
        const std::string args =
            "--scene " + scene + size + grid + " -p array.mapping=" + mapping + " --overhead";
        const auto s = run_array("image", args);
        ASSERT_FALSE(s.empty());
        EXPECT_TRUE(s.at("functional_image_identical").get<bool>()) << args;
        EXPECT_EQ(read_file(s.at("image_png").get<std::string>()), want) << args;
        // The detector held all the credit: every message was accounted for.
        EXPECT_GT(s["array"]["termination"]["credit_message_hops"].get<int>(), 0) << args;
        EXPECT_EQ(s["array"]["results_dropped"], 0);
      }
    }
  }
}

// array.interconnect = ring: one token ring instead of the mesh links. The same image; the ring
// carries every message straight to its destination (no processor on the way), and reports its
// load; its holder signal is in the VCD trace.
TEST(UllnerArray, OnARingTheImageIsTheSameAndTheRingCarriesEveryMessage) {
  const std::string base = "--scene builtin:ullner-cubes --width 32 --height 32";
  const fs::path golden = scratch_dir("array-ring-golden");
  ASSERT_EQ(
      run_rtsim("render --machine ullner-array " + base + " -q --out " + golden.string()).exit_code,
      0);
  const std::string want = read_file(golden / "image.png");
  const auto mesh = run_array("ring-mesh", base);
  const fs::path traced = scratch_dir("array-ring-vcd");
  const auto r = run_rtsim("run --machine ullner-array " + base +
                           " -p array.interconnect=ring --trace vcd -q --out " + traced.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto ring = read_json(traced / "stats.json");
  ASSERT_FALSE(mesh.empty());
  EXPECT_EQ(read_file(traced / "image.png"), want);
  EXPECT_EQ(read_file(mesh.at("image_png").get<std::string>()), want);
  EXPECT_EQ(ring["array"]["interconnect"], "ring");
  const auto& m = ring["modules"]["ring"];
  // Every message sent is one packet on the ring (68 bytes fit one), and nothing else is.
  double sent = 0;
  for (const auto& [type, n] : ring["array"]["messages_sent_by_type"].items())
    sent += n.get<double>();
  EXPECT_EQ(m["messages"].get<double>(), sent);
  EXPECT_EQ(m["packets"].get<double>(), sent);
  EXPECT_EQ(m["bytes.result"].get<double>(),
            ring["array"]["messages_sent_by_type"]["result"].get<double>() * (68 + 4));
  EXPECT_GT(m["utilization"].get<double>(), 0.0);
  EXPECT_GT(m["token_rotation_s"].get<double>(), 0.0);
  // No mesh links on a ring; the mesh has no ring.
  EXPECT_FALSE(ring["modules"].contains("node0.link_east"));
  EXPECT_FALSE(mesh["modules"].contains("ring"));
  // A ring at one mesh link's rate is one shared medium against many links: slower here.
  std::printf("frame: mesh %.4g s, ring %.4g s (ring busy %.0f%%)\n",
              mesh["simulated_time_s"].get<double>(), ring["simulated_time_s"].get<double>(),
              100 * m["utilization"].get<double>());
  EXPECT_GT(ring["simulated_time_s"].get<double>(), mesh["simulated_time_s"].get<double>());
  const std::string vcd = read_file(traced / "trace.vcd");
  // VCD scopes by module: the ring's scope holds its busy and holder variables.
  const auto scope = vcd.find("$scope module ring $end");
  ASSERT_NE(scope, std::string::npos);
  EXPECT_NE(vcd.find(" holder $end", scope), std::string::npos);
}

TEST(UllnerArray, OnARingTheProbeFollowsEachContributionOverTheRing) {
  // The generic probe test runs the mesh; on the ring a message goes from its copy out straight
  // to its destination's port, and that time is the ring's (queueing for the memory, then
  // transfer up to the delivery).
  const auto dir = scratch_dir("array-ring-probe");
  const auto r = run_rtsim(
      "run --machine ullner-array --scene builtin:ullner-cubes -p array.interconnect=ring "
      "--width 24 --height 24 --latency-probe -q --out " +
      dir.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto s = read_json(dir / "stats.json");
  const auto& p = s["latency_probe"];
  EXPECT_EQ(p["rays"], s["ray_latency_s"]["count"]);
  EXPECT_EQ(p["end_to_end_s"], s["ray_latency_s"]);
  const double e2e = p["end_to_end_s"]["mean"].get<double>();
  EXPECT_LE(std::abs(p["unattributed_s"].get<double>()), 1e-12 * e2e);
  ASSERT_TRUE(p["stages"].contains("ring")) << p["stages"].dump();
  EXPECT_FALSE(p["stages"].contains("node*.link_*"));
  EXPECT_GT(p["stages"]["ring"]["transfer_s"].get<double>(), 0.0);
  EXPECT_TRUE(p["stages"].contains("node*.in_ring"));
  std::printf("ring: %g s of %g s end to end on the ring (share %g)\n",
              p["stages"]["ring"]["total_s"].get<double>(), e2e,
              p["stages"]["ring"]["share"].get<double>());
}

// Termination costs what it should (credit flows to the detector along a combining tree): at
// 32x32 its messages are under 5% of the message hops, and no column is hot because of them.
// Returning credit straight to processor (0,0) made 50% of the hops here and column 0 busy while
// the rest idled. node.credit_quiet_time = 0 (send at once, still combined) must cost more hops.
// --trace perfetto: every message a link carries is a slice on the link's track with its ray
// tree, message, source and destination, and a flow links its links and the processors that take
// it, in time order, from a start ("s") on its first link. The image does not change.
TEST(UllnerArray, ThePerfettoTraceFollowsEachMessageAcrossTheArray) {
  const std::string args =
      "--scene builtin:ullner-cubes --width 16 --height 16 -p array.rows=4 -p array.cols=4";
  const fs::path dir = scratch_dir("array-flows");
  const auto r = run_rtsim("run --machine ullner-array " + args + " --trace perfetto -q --out " +
                           dir.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto plain = run_array("flows-plain", args);
  ASSERT_FALSE(plain.empty());
  EXPECT_EQ(read_file(dir / "image.png"), read_file(plain.at("image_png").get<std::string>()));
  const auto trace = read_json(dir / "trace.json");
  std::map<std::pair<int, int>, std::string> track;
  for (const auto& e : trace["traceEvents"])
    if (e["ph"] == "M" && e["name"] == "thread_name")
      track[{e["pid"].get<int>(), e["tid"].get<int>()}] = e["args"]["name"];
  auto track_of = [&](const nlohmann::json& e) {
    return track[{e["pid"].get<int>(), e["tid"].get<int>()}];
  };
  std::uint64_t link_slices = 0;
  std::map<std::uint64_t, std::vector<std::pair<double, std::string>>> flows;
  for (const auto& e : trace["traceEvents"]) {
    if (e["ph"] == "X" && track_of(e).find(".link_") != std::string::npos) {
      ++link_slices;
      for (const char* arg : {"ray", "message", "from", "to"}) EXPECT_TRUE(e["args"].contains(arg));
      EXPECT_NE(e["args"]["from"], e["args"]["to"]);
      EXPECT_EQ(track_of(e), "node" + std::to_string(e["args"]["from"].get<int>()) +
                                 track_of(e).substr(track_of(e).find(".link_")));
    }
    if (e["ph"] == "s" || e["ph"] == "t")
      flows[e["id"].get<std::uint64_t>()].push_back({e["ts"].get<double>(), e["ph"]});
  }
  std::uint64_t hops = 0;
  for (const auto& [type, n] : plain["array"]["messages_sent_by_type"].items())
    hops += n.get<std::uint64_t>();
  EXPECT_EQ(link_slices, hops);  // one slice a hop
  ASSERT_FALSE(flows.empty());
  std::size_t longest = 0;
  for (auto& [id, events] : flows) {
    std::stable_sort(events.begin(), events.end());
    EXPECT_EQ(events.front().second, "s") << "flow " << id;
    longest = std::max(longest, events.size());
  }
  EXPECT_GE(longest, 4u);  // link, processor, link, processor at least somewhere
}

// node.process = queue (the default) and method run each processor event-driven: an activation
// handles what is due at its time and computes ahead, the array's own event queue (one SystemC
// process for all of them, modules/wake_queue.hpp) or SystemC (an SC_METHOD each) activating it.
// node.process = thread is the reference, a thread that waits wherever it spends time. The two
// are allowed only because they are exact: on three scenes at 8 x 8 (cubes with its
// reflections, a faceted tetrahedron whose rays cross many subvolumes, a thousand lit sheets seen
// from the side), on the ring, and with sampled rows (windows timed by when contributions land),
// every statistic and the image are the thread's.
TEST(UllnerArray, EventDrivenProcessorsGiveTheThreadsStatisticsExactly) {
  const auto comparable = [](nlohmann::ordered_json s) {
    // And what the simulation cost in events: a method runs where a thread waits.
    for (const char* key : {"wall_time_s", "rays_per_second", "params", "image_bytes", "image_png",
                            "command", "simulation"})
      s.erase(key);
    return nlohmann::json(s);
  };
  const std::string tetra = rtsim::test::shared_path("scenes/tetra-s3.nff");
  for (const std::string& run :
       {std::string("--scene builtin:ullner-cubes"), "--scene " + tetra,
        std::string("--scene builtin:ullner-sheets-lit-1000"),
        std::string("--scene builtin:ullner-cubes -p array.interconnect=ring"),
        std::string("--scene builtin:ullner-cubes --sample 4 --sample-window 2")}) {
    const std::string args = run + " --width 32 --height 32 -p array.rows=8 -p array.cols=8";
    const auto thread = run_array("thread", args + " -p node.process=thread");
    ASSERT_FALSE(thread.empty()) << args;
    for (const char* kind : {"queue", "method"}) {
      const auto driven = run_array(kind, args + " -p node.process=" + kind);
      ASSERT_FALSE(driven.empty()) << args << " " << kind;
      EXPECT_EQ(read_file(driven.at("image_png").get<std::string>()),
                read_file(thread.at("image_png").get<std::string>()))
          << args << " " << kind;
      const nlohmann::json differences =
          nlohmann::json::diff(comparable(thread), comparable(driven));
      std::printf("%s: frame %.6g s (thread) %.6g s (%s), %zu statistics differ\n", args.c_str(),
                  thread.at("simulated_time_s").get<double>(),
                  driven.at("simulated_time_s").get<double>(), kind, differences.size());
      EXPECT_TRUE(differences.empty()) << args << " " << kind << "\n"
                                       << differences.dump().substr(0, 3000);
    }
  }
}

// The MC68000's bus cycles hold the shared memory for node.cpu_memory_share of its computing
// time (L839): every processor's cpu_memory_busy_s is that share of its busy time, part of its
// memory's busy time, and the frame is longer for it; the image is the same.
TEST(UllnerArray, TheCpusBusCyclesHoldTheSharedMemory) {
  const std::string args = "--scene builtin:ullner-cubes --width 24 --height 24";
  const auto shared = run_array("cpu-share", args);
  const auto alone = run_array("cpu-share-0", args + " -p node.cpu_memory_share=0");
  ASSERT_FALSE(shared.empty() || alone.empty());
  const auto& node = shared["modules"]["node9"];
  const double busy = node["busy_s"].get<double>();
  const double cpu = node["cpu_memory_busy_s"].get<double>();
  std::printf(
      "node9: CPU busy %.6g s, its bus cycles on the memory %.6g s (%.4f); frame %.6g s "
      "against %.6g s without them\n",
      busy, cpu, cpu / busy, shared["simulated_time_s"].get<double>(),
      alone["simulated_time_s"].get<double>());
  EXPECT_NEAR(cpu / busy, 0.6, 1e-6);
  EXPECT_GT(node["memory_busy_s"].get<double>(), cpu);
  EXPECT_EQ(alone["modules"]["node9"]["cpu_memory_busy_s"].get<double>(), 0.0);
  EXPECT_GT(shared["simulated_time_s"].get<double>(), alone["simulated_time_s"].get<double>());
  EXPECT_EQ(read_file(shared.at("image_png").get<std::string>()),
            read_file(alone.at("image_png").get<std::string>()));
}

TEST(UllnerArray, TerminationIsASmallShareOfTheHopsAndHeatsNoColumn) {
  const std::string args =
      "--scene builtin:ullner-cubes --width 64 --height 64 -p array.rows=32 -p array.cols=32";
  const auto quiet = run_array("term-quiet", args);
  const auto eager = run_array("term-eager", args + " -p node.credit_quiet_time=0s");
  ASSERT_FALSE(quiet.empty() || eager.empty());
  const auto share = [](const nlohmann::json& s) {
    double hops = 0.0;
    for (const auto& [type, n] : s["array"]["messages_sent_by_type"].items())
      hops += n.get<double>();
    return s["array"]["termination"]["credit_message_hops"].get<double>() / hops;
  };
  const auto& busy = quiet["array"]["node_busy_fraction"];
  std::vector<double> column(busy[0].size(), 0.0);
  double mean = 0.0;
  for (const auto& row : busy)
    for (std::size_t c = 0; c < row.size(); ++c) {
      column[c] += row[c].get<double>() / static_cast<double>(busy.size());
      mean += row[c].get<double>() / static_cast<double>(busy.size() * row.size());
    }
  std::printf(
      "credit share of hops: %.2f%% (quiet), %.2f%% (at once); column 0 busy %.3f, "
      "hottest column %.3f, mean %.3f\n",
      100 * share(quiet), 100 * share(eager), column[0],
      *std::max_element(column.begin(), column.end()), mean);
  EXPECT_LT(share(quiet), 0.05);
  EXPECT_GT(share(eager), share(quiet));
  EXPECT_LT(column[0], 1.5 * mean);
  EXPECT_EQ(read_file(quiet.at("image_png").get<std::string>()),
            read_file(eager.at("image_png").get<std::string>()));
}

TEST(UllnerArray, ALostResultMessageChangesTheImage) {
  const std::string args = "--scene builtin:ullner-cubes --width 24 --height 24";
  const auto clean = run_array("clean", args);
  const auto lost = run_array("lost", args + " -p array.fault.drop_result=200");
  ASSERT_FALSE(clean.empty() || lost.empty());
  EXPECT_EQ(lost["array"]["results_dropped"], 1);
  EXPECT_NE(read_file(clean.at("image_png").get<std::string>()),
            read_file(lost.at("image_png").get<std::string>()));
  // The frame still ends: the lost message's credit was returned where it was dropped.
  EXPECT_EQ(lost["array"]["results_added"], clean["array"]["results_added"]);
}

TEST(UllnerArray, ACorruptedPolygonWordInAProcessorsMemoryChangesTheImage) {
  // ullner-cubes has no corner normals: a processor's lines are 28 words from address 0 (the
  // header, the 25 words of the peripheral's line, the identity, the material). Flip the sign
  // of d_p (line word 4) of every line a centre processor holds; then, apart, the material
  // number of every line: the shading reads it from the memory too.
  const std::string args = "--scene builtin:ullner-cubes --width 24 --height 24";
  const auto clean = run_array("mem-clean", args);
  ASSERT_FALSE(clean.empty());
  std::string d_p, material;
  for (int line = 0; line < 40; ++line) {
    d_p += " --fault node27.memory:" + std::to_string(line * 28 + 4) + ":0x80000000";
    material += " --fault node27.memory:" + std::to_string(line * 28 + 27) + ":0x1";
  }
  for (const auto& [tag, faults] :
       {std::pair{"mem-d_p", d_p}, std::pair{"mem-material", material}}) {
    const auto bad = run_array(tag, args + faults);
    ASSERT_FALSE(bad.empty());
    EXPECT_NE(read_file(clean.at("image_png").get<std::string>()),
              read_file(bad.at("image_png").get<std::string>()))
        << tag;
  }
}

// The host broadcasts the scene through the array's links (L785-L797): every processor receives
// every record, keeps the polygons of its own subvolumes (exactly what the subdivision lists for
// them), and the load takes the time the slowest hop of the tree gives it: slower processors or
// a slower host port lengthen it, the image stays the same.
TEST(UllnerArray, TheHostsBroadcastLoadsEachProcessorThroughTheLinks) {
  const std::string args =
      "--scene builtin:ullner-cubes --width 16 --height 16 -p array.rows=4 -p array.cols=4";
  const auto base = run_array("load-base", args);
  const auto slow_cpu = run_array("load-cpu", args + " -p node.cycles.keep_test=2000");
  const auto slow_host = run_array("load-host", args + " -p host.word_time=\"20 us\"");
  ASSERT_FALSE(base.empty() || slow_cpu.empty() || slow_host.empty());
  const auto& m = base["modules"];
  const std::uint64_t records = m["host"]["records"].get<std::uint64_t>();
  EXPECT_EQ(records, base["array"]["polygons"].get<std::uint64_t>() + 2);  // + attributes, view
  std::uint64_t kept = 0;
  double first_ready = 0.0, last_ready = 0.0;
  for (int i = 0; i < 16; ++i) {
    const auto& n = m["node" + std::to_string(i)];
    EXPECT_EQ(n["load_records"].get<std::uint64_t>(), records) << i;
    kept += n["polygons"].get<std::uint64_t>();
    const double ready = n["frame_ready_s"].get<double>();
    EXPECT_GE(ready, base["array"]["load_time_s"].get<double>()) << i;
    if (i == 0) first_ready = ready;
    if (i == 15) last_ready = ready;
  }
  EXPECT_EQ(kept, base["array"]["polygons_kept"].get<std::uint64_t>());
  EXPECT_GT(last_ready, first_ready);  // the view reaches the far corner last
  const double load = base["array"]["load_time_s"].get<double>();
  std::printf("load %.4f s; keep test x10: %.4f s; host port 20 us a word: %.4f s\n", load,
              slow_cpu["array"]["load_time_s"].get<double>(),
              slow_host["array"]["load_time_s"].get<double>());
  EXPECT_GT(slow_cpu["array"]["load_time_s"].get<double>(), 2.0 * load);
  // The host's port bounds the load at 20 us a word: its words at least.
  EXPECT_GE(slow_host["array"]["load_time_s"].get<double>(),
            20e-6 * m["host"]["words"].get<double>() * 0.99);
  for (const auto* other : {&slow_cpu, &slow_host})
    EXPECT_EQ(read_file(base.at("image_png").get<std::string>()),
              read_file(other->at("image_png").get<std::string>()));
}

// A word corrupted as the host sends it reaches every processor: a polygon's parameter or its
// material changes the image; a word past the broadcast is refused.
TEST(UllnerArray, ABroadcastPolygonCorruptedInFlightChangesTheImage) {
  const std::string args = "--scene builtin:ullner-cubes --width 24 --height 24";
  const auto clean = run_array("bc-clean", args);
  ASSERT_FALSE(clean.empty());
  // Polygon 0's record: word 1 its first parameter (sign flipped), word 27 its material.
  for (const char* fault : {"host.broadcast:1:0x80000000", "host.broadcast:27:0x1"}) {
    const auto bad = run_array("bc-bad", args + " --fault " + fault);
    ASSERT_FALSE(bad.empty()) << fault;
    EXPECT_NE(read_file(clean.at("image_png").get<std::string>()),
              read_file(bad.at("image_png").get<std::string>()))
        << fault;
    EXPECT_EQ(bad["array"]["faults_in_flight"][0]["applied"], 1) << fault;
  }
  const fs::path out = scratch_dir("bc-refused");
  const auto refused = run_rtsim("run --machine ullner-array " + args +
                                 " --fault host.broadcast:99999999:1 -q --out " + out.string());
  EXPECT_EQ(refused.exit_code, 2) << refused.output;
  EXPECT_NE(refused.output.find("the host broadcasts"), std::string::npos) << refused.output;
  EXPECT_FALSE(fs::exists(out / "image.png"));
}

// A word of every ray message a link carries, corrupted on the wire: a contribution's colour or
// a ray's origin changes the image; a corrupted credit ends the run with a message and exit 2;
// a link that does not exist or a word past the message is refused.
TEST(UllnerArray, ARayMessageCorruptedOnALinkChangesTheImage) {
  const std::string args = "--scene builtin:ullner-cubes --width 24 --height 24";
  const auto clean = run_array("msg-clean", args);
  ASSERT_FALSE(clean.empty());
  for (const char* fault : {"node27.link_e:9:0x00400000", "node27.link_s:4:0x00100000"}) {
    const auto bad = run_array("msg-bad", args + " --fault " + fault);
    ASSERT_FALSE(bad.empty()) << fault;
    EXPECT_GT(bad["array"]["faults_in_flight"][0]["applied"].get<int>(), 0) << fault;
    EXPECT_NE(read_file(clean.at("image_png").get<std::string>()),
              read_file(bad.at("image_png").get<std::string>()))
        << fault;
  }
  // A corrupted type makes results rays again, shaded again and again: the watchdog ends them.
  const auto looping = run_array("msg-loop", args + " --fault node27.link_e:0:0x1");
  ASSERT_FALSE(looping.empty());
  EXPECT_GT(looping["array"]["messages_destroyed_looping"].get<int>(), 0);
  for (const auto& [fault, says] :
       {std::pair{"node27.link_e:16:0x1", "cannot tell when the frame"},
        std::pair{"node7.link_e:0:1", "links"}, std::pair{"node999.link_e:0:1", "links"},
        std::pair{"node27.link_e:17:1", "17 words"}}) {
    const fs::path out = scratch_dir("msg-refused");
    const auto r = run_rtsim("run --machine ullner-array " + args + " --fault " + fault +
                             " -q --out " + out.string());
    EXPECT_EQ(r.exit_code, 2) << fault << "\n" << r.output;
    EXPECT_NE(r.output.find(says), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(out / "image.png")) << fault;
  }
}

TEST(UllnerArray, BadSizesAreBadInput) {
  const fs::path dir = scratch_dir("array-bad");
  auto r = run_rtsim(
      "run --machine ullner-array --scene builtin:ullner-cubes "
      "-p array.subvolumes=4 -q --out " +
      dir.string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("array.subvolumes"), std::string::npos) << r.output;
  r = run_rtsim("run --machine ullner-array --scene builtin:npp-412 -q --out " + dir.string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  r = run_rtsim(
      "run --machine ullner-array --scene builtin:ullner-cubes -p array.mapping=twist "
      "-q --out " +
      dir.string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  // A processor whose memory cannot hold its subvolumes' polygons (L835).
  r = run_rtsim(
      "run --machine ullner-array --scene builtin:ullner-cubes -p node.memory_words=100 -q "
      "--out " +
      dir.string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("node.memory_words"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir));
}

// The array's own hostile rows (tests/hostile_table.hpp runs them as hostile_input_test runs
// the generic ones).
TEST(UllnerArrayHostile, EveryRowExitsAsAllowedWithinItsMemory) {
  using rtsim::test::absent;
  using rtsim::test::hostile_run;
  using rtsim::test::LimitedRun;
  using rtsim::test::present;
  std::vector<rtsim::test::HostileCase> c;
  c.push_back(
      {"describe: a 32 x 32 array is drawn with its class cut short",
       {"describe", "ullner-array", "-p", "array.rows=32", "-p", "array.cols=32", "--out", "big"},
       {0},
       [](const fs::path& d, const LimitedRun&) {
         std::ifstream f(d / "big/ullner-array.dot");
         const std::string dot((std::istreambuf_iterator<char>(f)), {});
         return dot.find("1016 more node") != std::string::npos
                    ? present(d / "big/ullner-array.svg")
                    : "the DOT file does not count the nodes it leaves out";
       }});
  // Issue 30 item 5: a memory the bounds allow but the computer cannot hold.
  c.push_back(
      {"node.memory_words at its bound",
       hostile_run("ullner-array", "builtin:ullner-cubes", {"-p", "node.memory_words=1000000000"}),
       {0, 2}});
  // Item 8: times that overflow outside the simulation.
  for (const char* p : {"array.load.word_time=1e6 s", "array.readout.pixel_time=1e6 s"})
    c.push_back({p, hostile_run("ullner-array", "builtin:ullner-cubes", {"-p", p}), {2}});
  // Item 9: a nested --out of a run refused while it runs leaves no folder.
  c.push_back(
      {"a nested --out of a run refused while it runs leaves no folder",
       {"run", "--machine", "ullner-array", "--scene", "builtin:ullner-cubes", "--width", "8",
        "--height", "8", "-q", "--out", "nest/a/b", "-p", "array.load.word_time=1e6 s"},
       {2},
       [](const fs::path& d, const LimitedRun&) { return absent(d / "nest"); }});
  rtsim::test::run_hostile_table(scratch_dir("array-hostile"), c);
}

// Item 9: SIGTERM to a run whose --sample-error pilot (a fork) is running ended the run and left
// the pilot running. The pilot now ends with its parent.
TEST(UllnerArrayHostile, ThePilotOfSampleErrorEndsWithItsRun) {
  const fs::path dir = rtsim::test::scratch_dir("hostile-pilot");
  fs::remove_all(dir);
  fs::create_directories(dir);
  // A pilot of about 4 s (a 32 x 32 array on a 512 x 512 frame): it is still running when its
  // run is ended.
  const pid_t run = rtsim::test::start_rtsim(
      {"run", "--machine", "ullner-array", "--scene", "builtin:ullner-cubes", "-p", "array.rows=32",
       "-p", "array.cols=32", "--width", "512", "--height", "512", "-q", "--sample-error", "1%",
       "--out", "out"},
      dir);
  std::vector<pid_t> pilots;
  for (int i = 0; i < 200 && pilots.empty(); ++i) {  // up to 10 s for the pilot to start
    ::usleep(50000);
    pilots = rtsim::test::children_of(run);
  }
  ASSERT_FALSE(pilots.empty()) << "the pilot never started";
  ::usleep(500000);
  ::kill(run, SIGTERM);
  int status = 0;
  ::waitpid(run, &status, 0);
  bool gone = false;
  for (int i = 0; i < 10 && !gone; ++i) {  // up to 0.5 s: the pilot itself runs for seconds
    gone = std::none_of(pilots.begin(), pilots.end(), rtsim::test::alive);
    if (!gone) ::usleep(50000);
  }
  EXPECT_TRUE(gone) << "the pilot outlived its run";
  for (const pid_t p : pilots) ::kill(p, SIGKILL);
  EXPECT_FALSE(fs::exists(dir / "out"));
  fs::remove_all(dir);
}

}  // namespace
