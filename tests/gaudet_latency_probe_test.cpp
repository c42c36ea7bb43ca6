// gaudet-pert with the latency probe (platform/machines/gaudet_pert/ray_probe.hpp): every ray's
// journey spans exactly the ray_latency_s window and is tiled by its stages' parts; the probe
// changes neither the image nor any other statistic; the stage figures agree with the
// processors' own accounting and move the way the broadcast mode says they must.
// The machine is called directly (platform::find_machine), each simulation in a forked child
// (SystemC allows one per process), the children running side by side.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "app/scene_input.hpp"
#include "platform/machine.hpp"
#include "platform/machine_registry.hpp"
#include "tests/test_support.hpp"

namespace fs = std::filesystem;
using json = nlohmann::ordered_json;  // keeps the stages in their order

namespace {

struct Sim {
  std::vector<std::string> overrides;
  bool probe = false;
};

/// One simulation of builtin:npp-412 at 24x24 on 2 PERTs: writes {stats, simulated_time_s,
/// rgb} to `out`. Runs in a child: returns its exit code.
int simulate(const Sim& run, const fs::path& out) {
  const auto& machine = rtsim::platform::find_machine("gaudet-pert");
  rtsim::params::ParamRegistry registry;
  rtsim::platform::declare_params_of(&machine, registry);
  registry.apply_override("pert_count=2");
  for (const auto& o : run.overrides) registry.apply_override(o);
  auto scene = rtsim::app::load_scene_with_seed("builtin:npp-412", registry);
  auto twin = machine.make_twin(scene, registry);
  rtsim::platform::RunOptions opts;
  opts.width = 24;
  opts.height = 24;
  opts.latency_probe = run.probe;
  const auto res = machine.run(scene, twin, registry, opts);
  json j;
  j["stats"] = res.stats;
  j["simulated_time_s"] = res.simulated_time_s;
  j["rgb"] = res.image.rgb;
  std::ofstream f(out);
  f << j.dump();
  return f ? 0 : 3;
}

/// Runs every simulation in its own child process, side by side; their results in order.
std::vector<json> simulate_all(const std::vector<Sim>& runs, const std::string& tag) {
  const fs::path dir = rtsim::test::scratch_dir(tag);
  fs::create_directories(dir);
  std::fflush(nullptr);
  std::vector<pid_t> pids;
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const pid_t pid = ::fork();
    if (pid == 0) {
      ::alarm(120);  // a simulation that hangs fails the test instead of stalling it
      int code = 2;
      try {
        code = simulate(runs[i], dir / (std::to_string(i) + ".json"));
      } catch (const std::exception& e) {
        std::fprintf(stderr, "simulation %zu: %s\n", i, e.what());
      }
      std::fflush(nullptr);
      ::_exit(code);
    }
    pids.push_back(pid);
  }
  std::vector<json> out;
  for (std::size_t i = 0; i < runs.size(); ++i) {
    int status = 0;
    EXPECT_EQ(::waitpid(pids[i], &status, 0), pids[i]);
    EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << "simulation " << i;
    out.push_back(json::parse(rtsim::test::read_file(dir / (std::to_string(i) + ".json"))));
  }
  fs::remove_all(dir);
  return out;
}

const char* const kStages[] = {"queue.shade_to_shell", "shell", "shell_bus",
                               "queue.shell_to_prim",  "prim",  "prim_bus",
                               "queue.prim_to_shade",  "shade"};

void print_stages(const std::string& what, const json& probe) {
  std::printf("%s: %llu rays, end-to-end mean %.6g s, unattributed %.3g s\n", what.c_str(),
              static_cast<unsigned long long>(probe["rays"].get<std::uint64_t>()),
              probe["end_to_end_s"]["mean"].get<double>(), probe["unattributed_s"].get<double>());
  std::printf("  %-22s %12s %12s %12s %12s %7s\n", "stage", "queueing_s", "service_s", "transfer_s",
              "total_s", "share");
  for (const auto& [name, s] : probe["stages"].items())
    std::printf("  %-22s %12.4g %12.4g %12.4g %12.4g %6.1f%%\n", name.c_str(),
                s["queueing_s"].get<double>(), s["service_s"].get<double>(),
                s["transfer_s"].get<double>(), s["total_s"].get<double>(),
                100.0 * s["share"].get<double>());
}

/// What holds for every probed run: the journeys span the ray_latency_s window, are tiled by
/// their parts, and the service of the Shell and Prim stages is the processors' processing.
void check_journeys(const json& stats, const std::string& what) {
  SCOPED_TRACE(what);
  ASSERT_TRUE(stats.contains("latency_probe"));
  const json& probe = stats["latency_probe"];
  // The window is ray_latency_s's: the same rays, the same durations (integer picoseconds,
  // now - sent), so end_to_end_s *is* ray_latency_s, exactly.
  const json& lat = stats["ray_latency_s"];
  EXPECT_EQ(probe["rays"], lat["count"]);
  EXPECT_GT(probe["rays"].get<std::uint64_t>(), 24u * 24u);  // shadow and reflected rays too
  std::printf("end-to-end mean: expected (ray_latency_s) %.9g s, measured %.9g s\n",
              lat["mean"].get<double>(), probe["end_to_end_s"]["mean"].get<double>());
  EXPECT_EQ(probe["end_to_end_s"], lat);

  // Tiled by construction: what is left over is the rounding of summing the parts in double
  // (each part is an exact sc_time; ~1e-16 relative of a latency of ~1e-3 s).
  EXPECT_LT(std::abs(probe["unattributed_s"].get<double>()), 1e-9);

  // The stages in the order a ray meets them; no part negative; shares add up to 1.
  std::vector<std::string> names;
  double shares = 0.0;
  for (const auto& [name, s] : probe["stages"].items()) {
    names.push_back(name);
    for (const char* k : {"queueing_s", "service_s", "transfer_s", "total_s"})
      EXPECT_GE(s[k].get<double>(), 0.0) << name << " " << k;
    shares += s["share"].get<double>();
  }
  EXPECT_EQ(names, std::vector<std::string>(std::begin(kStages), std::end(kStages)));
  EXPECT_NEAR(shares, 1.0, 1e-9);

  // Same accounting as the processors': every compute of the ShellProcessor and the
  // PrimProcessor is some ray's service exactly once (a packet shared by k rays in k shares),
  // so the service per ray is their processing per ray (the ray counts are equal: every ray
  // goes once round the ring). 1e-6 relative: the shares are whole picoseconds.
  const json& g = stats["gaudet"];
  for (const char* proc : {"shell", "prim"}) {
    const double expected = g[proc]["processing_per_ray_s"].get<double>();
    const double measured = probe["stages"][proc]["service_s"].get<double>();
    std::printf(
        "%s service per ray: expected (gaudet.%s.processing_per_ray_s) %.9g s, "
        "measured %.9g s\n",
        proc, proc, expected, measured);
    EXPECT_EQ(g[proc]["rays"], probe["rays"]) << proc;
    EXPECT_NEAR(measured, expected, 1e-6 * expected) << proc;
  }
}

}  // namespace

// The probe's journeys, adaptive broadcasting, against the same run without the probe.
TEST(GaudetLatencyProbe, JourneysTileTheRayLatencyWindowAndChangeNothingElse) {
  const auto r = simulate_all({{{}, true}, {{}, false}}, "glp-adaptive");
  ASSERT_EQ(r.size(), 2u);
  const json& on = r[0]["stats"];
  const json& off = r[1]["stats"];
  ASSERT_TRUE(on.contains("latency_probe"));
  const json& probe = on["latency_probe"];
  print_stages("adaptive", probe);

  // Off: no latency_probe key; everything else identical, the image too.
  EXPECT_FALSE(off.contains("latency_probe"));
  json on_rest = on;
  on_rest.erase("latency_probe");
  EXPECT_EQ(on_rest, off);
  EXPECT_EQ(r[0]["rgb"], r[1]["rgb"]);
  EXPECT_EQ(r[0]["simulated_time_s"], r[1]["simulated_time_s"]);

  check_journeys(on, "adaptive");
  // Bus stages: rays wait for and receive SHELL and PRIM packets.
  for (const char* bus : {"shell_bus", "prim_bus"}) {
    EXPECT_GT(probe["stages"][bus]["queueing_s"].get<double>(), 0.0) << bus;
    EXPECT_GT(probe["stages"][bus]["transfer_s"].get<double>(), 0.0) << bus;
    EXPECT_EQ(probe["stages"][bus]["service_s"].get<double>(), 0.0) << bus;
  }
  // Queues hold rays only: neither service nor transfer there.
  for (const char* q : {"queue.shade_to_shell", "queue.shell_to_prim", "queue.prim_to_shade"}) {
    EXPECT_EQ(probe["stages"][q]["service_s"].get<double>(), 0.0) << q;
    EXPECT_EQ(probe["stages"][q]["transfer_s"].get<double>(), 0.0) << q;
  }
}

// A what-if: non-adaptive broadcasting sends every PRIM packet every cycle, so a PRIM packet
// comes round later and a ray spends longer on the Prim bus than with adaptive broadcasting
// (Fig. 6-9). In direct mode the "bus" is the processor's own memory: only its access time.
TEST(GaudetLatencyProbe, PrimBusTimeGrowsWithoutAdaptiveBroadcasting) {
  const auto r = simulate_all({{{"broadcast.mode=adaptive"}, true},
                               {{"broadcast.mode=non-adaptive"}, true},
                               {{"broadcast.mode=direct"}, true}},
                              "glp-modes");
  ASSERT_EQ(r.size(), 3u);
  const char* modes[] = {"adaptive", "non-adaptive", "direct"};
  double prim_bus[3];
  for (int i = 0; i < 3; ++i) {
    const json& probe = r[static_cast<std::size_t>(i)]["stats"]["latency_probe"];
    print_stages(modes[i], probe);
    prim_bus[i] = probe["stages"]["prim_bus"]["total_s"].get<double>();
    check_journeys(r[static_cast<std::size_t>(i)]["stats"], modes[i]);
  }
  std::printf("prim_bus per ray: adaptive %.6g s, non-adaptive %.6g s, direct %.6g s\n",
              prim_bus[0], prim_bus[1], prim_bus[2]);
  EXPECT_GT(prim_bus[1], prim_bus[0]);
  EXPECT_GT(prim_bus[0], prim_bus[2]);
  // Direct memory: no waiting for the bus, only the first access of each packet.
  const json& direct = r[2]["stats"]["latency_probe"]["stages"]["prim_bus"];
  EXPECT_EQ(direct["queueing_s"].get<double>(), 0.0);
  EXPECT_GT(direct["transfer_s"].get<double>(), 0.0);
}

// Where the model is pushed (temporal decoupling, one ID register, one buffer, queues of one,
// more rays in flight, more PERTs, random broadcast order) the journeys still tile the window:
// the cursor rule does not rely on the processors running in global time order.
TEST(GaudetLatencyProbe, JourneysStayTiledUnderStress) {
  const std::vector<Sim> runs = {
      {{"quantum=10 us", "broadcast.order=random"}, true},
      {{"pert_count=3", "pert.shell.bic.id_registers=1", "pert.prim.bic.id_registers=1",
        "pert.shell.bic.buffers=1", "pert.prim.bic.buffers=1", "pert.queue.shade_to_shell=1",
        "pert.queue.shell_to_prim=1", "pert.queue.prim_to_shade=1"},
       true},
      {{"pert.shade.rays_in_flight=16", "pert.shell.rays_in_flight=16",
        "broadcast.mode=non-adaptive", "quantum=1 us"},
       true}};
  const auto r = simulate_all(runs, "glp-stress");
  ASSERT_EQ(r.size(), runs.size());
  for (std::size_t i = 0; i < r.size(); ++i) {
    print_stages("stress " + std::to_string(i), r[i]["stats"]["latency_probe"]);
    check_journeys(r[i]["stats"], "stress " + std::to_string(i));
  }
}
