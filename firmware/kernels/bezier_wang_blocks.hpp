#pragma once
// The six functional blocks of Wang, Lewis & Hung's ray/Bezier-patch pipeline (seed 002 Table 1,
// L405-L413): PlaneGenerator, PatchSubdivider, HullClassification, PatchCenter, PatchDistance,
// Culler. Each block is a struct with one static function and its machine-neutral cost kCost
// (what the code below really does, counted per call). Templated on the scalar type: the paper's
// DSPs compute in IEEE single (L296), the renderer may use double.
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdlib>

#include "firmware/cost.hpp"
#include "firmware/kernels/bezier_patch_math.hpp"
#include "firmware/math.hpp"

namespace rtsim::kernels {

/// The ray as two perpendicular planes U and V that both contain it (§2.3, L124-L135), each as
/// N.x + E = 0 (eq. 1, L102). The paper never states the constant E; the planes contain the ray,
/// so E = -N.O.
template <typename T>
struct RayPlanes {
  Vec3T<T> n_u{T(0)};
  T e_u = T(0);
  Vec3T<T> n_v{T(0)};
  T e_v = T(0);
};

/// PlaneGenerator (§2.3, L130-L133).
struct PlaneGenerator {
  /// choose xi: 3 |.| (instructions) + 2 comparisons; N_u = T x D is a rearrangement with one
  /// negation (1 instruction, L135); N_v = N_u x D: 6 mul, 3 add; E_u = -N_u.O and E_v = -N_v.O:
  /// 3 mul + 2 add each and a negation each (2 instructions). Memory: O, D in (6), 8 plane words
  /// out.
  static constexpr Cost kCost{.fp_add = 2 + 3 + 2 + 2,
                              .fp_mul = 6 + 3 + 3,
                              .fp_div = 0,
                              .fp_sqrt = 0,
                              .mem_words = 6 + 8,
                              .instructions = 3 + 1 + 2};

  template <typename T>
  static RayPlanes<T> generate(const Vec3T<T>& o, const Vec3T<T>& d) {
    // 1. xi with |D_xi| = min(|D_x|, |D_y|, |D_z|); ties go to the earlier axis.
    const T ax = std::fabs(d.x), ay = std::fabs(d.y), az = std::fabs(d.z);
    const int xi = (ax <= ay && ax <= az) ? 0 : (ay <= az ? 1 : 2);
    // 2.-3. T = e_xi, N_u = T x D: only a rearrangement of D's elements (L135).
    Vec3T<T> n_u;
    if (xi == 0)
      n_u = Vec3T<T>(T(0), -d.z, d.y);
    else if (xi == 1)
      n_u = Vec3T<T>(d.z, T(0), -d.x);
    else
      n_u = Vec3T<T>(-d.y, d.x, T(0));
    // 4. N_v = N_u x D.
    RayPlanes<T> planes;
    planes.n_u = n_u;
    planes.n_v = glm::cross(n_u, d);
    planes.e_u = -glm::dot(planes.n_u, o);
    planes.e_v = -glm::dot(planes.n_v, o);
    return planes;
  }
};

/// A subpatch travelling through the pipeline: its control net and where it sits in the original
/// patch's parameter square: u in [iu, iu+1] / 2^level, v in [iv, iv+1] / 2^level. The paper
/// tracks no parameters (it outputs only a point, L260); we carry the indices so the hit can
/// report (u, v). Integer indices are exact at any depth in any precision.
template <typename T>
struct Subpatch {
  ControlNet<T> net;
  std::uint32_t iu = 0;
  std::uint32_t iv = 0;
  std::uint32_t level = 0;

  double u_center() const { return (iu + 0.5) / static_cast<double>(std::uint64_t{1} << level); }
  double v_center() const { return (iv + 0.5) / static_cast<double>(std::uint64_t{1} << level); }
};

/// PatchSubdivider (§2.4, eqs. 7-11, L137-L169): one patch into four.
struct PatchSubdivider {
  /// 36 cubic splits (12 curves for the u-split, 2 x 12 for the v-splits) x 3 coordinates x (6 add,
  /// 6 halvings); memory: 48 words in, 4 x 48 out; 8 integer instructions for the parameter
  /// indices of the four children.
  static constexpr Cost kCost{.fp_add = 36 * 3 * 6,
                              .fp_mul = 36 * 3 * 6,
                              .fp_div = 0,
                              .fp_sqrt = 0,
                              .mem_words = 48 + 4 * 48,
                              .instructions = 8};

  template <typename T>
  static void subdivide(const Subpatch<T>& in, Subpatch<T> out[4]) {
    ControlNet<T> nets[4];
    split4(in.net, nets);
    for (int q = 0; q < 4; ++q) {
      out[q].net = nets[q];
      out[q].iu = 2 * in.iu + static_cast<std::uint32_t>(quadrant_u_half(q));
      out[q].iv = 2 * in.iv + static_cast<std::uint32_t>(quadrant_v_half(q));
      out[q].level = in.level + 1;
    }
  }
};

/// The result of HullClassification: the two sign sums of eq. 16 and the verdict.
struct HullClass {
  int sgnsum_u = 0;
  int sgnsum_v = 0;
  bool may_hit = false;  ///< false when |Sgnsum| = 16 for either plane (L207)
};

/// HullClassification (§2.5, eqs. 13-16, L171-L207).
struct HullClassification {
  /// Sign distances d^s = A x + B y + C z + E of 16 points against 2 planes (eq. 15): 32 x (3 mul,
  /// 3 add); 32 sign tests (comparisons); Sgnsum: 32 integer additions; two |Sgnsum| = 16 checks
  /// (4 instructions). Memory: 48 point words and 8 plane words. All 16 points are always
  /// evaluated, no early exit (L193), so the cost is data-independent.
  static constexpr Cost kCost{.fp_add = 32 * 3 + 32,
                              .fp_mul = 32 * 3,
                              .fp_div = 0,
                              .fp_sqrt = 0,
                              .mem_words = 48 + 8,
                              .instructions = 32 + 4};

  template <typename T>
  static HullClass classify(const RayPlanes<T>& planes, const ControlNet<T>& net) {
    HullClass h;
    for (const auto& row : net.p)
      for (const auto& q : row) {
        const T du = glm::dot(planes.n_u, q) + planes.e_u;  // eq. 13 for plane U
        const T dv = glm::dot(planes.n_v, q) + planes.e_v;  // eq. 13 for plane V
        // eq. 16: a point on the plane (d^s = 0) counts as positive ("above", L181).
        h.sgnsum_u += du >= T(0) ? 1 : -1;
        h.sgnsum_v += dv >= T(0) ? 1 : -1;
      }
    h.may_hit = std::abs(h.sgnsum_u) != 16 && std::abs(h.sgnsum_v) != 16;
    return h;
  }
};

/// PatchCenter (§2.6, eqs. 17-18, L209-L221): the parametric centre Q(1/2, 1/2), which lies on
/// the patch (unlike the mean of the control points, L213).
struct PatchCenter {
  /// parametric_center: 3 x (11 mul, 15 add); memory: 48 words in, 3 out.
  static constexpr Cost kCost{.fp_add = 3 * 15,
                              .fp_mul = 3 * 11,
                              .fp_div = 0,
                              .fp_sqrt = 0,
                              .mem_words = 48 + 3,
                              .instructions = 0};

  template <typename T>
  static Vec3T<T> center(const ControlNet<T>& net) {
    return parametric_center(net);
  }
};

/// PatchDistance (§2.7, eqs. 20-21, L223-L245): the signed ray/patch distance d^p.
struct PatchDistance {
  /// The flag for a centre behind the origin (eq. 21). Any negative key sorts as "greater" than
  /// every valid distance in the Culler (L306).
  static constexpr double kBehind = -1.0;

  /// C - O: 3 add; Manhattan sum: 3 |.| (instructions) + 2 add (eq. 20); (C - O).D: 3 mul + 2 add;
  /// sign test: 1 comparison and 1 select (instruction). Memory: centre in, key out.
  static constexpr Cost kCost{.fp_add = 3 + 2 + 2 + 1,
                              .fp_mul = 3,
                              .fp_div = 0,
                              .fp_sqrt = 0,
                              .mem_words = 3 + 1,
                              .instructions = 3 + 1};

  template <typename T>
  static T distance(const Vec3T<T>& o, const Vec3T<T>& d, const Vec3T<T>& c) {
    const Vec3T<T> w = c - o;
    const T manhattan = std::fabs(w.x) + std::fabs(w.y) + std::fabs(w.z);  // eq. 20
    // eq. 21: a dot product of exactly 0 counts as "in front".
    return glm::dot(w, d) >= T(0) ? manhattan : T(kBehind);
  }
};

/// Culler (§2.8, L247-L249): from the 16 candidates of buffer2 keep at most N_i = 4 with the
/// smallest non-negative key, nearest first.
struct Culler {
  static constexpr int kCandidates = 16;  ///< buffer2 capacity (L256)
  static constexpr int kSurvivors = 4;    ///< N_i, buffer1 capacity (L253)
  /// A sort key's bits: a single's 32 and the 4-bit tag (Fig. 11, L304); the fewest a key may
  /// have (one distance bit). Below kKeyBits only the distance's top key_bits - 4 bits count
  /// (culler_network.hpp: the prototype's 12-bit Culler, L316).
  static constexpr int kKeyBits = 36;
  static constexpr int kMinKeyBits = 5;

  /// A non-negative distance's key with `key_bits` bits, tag apart: its single's top
  /// key_bits - 4 bits (the single's bit pattern orders non-negative values as the values do).
  template <typename T>
  static std::uint32_t kept_bits(T distance, int key_bits) {
    return std::bit_cast<std::uint32_t>(static_cast<float>(distance)) >> (kKeyBits - key_bits);
  }

  /// Software version: partial selection sort, 4 passes over the keys, at most 15 + 14 + 13 + 12
  /// key comparisons; per pass 16 "already taken / flagged" tests and the bookkeeping (64
  /// instructions). Memory: 16 keys read per pass, 4 indices written. (The paper's software used
  /// Quicksort, 3081 DSP cycles; the hardware a 16-input bitonic network, L310. A machine model
  /// times the Culler with its own parameters; this is what the code below does.)
  static constexpr Cost kCost{.fp_add = 15 + 14 + 13 + 12,
                              .fp_mul = 0,
                              .fp_div = 0,
                              .fp_sqrt = 0,
                              .mem_words = 4 * 16 + 4,
                              .instructions = 4 * 16};

  /// keys[i] < 0 marks a candidate that is behind the origin (eq. 21) or failed the hull test. The
  /// paper is silent on how a hull failure enters the sort key (note 002 §2.7); we flag it exactly
  /// like "behind", so the Culler drops it: the hardware key's sign bit makes it sort greater than
  /// any valid distance (L306), and a flagged key is never kept. Equal keys keep the lower buffer2
  /// index first (the 4-bit patch index tag of the key, L304). Returns the number kept (0..4);
  /// out[0] is the nearest.
  /// With `key_bits` < kKeyBits the distances compare on their single's top key_bits - 4 bits
  /// (as the network does).
  template <typename T>
  static int select(const std::array<T, kCandidates>& keys, std::array<int, kSurvivors>& out,
                    int key_bits = kKeyBits) {
    const auto less = [&](int a, int b) {
      if (key_bits == kKeyBits) return keys[a] < keys[b];
      return kept_bits(keys[a], key_bits) < kept_bits(keys[b], key_bits);
    };
    std::uint32_t taken = 0;
    int kept = 0;
    for (; kept < kSurvivors; ++kept) {
      int best = -1;
      for (int i = 0; i < kCandidates; ++i) {
        if ((taken >> i) & 1u || !(keys[i] >= T(0))) continue;
        if (best < 0 || less(i, best)) best = i;
      }
      if (best < 0) break;
      taken |= 1u << best;
      out[kept] = best;
    }
    return kept;
  }
};

}  // namespace rtsim::kernels
