#pragma once
// The broadcast program of the T&C processors (seed 000 Figs. 3-10 to 3-15, L1104-L1323),
// hand-compiled for the processor of tc_isa.hpp as L1334 describes ("assuming a simple machine
// architecture, hand compiling the programs, and then counting the resulting instructions"):
//
//   vertex transformation   Fig. 3-10: the matrix's 16 literals stored once, used four times
//   colour computation      Fig. 3-11: I = (I_a + I_p max(0, n.p)) R a component, a vertex
//   clipping                Figs. 3-12/3-13: Sutherland-Hodgman, six planes one after another,
//                           vertex lists of indices, crossings noted in a loop bounded by
//                           4, 5, ... 9 vertices, then the intersections broadcast twice
//   perspective division    Fig. 3-14: x, y, z over w, ten times
//   scan-conversion         Fig. 3-15: the leftmost top vertex, the winding, then both edge
//   preprocessing           chains traced top to bottom in one loop of 12, an entry of 11
//                           values a vertex sent to the scan conversion processor
//
// The instruction counts come from the program as built; Fig. 3-16's (272 / 153 / 1904 / 152 /
// 1171, 3652 in all) are set beside them by the validation, not used here.
//
// Where the figures and the text disagree, the program follows the text: Figs. 3-12 and 3-13
// compute an intersection only where an edge enters the visible side, but a convex polygon
// crossing a plane has an entering and a leaving edge, and L1210 broadcasts the intersection
// code twice for the two; the program notes an edge whose ends lie on opposite sides (their
// distances' product is negative). Fig. 3-13 interpolates normals where Fig. 3-12 and the
// Gouraud text (L1011-L1015) interpolate colours: the program interpolates colours.
#include <array>
#include <cstdint>
#include <string_view>
#include <vector>

#include "firmware/math.hpp"
#include "firmware/scanline/tc_isa.hpp"

namespace rtsim::scanline {

/// Fig. 3-16's rows.
enum class TcTask : std::uint8_t { Transform, Colour, Clipping, Division, Preprocessing };
inline constexpr int kTcTasks = 5;
inline constexpr std::array<std::string_view, kTcTasks> kTcTaskNames = {
    "vertex_transformation", "colour_computation", "clipping", "perspective_division",
    "scan_conversion_preprocessing"};

/// What the bus's end broadcasts as literals with the program: the viewing and perspective
/// transformation (a row vector times it, L979-L999: [x y z 1] M, mapping the visible region to
/// -w <= x, y <= w, 0 <= z <= w) and the lights (Fig. 3-11).
struct TcLiterals {
  std::array<std::array<float, 4>, 4> matrix{};  ///< matrix[row][column]
  std::array<float, 3> ambient{};                ///< a_r, a_g, a_b
  std::array<float, 3> point{};                  ///< p_r, p_g, p_b
  std::array<float, 3> direction{};              ///< p_x, p_y, p_z: unit, towards the light
  /// Whether there is a point source: without one the program computes the ambient term only
  /// (a scene skips the work it does not need).
  bool point_light = true;
};

struct BroadcastProgram {
  std::vector<Instruction> code;
  std::array<std::uint32_t, kTcTasks> count{};  ///< instructions broadcast for each task
  std::uint32_t total() const;
};

/// Builds the program for one frame's literals.
BroadcastProgram build_tc_program(const TcLiterals& literals);

/// A polygon as the bus loads it into a processor (L1272: 4 points, 4 normals, a colour: 27
/// words).
struct TcPolygon {
  std::array<Vec3, 4> vertex{};
  std::array<Vec3, 4> normal{};
  Color colour{0.0};
};
void load_polygon(TcProcessor& p, const TcPolygon& polygon);

/// Runs the whole program on every processor, as the bus broadcasts it.
void broadcast(const BroadcastProgram& program, std::vector<TcProcessor>& processors);

/// One entry of an edge chain (Fig. 3-15's `send`s): a vertex, quantized, and the increments of
/// x, z, r, g, b a unit of y down to the next vertex of its chain (0 where the next is not
/// lower: a horizontal edge, or the chain's bottom).
struct EdgeEntry {
  float y = 0.0f, x = 0.0f, dx = 0.0f, z = 0.0f, dz = 0.0f, r = 0.0f, dr = 0.0f, g = 0.0f,
        dg = 0.0f, b = 0.0f, db = 0.0f;
};
inline constexpr int kEdgeEntryWords = 11;

/// What a T&C processor sent its scan conversion processor: the left chain's entries from the
/// top vertex down, then the right chain's (which starts at the top vertex again, so the first
/// entry higher than the one before begins it). A chain ends at a vertex whose next is higher,
/// so a level bottom edge is in both; the loop's 12 passes (Fig. 3-15) may leave the last entry
/// of a 10-vertex polygon's right chain unsent, one level with the entry before it.
struct EdgeChains {
  std::vector<EdgeEntry> left, right;
  bool empty() const { return left.empty() || right.empty(); }
};
EdgeChains edge_chains(const std::vector<float>& sent);

}  // namespace rtsim::scanline
