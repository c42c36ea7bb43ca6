#include "firmware/kernels/ullner_description_words.hpp"

#include <bit>

namespace rtsim::kernels {
namespace {

// A family's two bits in the identity word.
enum FamilyCode : std::uint32_t { kMinusRoot = 0, kPlusRoot = 1, kParallelForm = 2, kDeflated = 3 };
constexpr unsigned kUShift = kUllnerIdentityBits, kVShift = kUllnerIdentityBits + 2;

std::uint32_t single_bits(double v) { return std::bit_cast<std::uint32_t>(static_cast<float>(v)); }
double from_single(std::uint32_t w) { return static_cast<double>(std::bit_cast<float>(w)); }

std::uint32_t code_of(bool parallel, bool plus_root, QuadFamily family) {
  if (!parallel) return plus_root ? kPlusRoot : kMinusRoot;
  return family == QuadFamily::Deflated ? kDeflated : kParallelForm;
}

/// The first word of a family's "B" vector (a) and its scalar (a0).
constexpr std::size_t a_word(bool u) {
  return static_cast<std::size_t>(u ? QuadParam::u_ax : QuadParam::v_ax);
}

}  // namespace

void describe(const UllnerQuadParams<double>& p, std::uint32_t identity,
              std::span<std::uint32_t, kUllnerDescriptionWords> out) {
  for (std::size_t i = 0; i < kUllnerParamCount; ++i) out[i] = single_bits(p.word[i]);
  const std::uint32_t u = code_of(p.u_parallel, p.u_plus_root, p.u_family);
  const std::uint32_t v = code_of(p.v_parallel, p.v_plus_root, p.v_family);
  // A deflated family's B is 1 (a = 0, a0 = 1): its a.x and a.y words carry its partner's (the
  // pencil's) thresholds instead.
  if (u == kDeflated) {
    out[a_word(true)] = single_bits(p.v_pole_b);
    out[a_word(true) + 1] = single_bits(p.v_pole_c);
  }
  if (v == kDeflated) {
    out[a_word(false)] = single_bits(p.u_pole_b);
    out[a_word(false) + 1] = single_bits(p.u_pole_c);
  }
  out[kUllnerDescriptionIdWord] = (identity & kUllnerMaxIdentity) | (u << kUShift) | (v << kVShift);
}

UllnerDescribedPolygon read_description(
    std::span<const std::uint32_t, kUllnerDescriptionWords> words) {
  UllnerDescribedPolygon d;
  UllnerQuadParams<double>& p = d.params;
  for (std::size_t i = 0; i < kUllnerParamCount; ++i) p.word[i] = from_single(words[i]);
  const std::uint32_t id_word = words[kUllnerDescriptionIdWord];
  d.identity = id_word & kUllnerMaxIdentity;
  const std::uint32_t u = (id_word >> kUShift) & 3u, v = (id_word >> kVShift) & 3u;
  p.u_parallel = u >= kParallelForm;
  p.v_parallel = v >= kParallelForm;
  p.u_plus_root = u != kMinusRoot;
  p.v_plus_root = v != kMinusRoot;
  // A pencil's thresholds are in its deflated partner's a.x and a.y; the deflated family's own
  // B is then restored to 1.
  const auto deflate = [&p](bool family_u, double& pole_b, double& pole_c) {
    const std::size_t a = a_word(family_u);
    pole_b = p.word[a];
    pole_c = p.word[a + 1];
    p.word[a] = p.word[a + 1] = p.word[a + 2] = 0.0;
    p.word[a + 3] = 1.0;
  };
  if (u == kDeflated) deflate(true, p.v_pole_b, p.v_pole_c);
  if (v == kDeflated) deflate(false, p.u_pole_b, p.u_pole_c);
  // Thresholds belong to a parallel form only: a deflated partner of a quadratic or of another
  // deflated family carries none that count.
  if (!p.u_parallel || u == kDeflated) p.u_pole_b = p.u_pole_c = 0.0;
  if (!p.v_parallel || v == kDeflated) p.v_pole_b = p.v_pole_c = 0.0;
  return d;
}

}  // namespace rtsim::kernels
