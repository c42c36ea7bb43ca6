#pragma once
// Reader for the .bpt Bezier patch layout used by SPD's teapot generator:
//
//   32                  number of patches (1 .. kMaxBptPatches)
//   3 3                 per patch: its degrees in u and v; only bicubic "3 3" is supported
//   x y z               then 16 control points, row by row (P00 P01 ... P33)
//
// The file is read as a stream of tokens, as NFF is (scene_tokens.hpp): SPD writes one point a
// line, but any layout reads the same; '#' comments, "\r" or "\r\n" line ends and a UTF-8
// byte-order mark at the start are allowed. Same error rules as the NFF reader (see
// nff_reader.hpp): one rtsim::InputError naming file, line and what was expected; counts may be
// written "32.0"; the patch count is checked against kMaxBptPatches and the tokens left in the
// file before anything is allocated; content after the last declared patch is an error.
// Primitive::source_line is the line of a patch's first degree.
//
// The format has no camera, lights or materials: has_camera stays false (the renderer frames
// the scene itself), there are no lights, and every patch uses one material, kDefaultBptMaterial.
#include <cstdint>
#include <string>
#include <string_view>

#include "firmware/scene.hpp"

namespace rtsim::scenes {

/// Most patches a .bpt file may declare (the teapot has 32).
inline constexpr std::int64_t kMaxBptPatches = 1'000'000;

/// The one material of a .bpt scene: white, mostly diffuse with a little Phong highlight.
inline const Material kDefaultBptMaterial{Color{1.0}, 0.8, 0.2, 20.0, 0.0, 1.0};

Scene read_bpt(const std::string& path);
Scene parse_bpt(std::string_view text, const std::string& name);

}  // namespace rtsim::scenes
