// NFF read as a token stream, as the reference NFF readers (scanf) read it: the real-world forms
// a line-by-line reader refused (docs/scene-formats.md), one test each, and the forms that stay
// refused because they are ambiguous, each with its file:line.
#include <gtest/gtest.h>

#include "scene_test_support.hpp"
#include "scenes/nff_reader.hpp"

namespace rtsim::scenes {
namespace {

using testing::expect_input_error;
using testing::expect_same_content;
using testing::expect_scene_sound;

/// A valid view block on lines 1..7.
const std::string kView =
    "v\nfrom 0 0 5\nat 0 0 0\nup 0 1 0\nangle 45\nhither 0.1\nresolution 64 64\n";

Scene parse(const std::string& text) {
  Scene s = parse_nff(text, "tokens.nff");
  expect_scene_sound(s);
  return s;
}

auto parsing(const std::string& text) {
  return [text] { parse_nff(text, "bad.nff"); };
}

// --- 1. Cones --------------------------------------------------------------------------------

TEST(SceneNffTokens, ConeOnOneLineOrSplitAnyWay) {
  const Scene ref = parse("c\n0 0 0 1\n0 2 0 0.5\n");
  ASSERT_EQ(ref.cones.size(), 1u);
  for (const std::string text : {"c 0 0 0 1 0 2 0 0.5\n", "c 0 0 0 1\n0 2 0 0.5\n",
                                 "c\n0 0 0 1 0 2 0 0.5\n", "c 0 0\n0 1 0\n2 0\n0.5\n"}) {
    SCOPED_TRACE(text);
    const Scene s = parse(text);
    expect_same_content(ref, s);
    EXPECT_EQ(s.cones.at(0).apex, (Vec3{0, 2, 0}));
    EXPECT_EQ(s.cones.at(0).apex_radius, 0.5);
    EXPECT_EQ(s.primitives.at(0).source_line, 1u);
  }
  // Source line: the line of 'c'.
  EXPECT_EQ(parse("s 0 0 0 1\n\nc 0 0 0 1 0 2 0 0.5\n").primitives.at(1).source_line, 3u);
}

// --- 2. Polygon vertices ---------------------------------------------------------------------

TEST(SceneNffTokens, PolygonVerticesInAnyLayout) {
  const Scene ref = parse("p 3\n0 0 0\n1 0 0\n0 1 0\n");
  for (const std::string text :
       {"p 3 0 0 0 1 0 0 0 1 0\n", "p 3\n0 0 0 1 0 0\n0 1 0\n", "p 3 0 0\n0 1 0\n0 0 1 0\n",
        "p\n3\n0\n0\n0\n1\n0\n0\n0\n1\n0\n"}) {
    SCOPED_TRACE(text);
    const Scene s = parse(text);
    expect_same_content(ref, s);
    EXPECT_EQ(s.polygons.at(0).vertices.at(2), (Vec3{0, 1, 0}));
    EXPECT_EQ(s.primitives.at(0).source_line, 1u);
  }
  // Two polygons on one line each.
  const Scene two = parse("p 3 0 0 0 1 0 0 0 1 0\np 4 0 0 1 1 0 1 1 1 1 0 1 1\n");
  ASSERT_EQ(two.polygons.size(), 2u);
  EXPECT_EQ(two.polygons[1].vertices[3], (Vec3{0, 1, 1}));
  EXPECT_EQ(two.primitives[1].source_line, 2u);
}

TEST(SceneNffTokens, PolygonWithNormalsInAnyLayout) {
  const Scene ref = parse("pp 3\n0 0 0 0 0 1\n1 0 0 0 0 1\n0 1 0 0 0 1\n");
  for (const std::string text : {"pp 3 0 0 0 0 0 1 1 0 0 0 0 1 0 1 0 0 0 1\n",
                                 "pp 3\n0 0 0\n0 0 1\n1 0 0\n0 0 1\n0 1 0\n0 0 1\n",
                                 "pp 3 0 0 0 0\n0 1 1 0 0 0 0 1 0 1\n0 0 0 1\n"}) {
    SCOPED_TRACE(text);
    const Scene s = parse(text);
    expect_same_content(ref, s);
    EXPECT_EQ(s.polygons.at(0).normals.at(1), (Vec3{0, 0, 1}));
  }
}

// --- 3. Comments after content ---------------------------------------------------------------

TEST(SceneNffTokens, CommentAfterContentOnALine) {
  const Scene ref = parse(kView + "l 1 1 1\ns 0 0 0 1\np 3\n0 0 0\n1 0 0\n0 1 0\n");
  const Scene s = parse(
      "v # the camera\nfrom 0 0 5 # eye\nat 0 0 0\t# centre\nup 0 1 0 #no blank after the mark\n"
      "angle 45\nhither 0.1\nresolution 64 64 # pixels\n"
      "l 1 1 1 # caf\xC3\xA9: non-ASCII bytes are fine in a comment\n"
      "s 0 0 0 1 # 2 3 4: numbers in a comment are not read\n"
      "p 3 # a triangle\n0 0 0 # first\n1 0 0 #\n0 1 0 ##\n");
  expect_same_content(ref, s);
  EXPECT_EQ(s.primitives.at(1).source_line, 10u);
}

// --- 4. UTF-8 byte-order mark ----------------------------------------------------------------

TEST(SceneNffTokens, Utf8ByteOrderMarkAtTheStartIsSkipped) {
  const Scene ref = parse("s 0 0 0 1\np 3 0 0 0 1 0 0 0 1 0\n");
  const Scene a = parse("\xEF\xBB\xBFs 0 0 0 1\np 3 0 0 0 1 0 0 0 1 0\n");
  expect_same_content(ref, a);
  EXPECT_EQ(a.primitives.at(1).source_line, 2u);
  const Scene b = parse(
      "\xEF\xBB\xBF# saved by an editor that writes a BOM\ns 0 0 0 1\np 3 0 0 0 1 0 0 0 1 0\n");
  expect_same_content(ref, b);
  EXPECT_EQ(b.primitives.at(1).source_line, 3u);
  // Line numbers count from the BOM's line.
  expect_input_error(parsing("\xEF\xBB\xBFs 0 0 0 1\ns 0 0 0 -1\n"), 2,
                     "sphere radius must be > 0, got '-1'");
}

// --- 5. CR-only line ends --------------------------------------------------------------------

TEST(SceneNffTokens, ClassicMacLineEndsCountAsLines) {
  const std::string lf =
      kView + "l 1 2 3\n# comment\nf 1 0 0 1 0 0 0 1\ns 0 0 0 1\np 3\n0 0 0\n1 0 0\n0 1 0\n";
  std::string cr = lf;
  for (char& c : cr) c = c == '\n' ? '\r' : c;
  const Scene a = parse(lf);
  const Scene b = parse(cr);
  expect_same_content(a, b);
  EXPECT_EQ(b.camera.width, 64);
  EXPECT_EQ(b.primitives.at(0).source_line, 11u);
  EXPECT_EQ(b.primitives.at(1).source_line, 12u);
  // "\r\n" stays one line end, next to "\r" and "\n" in the same file.
  const Scene mixed = parse("s 0 0 0 1\r\ns 0 0 0 2\rs 0 0 0 3\n\r\ns 0 0 0 4\r");
  ASSERT_EQ(mixed.primitives.size(), 4u);
  EXPECT_EQ(mixed.primitives[1].source_line, 2u);
  EXPECT_EQ(mixed.primitives[2].source_line, 3u);
  EXPECT_EQ(mixed.primitives[3].source_line, 5u);
  // Messages name the right line of a CR-only file.
  expect_input_error(parsing("s 0 0 0 1\rs 0 0 0 1\r# x\rs 0 0 0 -1\r"), 4,
                     "sphere radius must be > 0, got '-1'");
  expect_input_error(parsing("# one\r# two\r# three\r"), 3, "no primitives in scene file");
  expect_input_error(parsing("s 0 0 0 1\r\x01\r"), 2, "non-printable byte 0x01 at column 1");
}

// --- 6. Light with an intensity --------------------------------------------------------------

TEST(SceneNffTokens, LightWithFourNumbersIsPositionAndIntensity) {
  const Scene s = parse("l 1 2 3 0.5\nl 4 5 6\nl 7 8 9 0.1 0.2 0.3\nl 0 0 0\n2\ns 0 0 0 1\n");
  ASSERT_EQ(s.lights.size(), 4u);
  EXPECT_EQ(s.lights[0].position, (Vec3{1, 2, 3}));
  EXPECT_EQ(s.lights[0].color, (Color{0.5, 0.5, 0.5}));
  EXPECT_EQ(s.lights[1].color, (Color{1.0}));  // 3 numbers: white
  EXPECT_EQ(s.lights[2].color, (Color{0.1, 0.2, 0.3}));
  EXPECT_EQ(s.lights[3].color, (Color{2.0}));  // the intensity on the next line
  expect_input_error(parsing("l 1 2 3 -1\ns 0 0 0 1\n"), 1,
                     "light intensity must be >= 0, got '-1'");
}

// --- 7. Integers written as decimals ---------------------------------------------------------

TEST(SceneNffTokens, IntegralDecimalsAreIntegers) {
  const Scene p = parse(
      "p 3.0\n0 0 0\n1 0 0\n0 1 0\n"
      "pp +4.\n0 0 0 0 0 1\n1 0 0 0 0 1\n1 1 0 0 0 1\n0 1 0 0 0 1\n"
      "p 30e-1 0 0 0 1 0 0 0 1 0\n");
  ASSERT_EQ(p.polygons.size(), 3u);
  EXPECT_EQ(p.polygons[0].vertices.size(), 3u);
  EXPECT_EQ(p.polygons[1].vertices.size(), 4u);
  EXPECT_EQ(p.polygons[2].vertices.size(), 3u);
  std::string view = kView;
  view.replace(view.find("resolution 64 64"), 16, "resolution 8.0 8");
  const Scene v = parse(view + "s 0 0 0 1\n");
  EXPECT_EQ(v.camera.width, 8);
  EXPECT_EQ(v.camera.height, 8);
}

// --- What stays refused ----------------------------------------------------------------------

TEST(SceneNffTokens, LightWithFiveNumbersIsAmbiguous) {
  expect_input_error(parsing("s 0 0 0 1\nl 1 2 3 4 5\n"), 2,
                     "light with 5 numbers is ambiguous; expected 3 (x y z: white), 4 (x y z "
                     "intensity) or 6 (x y z r g b)");
  expect_input_error(parsing("s 0 0 0 1\nl 1 2 3\n4 5\nf 1 1 1 1 0 0 0 1\n"), 2,
                     "light with 5 numbers is ambiguous");
}

TEST(SceneNffTokens, FractionalOrHugeCountsAreRefused) {
  expect_input_error(parsing("p 3.5\n0 0 0\n1 0 0\n0 1 0\n"), 1,
                     "expected an integer for polygon vertex count, got '3.5'");
  expect_input_error(parsing("s 0 0 0 1\npp 1e400\n"), 2,
                     "number '1e400' for polygon vertex count is outside the range of a double");
  expect_input_error(parsing("p 1e-3\n"), 1, "expected an integer for polygon vertex count");
  std::string view = kView;
  view.replace(view.find("resolution 64 64"), 16, "resolution 8 7.5");
  expect_input_error(parsing(view + "s 0 0 0 1\n"), 7,
                     "expected an integer for resolution height, got '7.5'");
}

TEST(SceneNffTokens, MissingNumbersBeforeAKeyword) {
  // Reported at the line of the last value the entity took; the keyword that came instead and,
  // when elsewhere, the entity's own line are named.
  expect_input_error(parsing("s 0 0 0 1\nc 0 0 0 1 0 0\ns 0 0 0 1\n"), 2,
                     "expected 4 numbers for cone apex (x y z r), got 2 before keyword 's' at "
                     "line 3");
  expect_input_error(parsing("p 3\n0 0 0\n1 0 0\n0 1\ns 0 0 0 1 0 0 0 1\n"), 4,
                     "expected 3 numbers for polygon vertex 3 of 3 (x y z), got 2 before keyword "
                     "'s' at line 5 ('p' at line 1)");
  expect_input_error(parsing("s 1 2 3 p 3 0 0 0 1 0 0 0 1 0\n"), 1,
                     "expected 4 numbers for sphere centre and radius (x y z r), got 3 before "
                     "keyword 'p'");
  expect_input_error(parsing("v\nfrom 0 0 5\nat 0 0\nup 0 1 0\n"), 3,
                     "expected 3 numbers for view 'at' point, got 2 before keyword 'up' at line 4");
  expect_input_error(parsing("s 0 0 0 1\np\npp 3\n"), 2,
                     "expected the vertex count after 'p', got keyword 'pp' at line 3");
  expect_input_error(parsing("s 0 0 0 1\nf 1 1 1 0.5 0.5\n"), 2,
                     "expected 8 numbers for material (r g b Kd Ks Shine T index_of_refraction), "
                     "got 5 before the end of the file");
}

TEST(SceneNffTokens, TrailingJunkIsRefused) {
  expect_input_error(parsing("s 0 0 0 1 junk\n"), 1,
                     "unknown keyword 'junk'; expected one of v, b, l, f, s, c, p, pp, # (after "
                     "'s' at line 1, which took 4 values)");
  expect_input_error(parsing("s 0 0 0 1 2\n"), 1,
                     "unexpected '2' after 's' at line 1, which took 4 values; expected a keyword");
  // A vertex line with a fourth number: the numbers shift, and one is left after the polygon.
  expect_input_error(parsing("p 3\n0 0 0 7\n1 0 0\n0 1 0\n"), 4,
                     "unexpected '0' after 'p' at line 1, which took 10 values");
  // '#' inside a token is part of it, not a comment.
  expect_input_error(parsing("s 0 0 0 1#c\n"), 1,
                     "expected a number for sphere centre and radius (x y z r) (value 4), got "
                     "'1#c'");
  expect_input_error(parsing("v 1\n"), 1, "unexpected '1' in the view block of line 1");
}

TEST(SceneNffTokens, ByteOrderMarksElsewhereAreRefused) {
  expect_input_error(parsing("s 0 0 0 1\n\xEF\xBB\xBFs 0 0 0 1\n"), 2,
                     "non-ASCII byte 0xEF at column 1 outside a comment");
  expect_input_error(parsing("\xFF\xFEs 0 0 0 1\n"), 1,
                     "non-ASCII byte 0xFF at column 1 outside a comment; scene files are plain "
                     "ASCII text (this file starts with a UTF-16 byte-order mark");
}

TEST(SceneNffTokens, CountsAreCheckedAgainstTheValuesLeft) {
  // Comments hold no values: the 4-vertex polygon has 6 numbers left, not 4 lines.
  expect_input_error(parsing("p 4\n0 0 0\n1 0 0 # 1 1 0\n# 0 1 0\n"), 1,
                     "polygon declares 4 vertices (12 numbers) but the file has only 6 values "
                     "left");
  expect_input_error(parsing("pp 100000 0 0 0\n"), 1,
                     "polygon declares 100000 vertices (600000 numbers) but the file has only "
                     "3 values left");
}

}  // namespace
}  // namespace rtsim::scenes
