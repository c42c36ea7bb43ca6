// Generated scenes: Gaudet's npp clusters, Ullner's 83 cubes, the default scene, and the
// builtin: names of the loader. Checks are structural and exact (no tolerances except the
// geometric ones stated next to them).
#include <gtest/gtest.h>

#include <algorithm>
#include <set>

#include "common/splitmix64.hpp"
#include "common/suggest.hpp"
#include "scene_test_support.hpp"
#include "scenes/bpt_reader.hpp"
#include "scenes/generators/default_scene.hpp"
#include "scenes/generators/npp_scene.hpp"
#include "scenes/generators/ullner_cubes.hpp"
#include "scenes/generators/ullner_random.hpp"
#include "scenes/nff_reader.hpp"
#include "scenes/scene_loader.hpp"
#include "scenes/scene_writer.hpp"

namespace rtsim::scenes {
namespace {

using testing::expect_input_error;
using testing::expect_same_content;
using testing::expect_scene_sound;

TEST(SceneGenerators, SplitMix64MatchesTheReferenceSequence) {
  // First outputs of SplitMix64 seeded with 1234567 (Vigna's reference splitmix64.c).
  SplitMix64 rng(1234567);
  EXPECT_EQ(rng.next(), 6457827717110365317ull);
  EXPECT_EQ(rng.next(), 3203168211198807973ull);
  EXPECT_EQ(rng.next(), 9817491932198370423ull);
  SplitMix64 r2(7);
  for (int i = 0; i < 1000; ++i) {
    const double u = r2.uniform();
    ASSERT_GE(u, 0.0);
    ASSERT_LT(u, 1.0);
    ASSERT_LT(r2.below(6), 6u);
  }
}

// --- npp --------------------------------------------------------------------------------------

TEST(SceneGenerators, NppExpectedCountsAreFigure61) {
  // Fig 6-1 (seed 001 L980-L989): shells, shell packets, primitives, primitive packets.
  struct Row {
    int n, pp, shells, shell_packets, prims, prim_packets;
  };
  const Row fig61[] = {{2, 4, 126, 63, 256, 64},
                       {4, 8, 84, 21, 512, 64},
                       {8, 12, 72, 9, 768, 64},
                       {8, 16, 72, 9, 1024, 64},
                       {8, 20, 72, 9, 1280, 64}};
  for (const Row& r : fig61) {
    const NppShellCounts c = npp_expected_counts(r.n, r.pp);
    EXPECT_EQ(c.shells, r.shells) << r.n << r.pp;
    EXPECT_EQ(c.shell_packets, r.shell_packets) << r.n << r.pp;
    EXPECT_EQ(c.primitives, r.prims) << r.n << r.pp;
    EXPECT_EQ(c.primitive_packets, r.prim_packets) << r.n << r.pp;
  }
}

TEST(SceneGenerators, NppScenesHaveContiguousClustersInsideTheirCells) {
  const double margin = kNppCellMargin * kNppCellSize;
  for (int n : {2, 4, 8}) {
    for (int pp : {4, 8, 12, 16, 20}) {
      SCOPED_TRACE("npp " + std::to_string(n) + " " + std::to_string(pp));
      const Scene s = make_npp_scene(n, pp);
      expect_scene_sound(s);
      ASSERT_EQ(s.spheres.size(), static_cast<std::size_t>(64 * pp));
      ASSERT_EQ(s.primitives.size(), s.spheres.size());
      ASSERT_EQ(s.cluster_of_primitive.size(), s.primitives.size());
      EXPECT_TRUE(s.has_camera);
      EXPECT_GE(s.lights.size(), 1u);
      EXPECT_LE(s.lights.size(), 2u);
      // Clusters 0..63 in order, each exactly pp consecutive primitives.
      for (std::size_t i = 0; i < s.primitives.size(); ++i) {
        ASSERT_EQ(s.cluster_of_primitive[i], i / static_cast<std::size_t>(pp));
      }
      for (std::size_t i = 0; i < s.primitives.size(); ++i) {
        const Sphere& sp = s.spheres[s.primitives[i].index];
        const Bounds cell = npp_cluster_cell(static_cast<int>(s.cluster_of_primitive[i]));
        for (int a = 0; a < 3; ++a) {
          ASSERT_GE(sp.center[a] - sp.radius, cell.lo[a] + margin);
          ASSERT_LE(sp.center[a] + sp.radius, cell.hi[a] - margin);
        }
        // No two spheres of a cluster overlap (documented choice).
        const std::size_t first = i - i % static_cast<std::size_t>(pp);
        for (std::size_t j = first; j < i; ++j) {
          const Sphere& o = s.spheres[s.primitives[j].index];
          ASSERT_GT(glm::length(sp.center - o.center), sp.radius + o.radius);
        }
      }
      // Some spheres are reflective (Ks >= 0.6) so reflection rays are exercised.
      const bool reflective =
          std::any_of(s.primitives.begin(), s.primitives.end(),
                      [&](const Primitive& p) { return s.materials[p.material].ks >= 0.6; });
      EXPECT_TRUE(reflective);
    }
  }
}

TEST(SceneGenerators, NppCellsAreAMortonOrderedGrid) {
  // Every aligned run of b consecutive clusters (b = 2, 4, 8, 16, 32, 64) covers a box made of
  // exactly b cells: what a complete b-ary tree over consecutive clusters needs.
  std::set<std::tuple<double, double, double>> corners;
  for (int k = 0; k < kNppClusterCount; ++k) {
    const Bounds c = npp_cluster_cell(k);
    EXPECT_EQ(c.extent(), Vec3{kNppCellSize});
    corners.insert({c.lo.x, c.lo.y, c.lo.z});
  }
  EXPECT_EQ(corners.size(), 64u) << "cells are distinct";
  for (int b = 2; b <= 64; b *= 2) {
    for (int start = 0; start < 64; start += b) {
      Bounds box;
      for (int k = start; k < start + b; ++k) box.extend(npp_cluster_cell(k));
      const Vec3 e = box.extent() / kNppCellSize;
      EXPECT_DOUBLE_EQ(e.x * e.y * e.z, b) << "run of " << b << " from " << start;
    }
  }
}

TEST(SceneGenerators, NppScenesWithTheSamePpShareTheirPrimitives) {
  for (int pp : {4, 12, 20}) {
    const Scene a = make_npp_scene(2, pp);
    const Scene b = make_npp_scene(4, pp);
    const Scene c = make_npp_scene(8, pp);
    expect_same_content(a, b);
    expect_same_content(a, c);
    EXPECT_EQ(a.cluster_of_primitive, c.cluster_of_primitive);
    EXPECT_EQ(a.name, "builtin:npp-2" + std::string(pp < 10 ? "0" : "") + std::to_string(pp));
  }
  // Different seed, different spheres.
  const Scene d = make_npp_scene(4, 8, kNppDefaultSeed + 1);
  EXPECT_NE(d.spheres[0].center, make_npp_scene(4, 8).spheres[0].center);
}

TEST(SceneGenerators, NppNamesAndArguments) {
  int n = 0, pp = 0;
  EXPECT_TRUE(parse_npp_name("npp-408", n, pp));
  EXPECT_EQ(n, 4);
  EXPECT_EQ(pp, 8);
  EXPECT_TRUE(parse_npp_name("npp-899", n, pp));
  EXPECT_FALSE(parse_npp_name("npp-300", n, pp));
  EXPECT_FALSE(parse_npp_name("npp-400", n, pp));
  EXPECT_FALSE(parse_npp_name("npp-40", n, pp));
  EXPECT_FALSE(parse_npp_name("npp-4a8", n, pp));
  EXPECT_FALSE(parse_npp_name("xpp-408", n, pp));
  EXPECT_THROW(make_npp_scene(3, 4), std::invalid_argument);
  EXPECT_THROW(make_npp_scene(2, 0), std::invalid_argument);
  EXPECT_THROW(make_npp_scene(2, 100), std::invalid_argument);
  // The extremes of pp still place every sphere without overlap.
  EXPECT_EQ(make_npp_scene(8, 99).spheres.size(), 64u * 99u);
  EXPECT_EQ(make_npp_scene(8, 1).spheres.size(), 64u);
}

// --- Ullner cubes -------------------------------------------------------------------------

TEST(SceneGenerators, UllnerCubesAreClosedOutwardFacingQuads) {
  const Scene s = make_ullner_cubes();
  expect_scene_sound(s);
  ASSERT_EQ(s.polygons.size(), 83u * 6u);
  ASSERT_EQ(s.primitives.size(), 498u);
  EXPECT_TRUE(s.spheres.empty());
  // Tolerance 1e-12: rotations are computed in double from unit quaternions; errors are a few
  // ulps of the unit-sized coordinates.
  constexpr double kTol = 1e-12;
  for (std::size_t cube = 0; cube < 83; ++cube) {
    Vec3 centre{0.0};
    for (std::size_t f = 0; f < 6; ++f) {
      for (const Vec3& v : s.polygons[6 * cube + f].vertices) centre += v / 24.0;
    }
    std::set<std::uint32_t> materials;
    for (std::size_t f = 0; f < 6; ++f) {
      const Polygon& q = s.polygons[6 * cube + f];
      ASSERT_EQ(q.vertices.size(), 4u);
      EXPECT_TRUE(q.normals.empty());
      materials.insert(s.primitives[6 * cube + f].material);
      Vec3 face_centre{0.0};
      for (int i = 0; i < 4; ++i) {
        const Vec3& a = q.vertices[static_cast<std::size_t>(i)];
        const Vec3& b = q.vertices[static_cast<std::size_t>((i + 1) % 4)];
        const Vec3& c = q.vertices[static_cast<std::size_t>((i + 2) % 4)];
        EXPECT_NEAR(glm::length(b - a), kUllnerCubeEdge, kTol);  // square: equal edges
        EXPECT_NEAR(glm::dot(b - a, c - b), 0.0, kTol);          // right angles
        for (int axis = 0; axis < 3; ++axis) {                   // inside the modelling cube
          EXPECT_GE(a[axis], 0.0);
          EXPECT_LE(a[axis], 1.0);
        }
        face_centre += a / 4.0;
      }
      // Counter-clockwise seen from outside: the right-hand normal points away from the cube.
      const Vec3 normal = glm::cross(q.vertices[1] - q.vertices[0], q.vertices[2] - q.vertices[1]);
      EXPECT_NEAR(glm::length(normal), kUllnerCubeEdge * kUllnerCubeEdge, kTol);
      EXPECT_GT(glm::dot(normal, face_centre - centre), 0.0);
      EXPECT_NEAR(glm::length(face_centre - centre), 0.5 * kUllnerCubeEdge, kTol);
    }
    EXPECT_EQ(materials.size(), 1u) << "one material per cube";
  }
  // Randomly oriented: the face normals of different cubes are not all axis-aligned.
  const Vec3 n0 = glm::normalize(glm::cross(s.polygons[0].vertices[1] - s.polygons[0].vertices[0],
                                            s.polygons[0].vertices[2] - s.polygons[0].vertices[1]));
  EXPECT_LT(std::max({std::fabs(n0.x), std::fabs(n0.y), std::fabs(n0.z)}), 0.999);
  EXPECT_EQ(make_ullner_cubes(5, 10).polygons.size(), 60u);
  EXPECT_THROW(make_ullner_cubes(5, 0), std::invalid_argument);
}

// --- default ----------------------------------------------------------------------------------

TEST(SceneGenerators, DefaultSceneHasMirrorGlassFloorAndTwoLights) {
  const Scene s = make_default_scene();
  expect_scene_sound(s);
  EXPECT_TRUE(s.has_camera);
  EXPECT_EQ(s.camera.width, 512);
  EXPECT_EQ(s.camera.height, 512);
  EXPECT_EQ(s.lights.size(), 2u);
  EXPECT_EQ(s.polygons.size(), static_cast<std::size_t>(kDefaultFloorTiles * kDefaultFloorTiles));
  bool mirror = false, glass = false;
  for (const Primitive& p : s.primitives) {
    const Material& m = s.materials[p.material];
    if (p.kind == PrimitiveKind::Sphere && m.ks >= 0.8) mirror = true;
    if (p.kind == PrimitiveKind::Sphere && m.transmittance >= 0.8 && m.ior == 1.5) glass = true;
  }
  EXPECT_TRUE(mirror);
  EXPECT_TRUE(glass);
  // Spheres rest on the floor (z = r), inside it, and do not overlap one another.
  for (std::size_t i = 0; i < s.spheres.size(); ++i) {
    const Sphere& a = s.spheres[i];
    EXPECT_EQ(a.center.z, a.radius);
    EXPECT_LE(std::fabs(a.center.x) + a.radius, kDefaultFloorHalfWidth);
    EXPECT_LE(std::fabs(a.center.y) + a.radius, kDefaultFloorHalfWidth);
    for (std::size_t j = 0; j < i; ++j) {
      EXPECT_GT(glm::length(a.center - s.spheres[j].center), a.radius + s.spheres[j].radius);
    }
  }
  // Every sphere is in front of the camera and inside its vertical field of view.
  const Vec3 forward = glm::normalize(s.camera.at - s.camera.from);
  for (const Sphere& sp : s.spheres) {
    const Vec3 d = glm::normalize(sp.center - s.camera.from);
    const double angle_deg = std::acos(glm::dot(d, forward)) * 180.0 / kPi;
    EXPECT_LT(angle_deg, 0.5 * s.camera.angle_deg);
  }
}

// --- Determinism and round trips ----------------------------------------------------------------

TEST(SceneGenerators, GeneratorsAreByteForByteDeterministicAndRoundTrip) {
  // The NFF round trip of the largest listed scenes (10^5 and 10^6 polygons, ~10 and ~100 MB of
  // text) would dominate the suite; their generator is checked in scene_ullner_random_test.cpp
  // and shares all code with the listed smaller sizes.
  constexpr std::size_t kRoundTripMaxPrimitives = 20'000;
  for (const std::string& name : builtin_scene_names()) {
    SCOPED_TRACE(name);
    if (const auto n = parse_ullner_random_name(name); n && *n > kRoundTripMaxPrimitives) continue;
    const Scene a = load_scene("builtin:" + name);
    const Scene b = load_scene("builtin:" + name);
    // Patch scenes (builtin:teapot) export as .bpt, the rest as NFF; a scene with both
    // (builtin:spd-teapot-patches) has no file format, so it is compared part by part.
    const bool patches = !a.patches.empty();
    if (patches && a.patches.size() != a.primitives.size()) {
      EXPECT_EQ(a.primitives.size(), b.primitives.size());
      EXPECT_EQ(a.polygons.size(), b.polygons.size());
      for (std::size_t i = 0; i < a.patches.size(); ++i)
        EXPECT_EQ(a.patches[i].control, b.patches[i].control);
      EXPECT_EQ(a.name, "builtin:" + name);
      continue;
    }
    const std::string ta = patches ? write_bpt(a) : write_nff(a);
    EXPECT_EQ(ta, patches ? write_bpt(b) : write_nff(b));
    EXPECT_EQ(a.cluster_of_primitive, b.cluster_of_primitive);
    EXPECT_EQ(a.name, "builtin:" + name);
    // The export reads back to the same scene (the reader's rules accept every generator).
    expect_same_content(a, patches ? parse_bpt(ta, name + ".bpt") : parse_nff(ta, name + ".nff"));
  }
}

// --- Loader -----------------------------------------------------------------------------------

TEST(SceneLoader, BuiltinNamesAndDescriptions) {
  const auto names = builtin_scene_names();
  ASSERT_EQ(names.size(), 30u);
  EXPECT_EQ(names[0], "default");
  EXPECT_EQ(names[1], "ullner-cubes");
  EXPECT_EQ(names[2], "ullner-random-100");
  EXPECT_EQ(names[6], "ullner-random-1000000");
  EXPECT_EQ(names[7], "ullner-sheets-1000");
  EXPECT_EQ(names[8], "ullner-sheets-lit-1000");
  EXPECT_EQ(names[9], "teapot");
  EXPECT_EQ(names[10], "spd-teapot");
  EXPECT_EQ(names[11], "spd-teapot-patches");
  EXPECT_EQ(names[12], "bowling");
  EXPECT_NE(std::find(names.begin(), names.end(), "npp-812"), names.end());
  EXPECT_EQ(names[28], "plb-head");
  EXPECT_EQ(names[29], "ullner-mosaic-64");
  // plb-head: the PLB head's stand-in, about its 59,592 polygons (seed 004 L570).
  EXPECT_EQ(load_scene("builtin:plb-head").polygons.size(), 59536u);
  // ullner-mosaic-N: N columns of 8 quads; N within a line's 4096 steps.
  EXPECT_EQ(load_scene("builtin:ullner-mosaic-10").polygons.size(), 80u);
  EXPECT_THROW(load_scene("builtin:ullner-mosaic-5000"), rtsim::InputError);
  EXPECT_THROW(load_scene("builtin:ullner-mosaic-0"), rtsim::InputError);
  // A number past the range, however long, gets the range, not "unknown scene".
  try {
    load_scene("builtin:ullner-mosaic-12345678901");
    ADD_FAILURE() << "an 11-digit mosaic was accepted";
  } catch (const rtsim::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("takes N from"), std::string::npos) << e.what();
  }
  for (const auto& s : builtin_scenes()) {
    EXPECT_FALSE(s.description.empty());
    EXPECT_EQ(s.description.find('\n'), std::string::npos);
  }
  // npp names beyond the listed ones are accepted.
  EXPECT_EQ(load_scene("builtin:npp-203").spheres.size(), 64u * 3u);
  // Seeds are plain arguments.
  GeneratorSeeds seeds = default_generator_seeds();
  seeds.ullner_cubes += 1;
  EXPECT_NE(load_scene("builtin:ullner-cubes", seeds).polygons[0].vertices[0],
            load_scene("builtin:ullner-cubes").polygons[0].vertices[0]);
}

TEST(SceneLoader, UnknownBuiltinSuggestsTheClosestNames) {
  expect_input_error([] { load_scene("builtin:defualt"); }, 0,
                     "unknown builtin scene 'defualt'; did you mean builtin:default?");
  expect_input_error([] { load_scene("builtin:ullner"); }, 0,
                     "did you mean builtin:ullner-cubes, builtin:ullner-random-100, "
                     "builtin:ullner-random-1000?");
  expect_input_error([] { load_scene("builtin:ullner-randm-1000"); }, 0,
                     "did you mean builtin:ullner-random-1000,");
  expect_input_error([] { load_scene("builtin:npp-1204"); }, 0, "did you mean builtin:npp-204");
  expect_input_error([] { load_scene("builtin:npp-300"); }, 0, "npp-NPP takes n in {2,4,8}");
  expect_input_error([] { load_scene("builtin:"); }, 0, "unknown builtin scene ''");
  EXPECT_EQ(rtsim::edit_distance("kitten", "sitting"), 3u);
  EXPECT_EQ(rtsim::edit_distance("", "abc"), 3u);
}

TEST(SceneLoader, FilesDispatchByExtension) {
  const Scene nff = load_scene(testing::shared_scene("tetra-s3.nff"));
  EXPECT_EQ(nff.polygons.size(), 64u);
  EXPECT_EQ(nff.name, testing::shared_scene("tetra-s3.nff"));
  const Scene bpt = load_scene(testing::shared_scene("teapot.bpt"));
  EXPECT_EQ(bpt.patches.size(), 32u);
}

}  // namespace
}  // namespace rtsim::scenes
