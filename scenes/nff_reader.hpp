#pragma once
// Reader for Eric Haines' Neutral File Format (NFF), the format of the Standard Procedural
// Databases (SPD). The file is a stream of whitespace-separated tokens, read the way the
// reference NFF readers read it with scanf: each keyword takes exactly the numbers it needs,
// wherever the line ends fall (docs/scene-formats.md has the full rules and the refused forms).
//
//   v                       view block; the six keys below follow, in any order
//   from x y z              eye
//   at x y z                look-at point
//   up x y z                up direction
//   angle deg               full field of view (0 < deg < 180)
//   hither d                near distance (d >= 0)
//   resolution w h          image size in pixels (1 .. kMaxNffResolution each)
//   b r g b                 background colour
//   l x y z [i | r g b]     point light: white, grey of intensity i, or colour r g b (the
//                           optional numbers are those before the next keyword; 5 in all is
//                           ambiguous and refused)
//   f r g b Kd Ks Shine T ior   material for the primitives that follow
//   s x y z r               sphere (r > 0)
//   c bx by bz br ax ay az ar   cone/cylinder: base point and radius, apex point and radius.
//                           A negative radius (NFF: seen from inside) is kept as read;
//                           geometry uses |r|.
//   p n  x y z ...          polygon: n vertices (3 <= n <= kMaxPolygonVertices)
//   pp n x y z nx ny nz ... polygon with a normal after each vertex
//   # ...                   comment: a '#' that starts a token, up to the end of its line
//
// Rules (each violation is one rtsim::InputError naming file, line and what was expected):
// - tokens and lines as in scene_tokens.hpp: "\n", "\r\n" and a lone "\r" end a line; a UTF-8
//   byte-order mark at the start is skipped; binary bytes are refused.
// - numbers are parsed with std::from_chars (locale-independent); NaN, infinity, values outside
//   the double range and trailing characters are errors. Counts and the resolution are integers,
//   also when written as a decimal with an integral value ("3.0"); "3.5" is an error.
// - a keyword where a number is expected is an error naming both; so is a number where a keyword
//   is expected (an entity given too many numbers).
// - colours, Kd, Ks, Shine, T and a light's intensity must be >= 0; ior must be > 0 when T > 0
//   (SPD writes ior 0 for opaque materials, which is kept as read).
// - a sphere radius must be > 0 (NFF has no inside-out spheres; a zero sphere is a typo).
// - the camera must be usable: up not zero and not parallel to at - from, from != at.
// - vertex counts are checked against kMaxPolygonVertices and against the tokens left in the
//   file before anything is allocated.
// - a file with no primitive is an error (it is almost certainly not the intended file).
// - at most one 'v' and one 'b' per file.
// Degenerate but well-formed geometry (zero-area polygons, repeated vertices, coincident cone
// ends, zero normals) is kept: conversion for a machine repairs or rejects it with a count.
//
// Primitive::source_line is the line of the primitive's keyword.
//
// Materials: each distinct `f` used by a primitive becomes one Scene::materials entry (exact
// duplicates share one entry), in order of first use. Primitives before any `f` get
// kDefaultNffMaterial.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "firmware/scene.hpp"

namespace rtsim::scenes {

/// Most vertices one `p`/`pp` polygon may declare. Far above any real polygon (SPD's largest
/// are a few hundred); a bound so an absurd count fails before allocation, and so triangulation
/// ends in seconds: the hardest shapes measured (a comb, a double spiral) take about 9 s at
/// 100,000 vertices (docs/bad-input.md); ear clipping is quadratic at worst.
inline constexpr std::int64_t kMaxPolygonVertices = 100'000;

/// Largest image width or height a `resolution` line may ask for.
inline constexpr std::int64_t kMaxNffResolution = 16384;

/// Material of primitives that come before any `f`: white, fully diffuse, no specular, opaque.
inline const Material kDefaultNffMaterial{Color{1.0}, 1.0, 0.0, 0.0, 0.0, 1.0};

/// Reads an NFF file (see read_scene_file for the file checks). Scene::name = path.
Scene read_nff(const std::string& path);

/// Parses NFF text; `name` is used as the file name in errors and as Scene::name.
Scene parse_nff(std::string_view text, const std::string& name);

}  // namespace rtsim::scenes
