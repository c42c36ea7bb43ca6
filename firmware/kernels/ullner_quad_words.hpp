#pragma once
// One polygon as the peripheral's memories hold it: 32-bit words, one line per polygon.
//   words  0-19  the twenty parameters, one per parameter memory (seed 000 L538-L544), each an
//                IEEE single: the thesis's 24-bit fraction and 8-bit exponent (L582);
//   words 20-23  the pole thresholds u_pole_b, u_pole_c, v_pole_b, v_pole_c (singles; not in
//                the thesis, see UllnerQuadParams);
//   word  24     the host's flag bits: bit 0 u_parallel, bit 1 v_parallel, bit 2 u_plus_root,
//                bit 3 v_plus_root (the initial validity bits that select a branch, L530).
// The host writes a line with store_words; the fetch stage reads it back with load_words. The
// kernel computes in double on what the line holds, and so does the functional twin: its
// parameters are rounded through the same words (as_stored), so the machine and the twin give
// the same answers bit for bit while every answer of the machine depends on the words it read.
#include <cstdint>
#include <span>

#include "firmware/kernels/ullner_quad.hpp"

namespace rtsim::kernels {

/// Words per polygon line: 20 parameters, 4 pole thresholds, 1 word of flags.
inline constexpr std::size_t kUllnerStoredWords = kUllnerParamCount + 5;
/// Index of the flags word and its bits.
inline constexpr std::size_t kUllnerFlagsWord = kUllnerParamCount + 4;
inline constexpr std::uint32_t kUllnerFlagUParallel = 1u << 0;
inline constexpr std::uint32_t kUllnerFlagVParallel = 1u << 1;
inline constexpr std::uint32_t kUllnerFlagUPlusRoot = 1u << 2;
inline constexpr std::uint32_t kUllnerFlagVPlusRoot = 1u << 3;

/// The line the host writes for `p` (values rounded to the nearest single).
void store_words(const UllnerQuadParams<double>& p,
                 std::span<std::uint32_t, kUllnerStoredWords> out);
/// The parameters a line holds, widened to double (exactly). The family fields (host
/// bookkeeping, not stored) are left Quadratic.
UllnerQuadParams<double> load_words(std::span<const std::uint32_t, kUllnerStoredWords> line);
/// `p` as it comes back from the memories: load_words(store_words(p)), family kept.
UllnerQuadParams<double> as_stored(const UllnerQuadParams<double>& p);

}  // namespace rtsim::kernels
