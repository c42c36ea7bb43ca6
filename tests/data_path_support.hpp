#pragma once
// A machine's answers come from the data its transactions carry (DESIGN.md "Data flows through
// the model"): corrupt one word on its way into a machine's memory and the image changes. What
// the machines' data-path tests share: a run in a child with faults, its image, and the word of
// the polygon the centre ray hits (for the machines that hold Ullner's quads a line each).
// Each simulation runs in a forked child (SystemC allows one per process).
#include <gtest/gtest.h>

#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "firmware/kernels/ullner_quad_words.hpp"
#include "firmware/shading/camera.hpp"
#include "platform/machine.hpp"
#include "tests/machine_test_support.hpp"
#include "tests/test_support.hpp"

namespace rtsim::test::data_path {

namespace fs = std::filesystem;

inline constexpr int kSize = 32;
inline constexpr const char* kScene = "builtin:ullner-cubes";

struct Frame {
  bool ok = false;
  std::vector<float> rgb;
};

/// Runs `machine_name` on `scene_name` at kSize x kSize with `faults` and `overrides`, in a
/// child; the image.
inline Frame simulate(const std::string& machine_name, const std::string& scene_name,
                      const std::vector<std::string>& overrides,
                      const std::vector<rtsim::platform::MemoryFault>& faults,
                      const fs::path& out) {
  Frame frame;
  frame.ok = image_in_child(machine_name, scene_name, kSize, overrides, faults, out) == 0;
  if (frame.ok) {
    const std::string bytes = rtsim::test::read_file(out);
    frame.rgb.resize(bytes.size() / sizeof(float));
    std::memcpy(frame.rgb.data(), bytes.data(), frame.rgb.size() * sizeof(float));
  }
  return frame;
}

/// The slot (line of `machine`'s polygon memory) of the polygon the centre pixel's ray hits, from
/// the twin (no simulation); -1 if it hits nothing.
inline long centre_slot(const std::string& machine) {
  auto m = rtsim::test::prepare_machine(machine, kScene);
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

inline std::size_t pixels_differing(const Frame& a, const Frame& b) {
  std::size_t n = 0;
  for (std::size_t p = 0; p + 2 < a.rgb.size() && p + 2 < b.rgb.size(); p += 3)
    if (a.rgb[p] != b.rgb[p] || a.rgb[p + 1] != b.rgb[p + 1] || a.rgb[p + 2] != b.rgb[p + 2]) ++n;
  return n;
}

/// Flips the sign of d_p (word 3 of a line, firmware/kernels/ullner_quad_words.hpp: it mirrors
/// the polygon's plane through the origin) of the polygon the centre ray hits, in `memory` of
/// `machine`, whose lines are `line_words` long with polygon k at line k: some pixels and the
/// centre pixel change.
inline void expect_centre_polygon_fault_shows(
    const std::string& machine, const std::string& memory, std::uint64_t line_words,
    std::uint64_t word_in_line = static_cast<std::size_t>(rtsim::kernels::QuadParam::d_p),
    std::uint32_t mask = 0x80000000u) {
  const fs::path dir = rtsim::test::scratch_dir("data-path-" + machine);
  fs::create_directories(dir);
  const long slot = centre_slot(machine);
  ASSERT_GE(slot, 0) << "the centre ray of " << kScene << " hits nothing";
  const std::uint64_t word = static_cast<std::uint64_t>(slot) * line_words + word_in_line;
  const Frame clean = simulate(machine, kScene, {}, {}, dir / "clean.bin");
  const Frame faulty = simulate(machine, kScene, {}, {{memory, word, mask}}, dir / "faulty.bin");
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

}  // namespace rtsim::test::data_path
