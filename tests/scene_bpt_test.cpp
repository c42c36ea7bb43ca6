// .bpt reader: the shared Newell teapot (32 bicubic patches) and its error rules.
#include <gtest/gtest.h>

#include "scene_test_support.hpp"
#include "scenes/bpt_reader.hpp"
#include "scenes/scene_loader.hpp"
#include "scenes/scene_text.hpp"
#include "scenes/scene_writer.hpp"

namespace rtsim::scenes {
namespace {

using testing::expect_input_error;
using testing::expect_same_content;
using testing::expect_same_view;
using testing::expect_scene_sound;
using testing::shared_scene;

std::string patch_text(int degree_u = 3, int degree_v = 3, int points = 16) {
  std::string t = std::to_string(degree_u) + " " + std::to_string(degree_v) + "\n";
  for (int i = 0; i < points; ++i)
    t += std::to_string(i % 4) + " " + std::to_string(i / 4) + " 0\n";
  return t;
}

TEST(SceneBpt, TeapotHas32PatchesAndNoCamera) {
  const Scene s = read_bpt(shared_scene("teapot.bpt"));
  expect_scene_sound(s);
  EXPECT_FALSE(s.has_camera);
  ASSERT_EQ(s.patches.size(), 32u);
  ASSERT_EQ(s.primitives.size(), 32u);
  ASSERT_EQ(s.materials.size(), 1u);
  EXPECT_EQ(s.materials[0].color, kDefaultBptMaterial.color);
  EXPECT_TRUE(s.lights.empty());
  // File: line 1 "32", patch k's "3 3" on line 2 + 17 k, its points on the 16 lines after.
  for (std::size_t k = 0; k < 32; ++k) {
    EXPECT_EQ(s.primitives[k].kind, PrimitiveKind::Patch);
    EXPECT_EQ(s.primitives[k].index, k);
    EXPECT_EQ(s.primitives[k].source_line, 2 + 17 * k);
  }
  EXPECT_EQ(s.patches[0].at(0, 0), (Vec3{1.4, 0, 2.4}));
  EXPECT_EQ(s.patches[0].at(0, 1), (Vec3{1.4, -0.784, 2.4}));
  EXPECT_EQ(s.patches[0].at(1, 0), (Vec3{1.3375, 0, 2.53125}));
  EXPECT_EQ(s.patches[0].at(3, 3), (Vec3{0, -1.5, 2.4}));
  EXPECT_EQ(s.patches[31].at(3, 3), (Vec3{1.5, 0, 0.15}));
}

TEST(SceneBpt, RoundTrip) {
  const Scene a = read_bpt(shared_scene("teapot.bpt"));
  const Scene b = parse_bpt(write_bpt(a), "again.bpt");
  expect_same_content(a, b);
}

// builtin:teapot is the shared file's patches, built in (scenes/generators/newell_teapot.cpp).
TEST(SceneBpt, BuiltinTeapotIsTheSharedFile) {
  const Scene file = read_bpt(shared_scene("teapot.bpt"));
  const Scene builtin = load_scene("builtin:teapot");
  EXPECT_EQ(builtin.name, "builtin:teapot");
  expect_same_content(file, builtin);
  ASSERT_EQ(builtin.patches.size(), file.patches.size());
  for (std::size_t k = 0; k < file.patches.size(); ++k)
    for (std::size_t i = 0; i < 16; ++i)
      EXPECT_EQ(builtin.patches[k].control[i], file.patches[k].control[i]) << k << " " << i;
}

TEST(SceneBpt, CommentsAndBlankLinesAreAllowed) {
  const Scene s = parse_bpt("# one flat patch\n\n1\n" + patch_text(), "flat.bpt");
  ASSERT_EQ(s.patches.size(), 1u);
  EXPECT_EQ(s.primitives[0].source_line, 4u);
  EXPECT_EQ(s.patches[0].at(2, 1), (Vec3{1, 2, 0}));
}

TEST(SceneBpt, ControlPointsInAnyLayout) {
  // Count-driven, as the NFF reader: line ends are whitespace like any other.
  const Scene ref = parse_bpt("1\n" + patch_text(), "ref.bpt");
  std::string one_line = "1 " + patch_text();
  for (char& c : one_line) c = c == '\n' ? ' ' : c;
  std::string two_per_line = "1\n3\n3\n";
  int k = 0;
  for (char c : patch_text().substr(4)) {
    if (c == ' ' || c == '\n') c = (++k % 2 == 0) ? '\n' : ' ';
    two_per_line += c;
  }
  for (const std::string& text :
       {one_line, two_per_line,
        "1.0 # patch count\n3.0 3e0 # degrees\n" + patch_text().substr(4)}) {
    SCOPED_TRACE(text.substr(0, 40));
    const Scene s = parse_bpt(text, "layout.bpt");
    expect_scene_sound(s);
    expect_same_content(ref, s);
  }
  EXPECT_EQ(parse_bpt(one_line, "one.bpt").primitives.at(0).source_line, 1u);
}

TEST(SceneBpt, TeapotWithOtherLineEndsAndLayouts) {
  const std::string original = read_scene_file(shared_scene("teapot.bpt"));
  const Scene ref = parse_bpt(original, "teapot.bpt");
  std::string cr = original;
  for (char& c : cr) c = c == '\n' ? '\r' : c;
  std::string flat = original;
  for (char& c : flat) c = c == '\n' ? ' ' : c;
  const Scene from_cr = parse_bpt("\xEF\xBB\xBF" + cr, "cr.bpt");
  const Scene from_flat = parse_bpt(flat + " # all on one line\n", "flat.bpt");
  expect_same_content(ref, from_cr);
  expect_same_content(ref, from_flat);
  for (std::size_t k = 0; k < ref.primitives.size(); ++k) {
    EXPECT_EQ(from_cr.primitives[k].source_line, ref.primitives[k].source_line);
    EXPECT_EQ(from_flat.primitives[k].source_line, 1u);
  }
}

TEST(SceneBpt, BadInput) {
  auto parse = [](const std::string& text) { return [text] { parse_bpt(text, "bad.bpt"); }; };
  expect_input_error(parse(""), 0, "empty .bpt file");
  expect_input_error(parse("# only a comment\n"), 0, "empty .bpt file");
  expect_input_error(parse("abc\n"), 1, "expected an integer for the patch count, got 'abc'");
  expect_input_error(parse("1.5\n"), 1, "expected an integer for the patch count");
  expect_input_error(parse("1 2\n"), 1,
                     "file declares 1 patch (50 numbers each: the degrees '3 3' and 16 control "
                     "points x y z) but has only 1 value left");
  expect_input_error(parse("2.5\n"), 1, "expected an integer for the patch count, got '2.5'");
  expect_input_error(parse("0\n"), 1, "patch count must be 1..1000000 (kMaxBptPatches), got '0'");
  expect_input_error(parse("-4\n"), 1, "patch count must be 1..");
  expect_input_error(parse("2000000\n"), 1, "patch count must be 1..1000000");
  expect_input_error(parse("99999999999999999999999\n"), 1, "far too large");
  // Count checked against the values left before anything is allocated (comments hold none).
  expect_input_error(parse("999999\n" + patch_text()), 1,
                     "file declares 999999 patches (50 numbers each: the degrees '3 3' and 16 "
                     "control points x y z) but has only 50 values left");
  expect_input_error(parse("1\n" + patch_text(2, 3)), 2,
                     "patch 1 of 1 has degrees '2 3'; only bicubic patches ('3 3') are supported");
  expect_input_error(parse("1\n3\n" + patch_text().substr(4)), 1,
                     "file declares 1 patch (50 numbers each: the degrees '3 3' and 16 control "
                     "points x y z) but has only 49 values left");
  // A patch with a 17th point: its numbers are read as patch 2's degrees.
  expect_input_error(parse("2\n" + patch_text(3, 3, 17) + patch_text()), 19,
                     "patch 2 of 2 has degrees '0 4'; only bicubic patches ('3 3') are supported");
  // Truncated inside a patch, with comments after: found by the count.
  expect_input_error(parse("1\n" + patch_text(3, 3, 15) + "# 0 0 0\n#\n"), 1,
                     "but has only 47 values left");
  expect_input_error(parse("2\n" + patch_text() + std::string(17, '\n')), 1,
                     "file declares 2 patches (50 numbers each: the degrees '3 3' and 16 control "
                     "points x y z) but has only 50 values left");
  expect_input_error(parse("1\n3 3\n0 0 0\n0 0 x\n" + patch_text().substr(4 + 6 * 2)), 4,
                     "expected a number for control point 2 of 16 of patch 1 of 1 (value 3), got "
                     "'x'");
  expect_input_error(parse("1\n3 3\n0 0 nan\n" + patch_text().substr(4 + 6)), 3,
                     "'nan' for control point 1 of 16 of patch 1 of 1 (value 3) is not a finite");
  expect_input_error(parse("1\n" + patch_text() + "1 2 3\n"), 19,
                     "unexpected content after the last of 1 patches: '1 2 3'");
  expect_input_error(parse("1\n3 3\x01\n"), 2, "non-printable byte 0x01 at column 4");
}

// builtin:spd-teapot is SPD's teapot scene (shared/scenes/teapot-s2.nff) with the patches cut
// finer: the same view, lights, background, materials and checkerboard, and a teapot of the same
// extent.
TEST(SceneBpt, BuiltinSpdTeapotIsSpdsTeapotScene) {
  const Scene file = load_scene(shared_scene("teapot-s2.nff"));
  const Scene built = load_scene("builtin:spd-teapot");
  expect_same_view(file, built);
  ASSERT_EQ(built.materials.size(), file.materials.size());
  for (std::size_t i = 0; i < file.materials.size(); ++i) {
    EXPECT_EQ(built.materials[i].color, file.materials[i].color) << i;
    EXPECT_EQ(built.materials[i].kd, file.materials[i].kd) << i;
    EXPECT_EQ(built.materials[i].shine, file.materials[i].shine) << i;
  }
  // The checkerboard: the first four polygons, as sets of corners.
  for (std::size_t i = 0; i < 4; ++i) {
    Bounds a, b;
    for (const Vec3& v : file.polygons[i].vertices) a.extend(v);
    for (const Vec3& v : built.polygons[i].vertices) b.extend(v);
    EXPECT_EQ(a.lo, b.lo) << i;
    EXPECT_EQ(a.hi, b.hi) << i;
  }
  // The teapot: triangles with a normal a vertex, over the same box as SPD's coarser cut.
  Bounds a, b;
  for (std::size_t i = 4; i < file.polygons.size(); ++i)
    for (const Vec3& v : file.polygons[i].vertices) a.extend(v);
  for (std::size_t i = 4; i < built.polygons.size(); ++i) {
    ASSERT_EQ(built.polygons[i].vertices.size(), 3u);
    ASSERT_EQ(built.polygons[i].normals.size(), 3u);
    for (const Vec3& v : built.polygons[i].vertices) b.extend(v);
  }
  EXPECT_EQ(built.polygons.size(), 4u + 992u);
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(a.lo[k], b.lo[k], 0.02) << k;
    EXPECT_NEAR(a.hi[k], b.hi[k], 0.02) << k;
  }
}

}  // namespace
}  // namespace rtsim::scenes
