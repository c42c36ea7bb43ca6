// Bad scene input: every rule of nff_reader.hpp gives one InputError with the expected
// file:line and a message saying what was expected; and a deterministic fuzz over the shared
// scene files shows parsing either succeeds with a sound scene or throws InputError, nothing
// else (bounded time by construction: a fixed number of mutations of fixed-size files).
#include <gtest/gtest.h>

#include <fstream>

#include "common/splitmix64.hpp"
#include "scene_test_support.hpp"
#include "scenes/bpt_reader.hpp"
#include "scenes/nff_reader.hpp"
#include "scenes/scene_loader.hpp"
#include "scenes/scene_text.hpp"

namespace rtsim::scenes {
namespace {

using testing::expect_input_error;
using testing::expect_scene_sound;
using testing::shared_scene;

/// A valid view block on lines 1..7.
const std::string kView =
    "v\nfrom 0 0 5\nat 0 0 0\nup 0 1 0\nangle 45\nhither 0.1\nresolution 64 64\n";

struct BadCase {
  std::string text;
  std::size_t line;
  std::string fragment;
};

std::string view_with(const std::string& key, const std::string& line) {
  std::string v = kView;
  const std::size_t at = v.find("\n" + key + " ") + 1;
  const std::size_t end = v.find('\n', at);
  return v.replace(at, end - at, line) + "s 0 0 0 1\n";
}

const std::vector<BadCase>& nff_cases() {
  static const std::vector<BadCase> cases = {
      // Wrong counts.
      {"s 1 2 3\n", 1, "expected 4 numbers for sphere centre and radius (x y z r), got 3"},
      {"s 0 0 0 1\ns\n", 2, "expected 4 numbers for sphere centre and radius (x y z r), got 0"},
      {"b 0 0\ns 0 0 0 1\n", 1, "expected 3 numbers for background colour (r g b), got 2"},
      {"l 1 2\ns 0 0 0 1\n", 1,
       "expected 3 numbers for light position (x y z, then optionally an intensity i or a colour "
       "r g b), got 2 before keyword 's' at line 2"},
      {"l 1 2 3 4 5\ns 0 0 0 1\n", 1, "light with 5 numbers is ambiguous"},
      {"f 1 1 1 0.5 0.5 3 0\ns 0 0 0 1\n", 1,
       "expected 8 numbers for material (r g b Kd Ks Shine T index_of_refraction), got 7"},
      // Unknown keywords.
      {"s 0 0 0 1\nsx 1 2 3 4\n", 2,
       "unknown keyword 'sx'; expected one of v, b, l, f, s, c, p, pp, #"},
      {"S 0 0 0 1\n", 1, "unknown keyword 'S'"},
      {"1 2 3\n", 1, "unknown keyword '1'"},
      {"s 0 0 0 1\nangle 45\n", 2, "'angle' outside a view block; it must follow a 'v'"},
      // Trailing garbage: what an entity does not take must be a keyword.
      {"s 0 0 0 1 junk\n", 1,
       "unknown keyword 'junk'; expected one of v, b, l, f, s, c, p, pp, # (after 's' at line 1, "
       "which took 4 values)"},
      {"s 0 0 0 1 2\n", 1, "unexpected '2' after 's' at line 1, which took 4 values"},
      {"s 0 0 0 1x\n", 1,
       "expected a number for sphere centre and radius (x y z r) (value 4), "
       "got '1x'"},
      {"s 0 0 0 1#c\n", 1, "got '1#c'"},  // '#' inside a token is no comment
      {"s 0x10 0 0 1\n", 1, "got '0x10'"},
      {"s 1,5 0 0 1\n", 1, "got '1,5'"},
      // A fourth number on a vertex line shifts the vertices; the last number is left over.
      {"p 3\n0 0 0 7\n1 0 0\n0 1 0\n", 4,
       "unexpected '0' after 'p' at line 1, which took 10 values"},
      {"v 1\n", 1,
       "unexpected '1' in the view block of line 1; expected one of 'from', 'at', 'up', 'angle', "
       "'hither', 'resolution'"},
      {"c 0 0 0 1\n", 1,
       "expected 4 numbers for cone apex (x y z r), got 0 before the end of the file"},
      {"p 3 3\n", 1, "polygon declares 3 vertices (9 numbers) but the file has only 1 value left"},
      {"p\n", 1, "expected the vertex count after 'p', got the end of the file"},
      // Non-finite and overflowing numbers.
      {"s 0 nan 0 1\n", 1,
       "'nan' for sphere centre and radius (x y z r) (value 2) is not a finite"},
      {"s inf 0 0 1\n", 1,
       "'inf' for sphere centre and radius (x y z r) (value 1) is not a finite"},
      {"s 0 0 -infinity 1\n", 1, "is not a finite number"},
      {"s 1e400 0 0 1\n", 1,
       "number '1e400' for sphere centre and radius (x y z r) (value 1) is "
       "outside the range of a double"},
      {"s 1e-400 0 0 1\n", 1, "outside the range of a double"},
      {"s 1e16 0 0 1\n", 1, "exceeds the magnitude limit of 1e15 (kMaxSceneNumberMagnitude)"},
      {"p 99999999999999999999999\n", 1,
       "integer '99999999999999999999999' for polygon vertex "
       "count is far too large"},
      // Polygon counts.
      {"p 2\n0 0 0\n1 0 0\n", 1, "polygon needs at least 3 vertices, got '2'"},
      {"p -5\n", 1, "polygon needs at least 3 vertices, got '-5'"},
      {"p 4.5\n", 1, "expected an integer for polygon vertex count, got '4.5'"},
      {"p 2000000\n0 0 0\n", 1,
       "polygon vertex count 2000000 exceeds the limit of 100000 (kMaxPolygonVertices: larger "
       "polygons can take minutes to triangulate)"},
      {"p 100000\n0 0 0\n1 0 0\n0 1 0\n", 1,
       "polygon declares 100000 vertices (300000 numbers) but the file has only 9 values left"},
      // Truncation.
      // (Counted in tokens: comment lines hold none.)
      {"p 4\n0 0 0\n1 0 0\n", 1,
       "polygon declares 4 vertices (12 numbers) but the file has only 6 values left"},
      {"p 4\n0 0 0\n1 0 0\n#\n#\n", 1,
       "polygon declares 4 vertices (12 numbers) but the file has only 6 values left"},
      {"pp 3\n0 0 0 0 0 1\n1 0 0 0 0 1\n0 1 0\n", 1,
       "polygon declares 3 vertices (18 numbers) but the file has only 15 values left"},
      // Missing numbers: at the line of the last value the entity took.
      {"p 4\n0 0 0\n1 0 0\n1 1 0\ns 0 0 0 1\n", 4,
       "expected 3 numbers for polygon vertex 4 of 4 (x y z), got 0 before keyword 's' at line 5 "
       "('p' at line 1)"},
      {"pp 3\n0 0 0 0 0 1\n1 0 0 0 0 1\n0 1 0\ns 0 0 0 1\n", 4,
       "expected 6 numbers for polygon vertex 3 of 3 (x y z nx ny nz), got 3 before keyword 's' at "
       "line 5 ('pp' at line 1)"},
      {"c\n0 0 0 1\n", 2,
       "expected 4 numbers for cone apex (x y z r), got 0 before the end of the file ('c' at line "
       "1)"},
      {"c\n0 0 0 1\ns 0 0 0 1\n", 2,
       "expected 4 numbers for cone apex (x y z r), got 0 before keyword 's' at line 3 ('c' at "
       "line 1)"},
      {"c\n0 0 0\n0 0 1 1\n", 3,
       "expected 4 numbers for cone apex (x y z r), got 3 before the end of the file ('c' at line "
       "1)"},
      // Binary garbage.
      {"s 0 0 0 1\n\x01\x02garbage\n", 2, "non-printable byte 0x01 at column 1"},
      {std::string("s 0 0\0 0 1\n", 11), 1, "non-printable byte 0x00 at column 6"},
      {"s 0 0 0 1\np 1000000\n\x7f", 3, "non-printable byte 0x7F"},
      {"s 0 0 0 1 \xC3\xA9\n", 1, "non-ASCII byte 0xC3 at column 11 outside a comment"},
      {"\xff\xfe s\n", 1, "non-ASCII byte 0xFF at column 1"},
      // Sphere radius.
      {"s 0 0 0 -1\n", 1, "sphere radius must be > 0, got '-1'"},
      {"s 0 0 0 0\n", 1, "sphere radius must be > 0, got '0'"},
      // Materials and colours.
      {"f 1 1 1 -0.5 0.5 3 0 1\ns 0 0 0 1\n", 1, "material Kd must be >= 0, got '-0.5'"},
      {"f 1 1 1 0.5 0.5 -3 0 1\ns 0 0 0 1\n", 1, "material Shine must be >= 0, got '-3'"},
      {"f 1 1 1 0.5 0.5 3 0.5 0\ns 0 0 0 1\n", 1,
       "material index_of_refraction must be > 0 for a transmissive material (T > 0), got '0'"},
      {"f 1 -1 1 0.5 0.5 3 0 1\ns 0 0 0 1\n", 1,
       "material colour components must be >= 0, got '-1'"},
      {"l 1 2 3 1 -1 1\ns 0 0 0 1\n", 1, "light colour components must be >= 0, got '-1'"},
      {"b 0 0 0\nb 1 1 1\ns 0 0 0 1\n", 2, "second background 'b' (the first is at line 1)"},
      // View block.
      {view_with("resolution", "resolution 0 64"), 7,
       "resolution width must be 1..16384 (kMaxNffResolution), got '0'"},
      {view_with("resolution", "resolution 64 -2"), 7, "resolution height must be 1..16384"},
      {view_with("resolution", "resolution 100000 64"), 7, "got '100000'"},
      {view_with("resolution", "resolution 64"), 7,
       "expected 2 integers for view 'resolution' (width height), got 1"},
      {view_with("resolution", "resolution 64.5 64"), 7,
       "expected an integer for resolution width, got '64.5'"},
      {view_with("up", "up 0 0 0"), 4, "view 'up' vector must not be zero"},
      {view_with("up", "up 0 0 -3"), 4, "view 'up' vector is parallel to the view direction"},
      {view_with("at", "at 0 0 5"), 3, "view 'at' point equals the 'from' point"},
      {view_with("angle", "angle 0"), 5, "view 'angle' must be between 0 and 180 degrees"},
      {view_with("angle", "angle 180"), 5, "view 'angle' must be between 0 and 180 degrees"},
      {view_with("hither", "hither -1"), 6, "view 'hither' must be >= 0, got '-1'"},
      {view_with("from", "from 0 0"), 2, "expected 3 numbers for view 'from' point, got 2"},
      {"v\nfrom 0 0 5\nat 0 0 0\nup 0 1 0\nangle 45\nresolution 64 64\ns 0 0 0 1\n", 1,
       "view block is missing 'hither'; expected from, at, up, angle, hither and resolution"},
      {"v\ns 0 0 0 1\n", 1,
       "view block is missing 'from', 'at', 'up', 'angle', 'hither', 'resolution'"},
      {"v\nfrom 0 0 5\nfrom 0 0 6\n", 3, "duplicate 'from' in the view block (first at line 2)"},
      {kView + kView + "s 0 0 0 1\n", 8, "second view block 'v' (the first is at line 1)"},
      // Nothing to render.
      {"", 0, "no primitives in scene file"},  // no line to name
      {"# just a comment\n\n", 2, "no primitives in scene file"},
      {kView + "l 1 1 1\n", 8, "no primitives"},
  };
  return cases;
}

TEST(SceneBadInput, EveryNffRuleGivesFileLineAndMessage) {
  for (const BadCase& c : nff_cases()) {
    SCOPED_TRACE(c.text.substr(0, 60));
    const std::string what =
        expect_input_error([&] { parse_nff(c.text, "bad.nff"); }, c.line, c.fragment);
    // what() is "file:line: message", or "file: message" when there is no line.
    const std::string prefix =
        c.line > 0 ? "bad.nff:" + std::to_string(c.line) + ": " : "bad.nff: ";
    EXPECT_EQ(what.rfind(prefix, 0), 0u) << what;
  }
}

TEST(SceneBadInput, ValidVariantsOfTheRulesStillParse) {
  // The edges of each rule, on the accepted side.
  EXPECT_NO_THROW(parse_nff("s +1 -0 1e-300 1E+2\n", "ok.nff"));
  EXPECT_NO_THROW(parse_nff("s 1e15 0 0 1\n", "ok.nff"));
  EXPECT_NO_THROW(parse_nff("s 0 0 0 1 # a comment after data\n", "ok.nff"));
  EXPECT_NO_THROW(parse_nff("p 3\n0 0 0\n0 0 0\n0 0 0\n", "ok.nff"));      // degenerate: kept
  EXPECT_NO_THROW(parse_nff("c\n0 0 0 1\n0 0 0 1\n", "ok.nff"));           // coincident ends: kept
  EXPECT_NO_THROW(parse_nff("f 1 1 1 0 0 0 0 0\ns 0 0 0 1\n", "ok.nff"));  // ior 0, opaque
  EXPECT_NO_THROW(parse_nff(view_with("resolution", "resolution 16384 1"), "ok.nff"));
  EXPECT_NO_THROW(parse_nff(view_with("angle", "angle 179.9"), "ok.nff"));
  EXPECT_NO_THROW(parse_nff(view_with("up", "up 0 1e-300 0"), "ok.nff"));  // tiny but not zero
}

TEST(SceneBadInput, FilesAndLoader) {
  const std::string data = RTSIM_TEST_DATA_DIR;
  expect_input_error(
      [&] { load_scene(data + "/bad-truncated-polygon.nff"); }, 7,
      "polygon declares 4 vertices (12 numbers) but the file has only 6 values left");
  expect_input_error([&] { load_scene(data + "/bad-binary.nff"); }, 3, "non-printable byte");
  expect_input_error([&] { load_scene(data + "/bad-degree.bpt"); }, 2,
                     "only bicubic patches ('3 3') are supported");
  const std::string what =
      expect_input_error([&] { load_scene(data + "/no-such-file.nff"); }, 0, "cannot open");
  EXPECT_NE(what.find("no-such-file.nff"), std::string::npos);
  expect_input_error([&] { load_scene(data); }, 0, "cannot open scene file: not a regular file");
  expect_input_error([&] { load_scene("default"); }, 0,
                     "cannot open scene file: no such file (did you mean builtin:default?)");
  const std::string obj = ::testing::TempDir() + "/rtsim_scene.obj";
  std::ofstream(obj) << "v 0 0 0\n";
  expect_input_error([&] { load_scene(obj); }, 0,
                     "unsupported scene file extension '.obj'; supported: .nff (Neutral File "
                     "Format), .bpt (Bezier patches), or builtin:NAME");
  const std::string none = ::testing::TempDir() + "/rtsim_scene_no_extension";
  std::ofstream(none) << "s 0 0 0 1\n";
  expect_input_error([&] { load_scene(none); }, 0, "extension '(none)'");
  // Extension matched case-insensitively.
  const std::string upper = ::testing::TempDir() + "/rtsim_scene_upper.NFF";
  std::ofstream(upper) << "s 0 0 0 1\n";
  EXPECT_EQ(load_scene(upper).spheres.size(), 1u);
}

// --- Fuzz -------------------------------------------------------------------------------------

/// Parses mutated text; returns true if it parsed. Anything but success or InputError fails.
bool parse_mutant(const std::string& text, bool bpt) {
  try {
    const Scene s = bpt ? parse_bpt(text, "fuzz.bpt") : parse_nff(text, "fuzz.nff");
    expect_scene_sound(s);
    return true;
  } catch (const InputError& e) {
    EXPECT_FALSE(e.message().empty());
    return false;
  } catch (const std::exception& e) {
    ADD_FAILURE() << "non-InputError exception: " << e.what();
    return false;
  }
}

std::string read_all(const std::string& path) { return read_scene_file(path); }

TEST(SceneBadInput, FuzzMutationsOnlyEverThrowInputError) {
  // Replacement tokens aimed at the rules: huge and negative counts, non-numbers, non-finite.
  const std::vector<std::string> kEvil = {"999999999",
                                          "2147483648",
                                          "-1",
                                          "0",
                                          "nan",
                                          "-inf",
                                          "1e999",
                                          "1e-999",
                                          "0x1p3",
                                          "1e16",
                                          "3.5",
                                          "",
                                          "p",
                                          "pp",
                                          "v",
                                          "c",
                                          "18446744073709551616",
                                          "+",
                                          "-",
                                          ".",
                                          "e5",
                                          "#",
                                          "\x01",
                                          "\xC3\xA9",
                                          "1 2 3 4 5 6 7 8 9"};
  const std::vector<std::pair<std::string, bool>> files = {
      {"balls-s1.nff", false}, {"balls-s2.nff", false},  {"balls-s3.nff", false},
      {"tetra-s3.nff", false}, {"teapot-s2.nff", false}, {"teapot.bpt", true}};
  SplitMix64 rng(20240601);
  std::size_t runs = 0, parsed = 0;
  for (const auto& [file, bpt] : files) {
    const std::string original = read_all(shared_scene(file));
    ASSERT_TRUE(parse_mutant(original, bpt)) << file;
    // Mutations per file: fewer for the biggest file so the whole test stays ~ a second.
    const std::size_t budget = original.size() > 20000 ? 600 : 1500;
    // 1. Truncate at every Nth byte (about 300 cuts per file, including inside numbers).
    const std::size_t step = original.size() / 300 + 1;
    for (std::size_t cut = 0; cut < original.size(); cut += step) {
      parsed += parse_mutant(original.substr(0, cut), bpt);
      ++runs;
    }
    for (std::size_t i = 0; i < budget; ++i) {
      std::string t = original;
      switch (i % 5) {
        case 0: {  // flip one byte to any value
          t[rng.below(t.size())] = static_cast<char>(rng.below(256));
          break;
        }
        case 1: {  // insert random printable garbage
          std::string g;
          for (std::uint64_t k = rng.below(12) + 1; k > 0; --k) {
            g += static_cast<char>(' ' + rng.below(95));
          }
          t.insert(rng.below(t.size() + 1), g);
          break;
        }
        case 2: {  // replace one whitespace-separated token with an evil one
          std::size_t at = rng.below(t.size());
          while (at > 0 && t[at - 1] != ' ' && t[at - 1] != '\n') --at;
          std::size_t end = at;
          while (end < t.size() && t[end] != ' ' && t[end] != '\n') ++end;
          t.replace(at, end - at, kEvil[rng.below(kEvil.size())]);
          break;
        }
        case 3: {  // delete or duplicate a line
          std::size_t at = rng.below(t.size());
          while (at > 0 && t[at - 1] != '\n') --at;
          std::size_t end = t.find('\n', at);
          end = (end == std::string::npos) ? t.size() : end + 1;
          const std::string line = t.substr(at, end - at);
          if (rng.below(2) == 0) {
            t.erase(at, end - at);
          } else {
            t.insert(at, line);
          }
          break;
        }
        default: {  // splice: move a random chunk to a random place
          const std::size_t a = rng.below(t.size());
          const std::size_t len = rng.below(std::min<std::size_t>(200, t.size() - a)) + 1;
          const std::string chunk = t.substr(a, len);
          t.erase(a, len);
          t.insert(rng.below(t.size() + 1), chunk);
          break;
        }
      }
      parsed += parse_mutant(t, bpt);
      ++runs;
    }
  }
  std::cout << "fuzz: " << runs << " mutants, " << parsed << " parsed, " << runs - parsed
            << " rejected with InputError\n";
  EXPECT_GT(runs, 8000u);
  EXPECT_GT(parsed, 0u);            // some mutations are harmless (e.g. a digit changed)
  EXPECT_GT(runs - parsed, 1000u);  // and many are caught
}

}  // namespace
}  // namespace rtsim::scenes
