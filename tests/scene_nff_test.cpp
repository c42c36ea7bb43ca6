// NFF reader: the shared SPD scenes parse with the counts we counted by hand (grep of the
// keywords), the parts of the format the SPD files do not use (cones, light colours, view keys in
// any order, comments, CRLF), and write_nff -> parse_nff round trips.
#include <gtest/gtest.h>

#include "scene_test_support.hpp"
#include "scenes/nff_reader.hpp"
#include "scenes/scene_writer.hpp"

namespace rtsim::scenes {
namespace {

using testing::expect_same_content;
using testing::expect_scene_sound;
using testing::shared_scene;

struct SharedSceneCounts {
  const char* file;
  std::size_t spheres;
  std::size_t polygons;     // p
  std::size_t pp_polygons;  // pp (with normals)
  std::size_t lights;
  std::size_t materials;      // distinct f lines used
  std::size_t vertices_each;  // vertex count of the pp/p polygons after the floor, 0 = mixed
};

// Expected values counted from the files themselves (`awk '{print $1}' | sort | uniq -c`):
// balls: 1 floor quad + 10/91/820 spheres, 3 lights, 2 f lines; tetra-s3: 64 triangles, 1 light,
// 1 f; teapot-s2: 4 checkerboard quads (2 f) + 240 pp triangles (1 f), 2 lights.
const SharedSceneCounts kShared[] = {
    {"balls-s1.nff", 10, 1, 0, 3, 2, 0},   {"balls-s2.nff", 91, 1, 0, 3, 2, 0},
    {"balls-s3.nff", 820, 1, 0, 3, 2, 0},  {"tetra-s3.nff", 0, 64, 0, 1, 1, 3},
    {"teapot-s2.nff", 0, 4, 240, 2, 3, 0},
};

TEST(SceneNff, SharedScenesParseWithTheRightCounts) {
  for (const auto& c : kShared) {
    SCOPED_TRACE(c.file);
    const Scene s = read_nff(shared_scene(c.file));
    expect_scene_sound(s);
    EXPECT_TRUE(s.has_camera);
    EXPECT_EQ(s.camera.width, 512);
    EXPECT_EQ(s.camera.height, 512);
    EXPECT_EQ(s.camera.angle_deg, 45.0);
    EXPECT_EQ(s.spheres.size(), c.spheres);
    std::size_t p = 0, pp = 0;
    for (const Polygon& poly : s.polygons) (poly.normals.empty() ? p : pp) += 1;
    EXPECT_EQ(p, c.polygons);
    EXPECT_EQ(pp, c.pp_polygons);
    EXPECT_EQ(s.primitives.size(), c.spheres + c.polygons + c.pp_polygons);
    EXPECT_EQ(s.lights.size(), c.lights);
    EXPECT_EQ(s.materials.size(), c.materials);
    EXPECT_TRUE(s.cones.empty());
    EXPECT_TRUE(s.patches.empty());
    EXPECT_EQ(s.background, (Vec3{0.078, 0.361, 0.753}));
    if (c.vertices_each != 0) {
      for (const Polygon& poly : s.polygons) EXPECT_EQ(poly.vertices.size(), c.vertices_each);
    }
  }
}

TEST(SceneNff, BallsS1DetailsAndSourceLines) {
  const Scene s = read_nff(shared_scene("balls-s1.nff"));
  EXPECT_EQ(s.camera.from, (Vec3{2.1, 1.3, 1.7}));
  EXPECT_EQ(s.camera.at, (Vec3{0, 0, 0}));
  EXPECT_EQ(s.camera.up, (Vec3{0, 0, 1}));
  EXPECT_EQ(s.camera.hither, 0.01);
  EXPECT_EQ(s.lights[1].position, (Vec3{1, -4, 4}));
  EXPECT_EQ(s.lights[1].color, (Color{1.0}));  // no colour given -> white
  // Line 12 "f 1 0.75 0.33 0.8 0 100000 0 1", line 13 "p 4", line 18 the sphere material,
  // line 19 the first sphere.
  ASSERT_EQ(s.primitives[0].kind, PrimitiveKind::Polygon);
  EXPECT_EQ(s.primitives[0].source_line, 13u);
  EXPECT_EQ(s.polygons[0].vertices[2], (Vec3{-12, -12, -0.5}));
  const Material& floor = s.materials[s.primitives[0].material];
  EXPECT_EQ(floor.color, (Color{1, 0.75, 0.33}));
  EXPECT_EQ(floor.kd, 0.8);
  EXPECT_EQ(floor.shine, 100000.0);
  ASSERT_EQ(s.primitives[1].kind, PrimitiveKind::Sphere);
  EXPECT_EQ(s.primitives[1].source_line, 19u);
  EXPECT_EQ(s.spheres[0].radius, 0.5);
  EXPECT_EQ(s.primitives.back().source_line, 28u);
  EXPECT_EQ(s.spheres[2].center.z, 1.11022e-16);
  const Material& ball = s.materials[s.primitives[1].material];
  EXPECT_EQ(ball.ks, 0.5);
  EXPECT_EQ(ball.shine, 3.0827);
  EXPECT_EQ(ball.ior, 1.0);
}

TEST(SceneNff, TeapotPolygonsWithNormals) {
  const Scene s = read_nff(shared_scene("teapot-s2.nff"));
  const Polygon& first_pp = s.polygons[4];
  ASSERT_EQ(first_pp.vertices.size(), 3u);
  ASSERT_EQ(first_pp.normals.size(), 3u);
  EXPECT_EQ(first_pp.vertices[0], (Vec3{1.4, 0, 2.4}));
  EXPECT_EQ(first_pp.normals[0], (Vec3{-0.902861, -0.0, -0.429934}));
  EXPECT_EQ(s.primitives[4].source_line, 34u);
  // SPD writes ior 0 for opaque materials: kept as read.
  EXPECT_EQ(s.materials[s.primitives[4].material].ior, 0.0);
}

TEST(SceneNff, SharedScenesRoundTripExactly) {
  for (const auto& c : kShared) {
    SCOPED_TRACE(c.file);
    const Scene a = read_nff(shared_scene(c.file));
    const std::string text = write_nff(a);
    const Scene b = parse_nff(text, "roundtrip.nff");
    expect_same_content(a, b);
    EXPECT_EQ(write_nff(b).substr(write_nff(b).find('\n')), text.substr(text.find('\n')))
        << "writing is a fixed point after one round";
  }
}

TEST(SceneNff, FeaturesTheSpdFilesDoNotUse) {
  const std::string text =
      "# every entity, view keys shuffled, CRLF line ends, blank lines, signs and exponents\r\n"
      "\r\n"
      "v\r\n"
      "resolution 320 200\r\n"
      "up 0 +1 0\r\n"
      "hither 0\r\n"
      "at 0 0 0\r\n"
      "angle 30.5\r\n"
      "from 0 0 1E1\r\n"
      "b 0.1 0.2 0.3\r\n"
      "l 1 2 3 0.5 0.25 1\r\n"
      "\t s  0 0 0   1.5e0 \r\n"
      "f 1 0 0 0.6 0.4 10 0 1\r\n"
      "c\r\n"
      "0 0 0 -1\r\n"
      "# comment between the cone's lines is allowed\r\n"
      "0 2 0 .5\r\n"
      "f 1 0 0 0.6 0.4 10 0 1\r\n"
      "p 3\r\n"
      "0 0 0\r\n"
      "0 0 0\r\n"
      "0 0 0\r\n"
      "f 1 1 1 0 0 0 0.9 1.5\r\n"
      "pp 3\r\n"
      "0 0 0 0 0 0\r\n"
      "1 0 0 0 0 1\r\n"
      "0 1 0 0 0 1";  // no final newline
  const Scene s = parse_nff(text, "features.nff");
  expect_scene_sound(s);
  EXPECT_TRUE(s.has_camera);
  EXPECT_EQ(s.camera.width, 320);
  EXPECT_EQ(s.camera.height, 200);
  EXPECT_EQ(s.camera.from, (Vec3{0, 0, 10}));
  EXPECT_EQ(s.camera.angle_deg, 30.5);
  EXPECT_EQ(s.camera.hither, 0.0);
  EXPECT_EQ(s.background, (Color{0.1, 0.2, 0.3}));
  EXPECT_EQ(s.lights.at(0).color, (Color{0.5, 0.25, 1}));
  ASSERT_EQ(s.primitives.size(), 4u);
  // The sphere comes before any f: default material.
  const Material& def = s.materials[s.primitives[0].material];
  EXPECT_EQ(def.color, kDefaultNffMaterial.color);
  EXPECT_EQ(def.kd, kDefaultNffMaterial.kd);
  EXPECT_EQ(s.primitives[0].source_line, 12u);
  // Cone keeps the sign of the inside-visible radius; source line is the 'c' line.
  ASSERT_EQ(s.cones.size(), 1u);
  EXPECT_EQ(s.cones[0].base_radius, -1.0);
  EXPECT_EQ(s.cones[0].apex, (Vec3{0, 2, 0}));
  EXPECT_EQ(s.cones[0].apex_radius, 0.5);
  EXPECT_EQ(s.primitives[1].source_line, 14u);
  // Two identical f lines share one material; degenerate polygon and zero normal are kept.
  EXPECT_EQ(s.primitives[1].material, s.primitives[2].material);
  EXPECT_EQ(s.materials.size(), 3u);
  EXPECT_EQ(s.polygons[0].vertices[1], (Vec3{0.0}));
  EXPECT_EQ(s.polygons[1].normals[0], (Vec3{0.0}));
  const Material& glass = s.materials[s.primitives[3].material];
  EXPECT_EQ(glass.transmittance, 0.9);
  EXPECT_EQ(glass.ior, 1.5);
  // Round trip of the features scene, cone included.
  expect_same_content(s, parse_nff(write_nff(s), "again.nff"));
}

TEST(SceneNff, NoViewBlockMeansNoCamera) {
  const Scene s = parse_nff("s 0 0 0 1\n", "noview.nff");
  EXPECT_FALSE(s.has_camera);
  EXPECT_TRUE(s.lights.empty());
  ASSERT_EQ(s.materials.size(), 1u);
  EXPECT_EQ(s.name, "noview.nff");
}

TEST(SceneNff, CommentsMayHoldUtf8) {
  const Scene s = parse_nff("# caf\xC3\xA9 au lait\ns 0 0 0 1\n", "utf8.nff");
  EXPECT_EQ(s.spheres.size(), 1u);
}

}  // namespace
}  // namespace rtsim::scenes
