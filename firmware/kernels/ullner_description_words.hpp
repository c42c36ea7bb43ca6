#pragma once
// One polygon as the ray-tracing pipeline's processors hold it and pass it down the chain at
// load time: "five vector and five scalar values, as they did in the ray tracing peripheral ...
// an additional value that serves to identify the polygon" (seed 000 L717): 21 words.
//   words  0-19  the twenty parameters (QuadParam order), IEEE singles as in the peripheral
//                (L538-L544, L582);
//   word   20    the identity in bits 0-27 and, in bits 28-29 (u) and 30-31 (v), how the host
//                stored each coordinate's family (the initial validity bits that select a branch,
//                L530):
//                  0  quadratic, the real root is -B - sqrt(B^2 - C)
//                  1  quadratic, the real root is -B + sqrt(B^2 - C)
//                  2  parallel form, -C / B (L380 / L408)
//                  3  deflated: the parallel form with B = 1 (a = 0, a0 = 1, not stored); its a.x
//                     and a.y words carry the other family's pole thresholds (that family is the
//                     pencil of a triangle's collapsed vertex: the only family with a pole).
// The peripheral's line (ullner_quad_words.hpp) spends five words more on the same polygon: the
// four thresholds and a flag word. This layout holds exactly what that line holds for every
// polygon the host prepares (only a pencil has thresholds, ullner_quad.cpp), so a processor
// decoding its description computes what the peripheral and the twin compute, bit for bit
// (tests/ullner_quad_test.cpp).
#include <cstdint>
#include <span>

#include "firmware/kernels/ullner_quad.hpp"

namespace rtsim::kernels {

inline constexpr std::size_t kUllnerDescriptionWords = kUllnerParamCount + 1;
/// Index of the identity-and-families word, and its fields.
inline constexpr std::size_t kUllnerDescriptionIdWord = kUllnerParamCount;
inline constexpr unsigned kUllnerIdentityBits = 28;
inline constexpr std::uint32_t kUllnerMaxIdentity = (1u << kUllnerIdentityBits) - 1;

/// A description decoded: what a processor computes with, and the identity it writes.
struct UllnerDescribedPolygon {
  UllnerQuadParams<double> params;
  std::uint32_t identity = 0;
};

/// The description the host presents for `p` (values rounded to the nearest single) with
/// identity `identity` (<= kUllnerMaxIdentity). `p` must be as the host prepares polygons:
/// pole thresholds only on a parallel family whose partner is deflated.
void describe(const UllnerQuadParams<double>& p, std::uint32_t identity,
              std::span<std::uint32_t, kUllnerDescriptionWords> out);
/// What a description's words say, widened to double (exactly). Any words decode: a corrupted
/// description is a different polygon, not an error. The family fields (host bookkeeping) are
/// left Quadratic.
UllnerDescribedPolygon read_description(
    std::span<const std::uint32_t, kUllnerDescriptionWords> words);

}  // namespace rtsim::kernels
