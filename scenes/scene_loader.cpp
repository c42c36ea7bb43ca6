#include "scenes/scene_loader.hpp"

#include <algorithm>
#include <array>
#include <filesystem>

#include "common/input_error.hpp"
#include "common/suggest.hpp"
#include "scenes/bpt_reader.hpp"
#include "scenes/generators/bowling.hpp"
#include "scenes/generators/default_scene.hpp"
#include "scenes/generators/newell_teapot.hpp"
#include "scenes/generators/npp_scene.hpp"
#include "scenes/generators/plb_head.hpp"
#include "scenes/generators/spd_teapot.hpp"
#include "scenes/generators/ullner_cubes.hpp"
#include "scenes/generators/ullner_mosaic.hpp"
#include "scenes/generators/ullner_random.hpp"
#include "scenes/generators/ullner_sheets.hpp"
#include "scenes/nff_reader.hpp"
#include "scenes/scene_text.hpp"

namespace rtsim::scenes {

namespace {

/// How many names an "unknown builtin scene" message suggests.
constexpr std::size_t kMaxSuggestions = 3;

/// The npp scenes listed by name: Gaudet's Fig 6-1 and Figs 6-9..6-11 use pp in this set.
constexpr std::array<int, 3> kListedNppBranching = {2, 4, 8};
constexpr std::array<int, 5> kListedNppSpheres = {4, 8, 12, 16, 20};
/// The ullner-random scenes listed by name: decades around Ullner's n_p = 1000 (seed 000 L654)
/// up to the 10^6 polygons the peripheral scales to (L751), for the "various scene
/// complexities" of Figs 2-20 to 2-22 (L662).
constexpr std::array<std::size_t, 5> kListedUllnerRandomCounts = {100, 1000, 10'000, 100'000,
                                                                  1'000'000};

std::string lower(std::string_view s) {
  std::string out(s);
  for (char& c : out) {
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
  }
  return out;
}

}  // namespace

GeneratorSeeds default_generator_seeds() {
  return {kNppDefaultSeed, kUllnerDefaultSeed, kUllnerRandomDefaultSeed};
}

const std::vector<BuiltinScene>& builtin_scenes() {
  static const std::vector<BuiltinScene> scenes = [] {
    std::vector<BuiltinScene> list;
    list.push_back(
        {"default", "checkerboard floor, mirror, glass and plastic spheres, 2 lights (69 prims)"});
    list.push_back({"ullner-cubes",
                    "Ullner Fig 2-19: 83 randomly oriented cubes as 498 quads in the unit cube"});
    for (std::size_t n : kListedUllnerRandomCounts) {
      list.push_back({std::string(kUllnerRandomPrefix) + std::to_string(n),
                      cat("Ullner's analytic model: N = ", n,
                          " random squares of total area 2 in the unit cube, no lights")});
    }
    list.push_back({std::string(kUllnerSheetsPrefix) + "1000",
                    "Ullner's Fig 2-18 scene: 1000 quads as two sheets through the unit cube "
                    "(a_t = 2, d_r = 1/2), no lights; any ullner-sheets-N"});
    list.push_back({std::string(kUllnerSheetsLitPrefix) + "1000",
                    "the same with one light at the eye: every vision ray hits and casts one "
                    "unoccluded shadow ray (Ullner's doubling for shadows, L743)"});
    list.push_back(
        {"teapot", "the Newell teapot: 32 bicubic Bezier patches (SPD's teapot.bpt), no lights"});
    list.push_back({"spd-teapot",
                    "SPD's teapot scene: the same patches as 992 triangles with vertex normals "
                    "on a checkerboard, 2 lights"});
    list.push_back({"spd-teapot-patches",
                    "SPD's teapot scene with the teapot as its 32 Bezier patches: patches beside "
                    "the checkerboard's 4 polygons, 2 lights"});
    list.push_back({"bowling",
                    "PixelFlow's bowling frame (seed 004 L89-L112): ten pins, a lane and a ball "
                    "as about 10,700 textured triangles, pin/alley/ball shaders, 1 light"});
    for (int n : kListedNppBranching) {
      for (int pp : kListedNppSpheres) {
        const std::string digits = std::to_string(n) + (pp < 10 ? "0" : "") + std::to_string(pp);
        const char* tree = n == 2 ? "binary" : n == 4 ? "quad" : "oct";
        list.push_back({"npp-" + digits,
                        "Gaudet scene " + digits + ": 64 clusters x " + std::to_string(pp) +
                            " spheres (" + std::to_string(64 * pp) + "), " + tree + " shell tree"});
      }
    }
    list.push_back({"plb-head",
                    "sort-first's stand-in for the coherence study's PLB head (seed 004 L570): a "
                    "closed head-like surface of 59,536 triangles at the screen's centre, 1 "
                    "light"});
    list.push_back({std::string(kUllnerMosaicPrefix) + "64",
                    "the scan-line tree's bandwidth scene: one sheet facing the eye in 64 "
                    "columns x 8 rows of quads, 128 visible triangles' segments a line; any "
                    "ullner-mosaic-N"});
    return list;
  }();
  return scenes;
}

std::vector<std::string> builtin_scene_names() {
  std::vector<std::string> names;
  for (const auto& s : builtin_scenes()) names.push_back(s.name);
  return names;
}

Scene make_builtin_scene(std::string_view name, const GeneratorSeeds& seeds) {
  if (name == "default") return make_default_scene();
  if (name == "ullner-cubes") return make_ullner_cubes(seeds.ullner_cubes);
  if (name == "teapot") return make_newell_teapot();
  if (name == "bowling") return make_bowling();
  if (name == "spd-teapot") return make_spd_teapot();
  if (name == "spd-teapot-patches") return make_spd_teapot_patches();
  if (name == "plb-head") return make_plb_head();
  int n = 0;
  int pp = 0;
  if (parse_npp_name(name, n, pp)) return make_npp_scene(n, pp, seeds.npp);
  if (const auto polygons = parse_ullner_random_name(name)) {
    if (*polygons < kUllnerRandomMinPolygons || *polygons > kUllnerRandomMaxPolygons) {
      throw InputError("", 0,
                       cat("builtin scene ", quote_token(name), ": ullner-random-N takes N from ",
                           kUllnerRandomMinPolygons, " to ", kUllnerRandomMaxPolygons));
    }
    return make_ullner_random(*polygons, seeds.ullner_random);
  }
  if (const auto columns = parse_ullner_mosaic_name(name)) {
    if (*columns < kUllnerMosaicMinColumns || *columns > kUllnerMosaicMaxColumns) {
      throw InputError("", 0,
                       cat("builtin scene ", quote_token(name), ": ullner-mosaic-N takes N from ",
                           kUllnerMosaicMinColumns, " to ", kUllnerMosaicMaxColumns));
    }
    return make_ullner_mosaic(*columns);
  }
  bool lit = false;
  if (const auto polygons = parse_ullner_sheets_name(name, &lit)) {
    if (*polygons < kUllnerSheetsMinPolygons || *polygons > kUllnerSheetsMaxPolygons) {
      throw InputError("", 0,
                       cat("builtin scene ", quote_token(name), ": ullner-sheets-N takes N from ",
                           kUllnerSheetsMinPolygons, " to ", kUllnerSheetsMaxPolygons));
    }
    return make_ullner_sheets(*polygons, lit);
  }

  // Suggestions: names that contain what was typed ("ullner"), in listing order, then the
  // closest by edit distance (closest_names, as for parameter names); at most kMaxSuggestions.
  std::vector<std::string_view> candidates;
  std::vector<std::string> near;
  for (const auto& s : builtin_scenes()) {
    candidates.push_back(s.name);
    if (!name.empty() && s.name.find(name) != std::string::npos && near.size() < kMaxSuggestions) {
      near.push_back(s.name);
    }
  }
  for (std::string& s : closest_names(name, candidates, kMaxSuggestions)) {
    if (near.size() < kMaxSuggestions && std::find(near.begin(), near.end(), s) == near.end()) {
      near.push_back(std::move(s));
    }
  }
  std::string msg = cat("unknown builtin scene ", quote_token(name));
  if (!near.empty()) {
    msg += "; did you mean ";
    for (std::size_t i = 0; i < near.size(); ++i) {
      msg += cat(i == 0 ? "" : ", ", kBuiltinPrefix, near[i]);
    }
    msg += "?";
  }
  msg += cat(" (`rtsim list scenes` lists all; npp-NPP takes n in {2,4,8} and pp in 01..99; ",
             kUllnerRandomPrefix, "N takes N in ", kUllnerRandomMinPolygons, "..",
             kUllnerRandomMaxPolygons, ")");
  throw InputError("", 0, msg);
}

Scene load_scene(const std::string& spec, const GeneratorSeeds& seeds) {
  if (spec.rfind(kBuiltinPrefix, 0) == 0) {
    return make_builtin_scene(std::string_view(spec).substr(kBuiltinPrefix.size()), seeds);
  }
  std::error_code ec;
  if (!std::filesystem::exists(spec, ec)) {
    std::string hint;
    for (const auto& s : builtin_scenes()) {
      if (s.name == spec) hint = cat(" (did you mean ", kBuiltinPrefix, spec, "?)");
    }
    throw InputError(spec, 0, cat("cannot open scene file: no such file", hint));
  }
  if (!std::filesystem::is_regular_file(spec, ec)) {
    throw InputError(spec, 0, "cannot open scene file: not a regular file");
  }
  const std::string ext = lower(std::filesystem::path(spec).extension().string());
  if (ext == ".nff") return read_nff(spec);
  if (ext == ".bpt") return read_bpt(spec);
  throw InputError(
      spec, 0,
      cat("unsupported scene file extension ", quote_token(ext.empty() ? "(none)" : ext),
          "; supported: .nff (Neutral File Format), .bpt (Bezier patches), or "
          "builtin:NAME"));
}

}  // namespace rtsim::scenes
