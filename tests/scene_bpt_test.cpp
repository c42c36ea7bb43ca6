// .bpt reader: the shared Newell teapot (32 bicubic patches) and its error rules.
#include <gtest/gtest.h>

#include "scene_test_support.hpp"
#include "scenes/bpt_reader.hpp"
#include "scenes/scene_writer.hpp"

namespace rtsim::scenes {
namespace {

using testing::expect_input_error;
using testing::expect_same_content;
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

TEST(SceneBpt, CommentsAndBlankLinesAreAllowed) {
  const Scene s = parse_bpt("# one flat patch\n\n1\n" + patch_text(), "flat.bpt");
  ASSERT_EQ(s.patches.size(), 1u);
  EXPECT_EQ(s.primitives[0].source_line, 4u);
  EXPECT_EQ(s.patches[0].at(2, 1), (Vec3{1, 2, 0}));
}

TEST(SceneBpt, BadInput) {
  auto parse = [](const std::string& text) { return [text] { parse_bpt(text, "bad.bpt"); }; };
  expect_input_error(parse(""), 0, "empty .bpt file");
  expect_input_error(parse("# only a comment\n"), 0, "empty .bpt file");
  expect_input_error(parse("abc\n"), 1, "expected an integer for the patch count, got 'abc'");
  expect_input_error(parse("1.5\n"), 1, "expected an integer for the patch count");
  expect_input_error(parse("1 2\n"), 1, "expected 1 number (the patch count)");
  expect_input_error(parse("0\n"), 1, "patch count must be 1..1000000 (kMaxBptPatches), got '0'");
  expect_input_error(parse("-4\n"), 1, "patch count must be 1..");
  expect_input_error(parse("2000000\n"), 1, "patch count must be 1..1000000");
  expect_input_error(parse("99999999999999999999999\n"), 1, "far too large");
  // Count checked against the lines left before anything is allocated.
  expect_input_error(parse("999999\n" + patch_text()), 1,
                     "file declares 999999 patches (17 lines each) but has only 17 lines left");
  expect_input_error(parse("1\n" + patch_text(2, 3)), 2,
                     "patch 1 of 1 has degrees '2 3'; only bicubic patches ('3 3') are supported");
  expect_input_error(parse("1\n3\n" + patch_text().substr(4)), 2,
                     "expected the degree line '3 3' of patch 1 of 1, got '3'");
  // A patch with a 17th point: the extra point is read where patch 2's degree line should be.
  expect_input_error(parse("2\n" + patch_text(3, 3, 17) + patch_text()), 19,
                     "expected the degree line '3 3' of patch 2 of 2, got '0 4 0'");
  // Truncated inside a patch (comment lines keep the line budget from catching it first).
  expect_input_error(parse("1\n" + patch_text(3, 3, 15) + "#\n#\n"), 2,
                     "file ends inside patch 1 of 1 after 15 of its 16 control points");
  expect_input_error(parse("2\n" + patch_text() + std::string(17, '\n')), 1,
                     "file declares 2 patches but ends after 1");
  expect_input_error(parse("1\n3 3\n0 0 0\n0 0\n" + patch_text().substr(4 + 6 * 2)), 4,
                     "expected 3 numbers for control point 2 of 16 of patch 1 of 1, got 2");
  expect_input_error(parse("1\n3 3\n0 0 nan\n" + patch_text().substr(4 + 6)), 3,
                     "'nan' for control point 1 of 16 of patch 1 of 1 (value 3) is not a finite");
  expect_input_error(parse("1\n" + patch_text() + "1 2 3\n"), 19,
                     "unexpected content after the last of 1 patches: '1 2 3'");
  expect_input_error(parse("1\n3 3\x01\n"), 2, "non-printable byte 0x01 at column 4");
}

}  // namespace
}  // namespace rtsim::scenes
