#include "firmware/kernels/ullner_quad_words.hpp"

#include <array>
#include <bit>

namespace rtsim::kernels {
namespace {

std::uint32_t single_bits(double v) { return std::bit_cast<std::uint32_t>(static_cast<float>(v)); }
double from_single(std::uint32_t w) { return static_cast<double>(std::bit_cast<float>(w)); }

}  // namespace

void store_words(const UllnerQuadParams<double>& p,
                 std::span<std::uint32_t, kUllnerStoredWords> out) {
  for (std::size_t i = 0; i < kUllnerParamCount; ++i) out[i] = single_bits(p.word[i]);
  out[kUllnerParamCount + 0] = single_bits(p.u_pole_b);
  out[kUllnerParamCount + 1] = single_bits(p.u_pole_c);
  out[kUllnerParamCount + 2] = single_bits(p.v_pole_b);
  out[kUllnerParamCount + 3] = single_bits(p.v_pole_c);
  out[kUllnerFlagsWord] =
      (p.u_parallel ? kUllnerFlagUParallel : 0u) | (p.v_parallel ? kUllnerFlagVParallel : 0u) |
      (p.u_plus_root ? kUllnerFlagUPlusRoot : 0u) | (p.v_plus_root ? kUllnerFlagVPlusRoot : 0u);
}

UllnerQuadParams<double> load_words(std::span<const std::uint32_t, kUllnerStoredWords> line) {
  UllnerQuadParams<double> p;
  for (std::size_t i = 0; i < kUllnerParamCount; ++i) p.word[i] = from_single(line[i]);
  p.u_pole_b = from_single(line[kUllnerParamCount + 0]);
  p.u_pole_c = from_single(line[kUllnerParamCount + 1]);
  p.v_pole_b = from_single(line[kUllnerParamCount + 2]);
  p.v_pole_c = from_single(line[kUllnerParamCount + 3]);
  const std::uint32_t flags = line[kUllnerFlagsWord];
  p.u_parallel = (flags & kUllnerFlagUParallel) != 0;
  p.v_parallel = (flags & kUllnerFlagVParallel) != 0;
  p.u_plus_root = (flags & kUllnerFlagUPlusRoot) != 0;
  p.v_plus_root = (flags & kUllnerFlagVPlusRoot) != 0;
  return p;
}

UllnerQuadParams<double> as_stored(const UllnerQuadParams<double>& p) {
  std::array<std::uint32_t, kUllnerStoredWords> line{};
  store_words(p, line);
  UllnerQuadParams<double> out = load_words(line);
  out.u_family = p.u_family;
  out.v_family = p.v_family;
  return out;
}

}  // namespace rtsim::kernels
