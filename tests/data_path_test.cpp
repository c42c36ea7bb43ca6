// A machine's answers come from the data its transactions carry (DESIGN.md "Data flows through
// the model"): corrupt one word on its way into a machine's memory and the image changes.
//  * ullner-peripheral: the intersection pipeline tests the twenty parameters, pole thresholds
//    and flags it read out of its parameter memories. Flipping the sign of d_p (the plane's
//    offset, word 3) of the polygon the centre ray hits moves that polygon's plane: the centre
//    pixel changes, while with no fault the image equals the functional twin's.
//  * gaudet-pert: the ShellProcessors box-test the SHELL records in the packets their BICs
//    caught; emptying the box of the first SHELL in the Shell bus's memory hides its subtree.
//    The PrimProcessors test the PRIM records of theirs: a sphere whose radius word is
//    corrupted to a huge value is hit by every ray that reaches its leaf shell.
//    A corrupted ID list stalls the machine: the run says so (exit 2), writing nothing.
//  * ullner-pipeline: each polygon processor intersects the ray description it received with the
//    polygon in its registers, shifted in by the host at load time. Flipping d_p of the
//    processor holding the centre pixel's polygon changes the centre pixel.
//  * `rtsim run --fault` names a memory and a word; a memory the machine does not have, or a
//    word past its end, is bad input (exit 2).
// Each simulation runs in a forked child (SystemC allows one per process).
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "app/scene_input.hpp"
#include "firmware/accel/gaudet_data_sets.hpp"
#include "firmware/kernels/ullner_quad_words.hpp"
#include "firmware/shading/camera.hpp"
#include "platform/functional/scene_tracer.hpp"
#include "platform/machine.hpp"
#include "platform/machines/gaudet_pert/data_sets.hpp"
#include "tests/machine_test_support.hpp"
#include "tests/test_support.hpp"

namespace fs = std::filesystem;
using rtsim::test::run_rtsim;

namespace {

constexpr int kSize = 32;
constexpr const char* kScene = "builtin:ullner-cubes";

struct Frame {
  bool ok = false;
  std::vector<float> rgb;
};

/// Runs `machine_name` on `scene_name` at kSize x kSize with `faults` and `overrides`, in a
/// child; the image.
Frame simulate(const std::string& machine_name, const std::string& scene_name,
               const std::vector<std::string>& overrides,
               const std::vector<rtsim::platform::MemoryFault>& faults, const fs::path& out) {
  Frame frame;
  frame.ok = rtsim::test::run_in_child([&] {
               auto m = rtsim::test::prepare_machine(machine_name, scene_name, overrides);
               rtsim::platform::RunOptions opts;
               opts.width = kSize;
               opts.height = kSize;
               opts.faults = faults;
               const auto res = m->machine->run(m->scene, m->twin, m->registry, opts);
               std::ofstream f(out, std::ios::binary);
               f.write(reinterpret_cast<const char*>(res.image.rgb.data()),
                       static_cast<std::streamsize>(res.image.rgb.size() * sizeof(float)));
               return f ? 0 : 4;
             }) == 0;
  if (frame.ok) {
    const std::string bytes = rtsim::test::read_file(out);
    frame.rgb.resize(bytes.size() / sizeof(float));
    std::memcpy(frame.rgb.data(), bytes.data(), frame.rgb.size() * sizeof(float));
  }
  return frame;
}

/// The slot (line of the parameter memories) of the polygon the centre pixel's ray hits, from
/// the twin (no simulation); -1 if it hits nothing.
long centre_slot() {
  auto m = rtsim::test::prepare_machine("ullner-peripheral", kScene);
  const auto& twin = m->twin;
  rtsim::shading::PinholeCamera camera(m->scene.camera, kSize, kSize);
  const rtsim::Ray ray = camera.primary(kSize / 2 + 0.5, kSize / 2 + 0.5);
  rtsim::Hit hit;
  rtsim::TraceCounters counters;
  if (!twin.tracer->closest_hit(ray, 0.0, rtsim::kInfinity, hit, counters)) return -1;
  const auto& shapes = twin.geometry->shapes;
  for (std::size_t s = 0; s < shapes.size(); ++s) {
    if (shapes[s].prim_id != hit.prim_id) continue;
    rtsim::SurfaceHit h;
    if (std::visit([&](const auto& k) { return k.intersect(ray, 0.0, rtsim::kInfinity, h); },
                   shapes[s].shape) &&
        h.t == hit.surface.t)
      return static_cast<long>(s);
  }
  return -1;
}

std::size_t pixels_differing(const Frame& a, const Frame& b) {
  std::size_t n = 0;
  for (std::size_t p = 0; p + 2 < a.rgb.size() && p + 2 < b.rgb.size(); p += 3)
    if (a.rgb[p] != b.rgb[p] || a.rgb[p + 1] != b.rgb[p + 1] || a.rgb[p + 2] != b.rgb[p + 2]) ++n;
  return n;
}

/// Flips the sign of d_p (word 3 of a line, firmware/kernels/ullner_quad_words.hpp: it mirrors
/// the polygon's plane through the origin) of the polygon the centre ray hits, in `memory` of
/// `machine`, whose lines are `line_words` long with polygon k at line k: some pixels and the
/// centre pixel change.
void expect_centre_polygon_fault_shows(const std::string& machine, const std::string& memory,
                                       std::uint64_t line_words) {
  const fs::path dir = rtsim::test::scratch_dir("data-path-" + machine);
  fs::create_directories(dir);
  const long slot = centre_slot();
  ASSERT_GE(slot, 0) << "the centre ray of " << kScene << " hits nothing";
  const std::uint64_t word = static_cast<std::uint64_t>(slot) * line_words +
                             static_cast<std::size_t>(rtsim::kernels::QuadParam::d_p);
  const Frame clean = simulate(machine, kScene, {}, {}, dir / "clean.bin");
  const Frame faulty =
      simulate(machine, kScene, {}, {{memory, word, 0x80000000u}}, dir / "faulty.bin");
  ASSERT_TRUE(clean.ok && faulty.ok);
  ASSERT_EQ(clean.rgb.size(), static_cast<std::size_t>(kSize * kSize * 3));
  const std::size_t changed = pixels_differing(clean, faulty);
  std::printf("%s: polygon %ld, word %llu flipped, %zu of %d pixels changed\n", machine.c_str(),
              slot, static_cast<unsigned long long>(word), changed, kSize * kSize);
  EXPECT_GT(changed, 0u);
  const std::size_t centre = (static_cast<std::size_t>(kSize / 2) * kSize + kSize / 2) * 3;
  EXPECT_NE(clean.rgb[centre] + clean.rgb[centre + 1] + clean.rgb[centre + 2],
            faulty.rgb[centre] + faulty.rgb[centre + 1] + faulty.rgb[centre + 2])
      << "the centre pixel's polygon moved but the centre pixel did not change";
  fs::remove_all(dir);
}

TEST(DataPath, PeripheralParameterMemoryWordChangesTheImage) {
  expect_centre_polygon_fault_shows("ullner-peripheral", "peripheral.parameter_memories",
                                    rtsim::kernels::kUllnerStoredWords);
}

TEST(DataPath, PipelineProcessorPolygonChangesTheImage) {
  // The pipeline's twin searches the same quads in the same order as the peripheral's brute
  // force, and processor k holds slot k: its registers are a line of the polygon words and the
  // identity (PolygonDescription).
  expect_centre_polygon_fault_shows("ullner-pipeline", "pipeline.polygon_registers",
                                    rtsim::kernels::kUllnerStoredWords + 1);
}

TEST(DataPath, GaudetShellBusMemoryWordChangesTheImage) {
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
  const Frame clean = simulate("gaudet-pert", "builtin:npp-412", two, {}, dir / "clean.bin");
  const Frame faulty = simulate("gaudet-pert", "builtin:npp-412", two,
                                {{"shell_bus.memory", word, 0x80000000u}}, dir / "faulty.bin");
  ASSERT_TRUE(clean.ok && faulty.ok);
  const std::size_t changed = pixels_differing(clean, faulty);
  std::printf(
      "shell_bus.memory word %llu (SHELL 0 of packet 0, box x %g..%g) flipped: %zu of %d "
      "pixels changed\n",
      static_cast<unsigned long long>(word), lo, hi, changed, kSize * kSize);
  EXPECT_GT(changed, 0u);

  // The first PRIM record of packet 0 in the Prim bus's memory, a sphere: raising its radius's
  // exponent by 128 makes it enclose the whole scene, so every ray that reaches its leaf shell
  // (the boxes still cull) hits it.
  ASSERT_EQ(sets.prim.memory.at(0), 0u);
  const std::uint32_t prim_address = sets.prim.memory.at(1);
  ASSERT_EQ(sets.prim.memory.at(prim_address + 2),
            static_cast<std::uint32_t>(rtsim::accel::PrimType::Sphere));
  const std::uint64_t radius_word = prim_address + 6;  // prim_id, surface, type, centre[3], radius
  const Frame big = simulate("gaudet-pert", "builtin:npp-412", two,
                             {{"prim_bus.memory", radius_word, 0x40000000u}}, dir / "big.bin");
  ASSERT_TRUE(big.ok);
  const std::size_t changed_prim = pixels_differing(clean, big);
  std::printf(
      "prim_bus.memory word %llu (radius of the first sphere) corrupted: %zu of %d pixels "
      "changed\n",
      static_cast<unsigned long long>(radius_word), changed_prim, kSize * kSize);
  EXPECT_GT(changed_prim, 0u);
  fs::remove_all(dir);
}

TEST(DataPath, ACorruptedIdListStallsGaudetPertWithAClearError) {
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

TEST(DataPath, FaultOnTheCommandLine) {
  const fs::path dir = rtsim::test::scratch_dir("fault-cli");
  const std::string base =
      "run --machine ullner-peripheral --scene builtin:ullner-cubes "
      "--width 16 --height 16 -q --out ";
  auto r =
      run_rtsim(base + (dir / "a").string() + " --fault peripheral.parameter_memorys:3:0x80000000");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("did you mean 'peripheral.parameter_memories'"), std::string::npos)
      << r.output;
  EXPECT_FALSE(fs::exists(dir / "a"));
  r = run_rtsim(base + (dir / "b").string() + " --fault peripheral.parameter_memories:99999999:1");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("holds"), std::string::npos) << r.output;
  r = run_rtsim(base + (dir / "c").string() + " --fault peripheral.parameter_memories:3");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  r = run_rtsim(base + (dir / "d").string() +
                " --fault peripheral.parameter_memories:3:0x80000000");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  const auto stats = rtsim::test::read_json(dir / "d" / "stats.json");
  ASSERT_TRUE(stats.contains("faults")) << stats.dump();
  EXPECT_EQ(stats["faults"][0]["applied"], 1);
  fs::remove_all(dir);
}

}  // namespace
