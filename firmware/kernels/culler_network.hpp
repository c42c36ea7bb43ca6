#pragma once
// The Culler ASIC of Wang, Lewis & Hung (seed 002 §4.2, L302-L318): a bitonic sorting network of
// upsort and downsort units on 16 keys (Fig. 20), 10 compare stages, whose first four outputs
// are the tags of the four nearest candidates (Fig. 13).
//
// A key (Fig. 11, L304-L306) is the ray/patch distance as an IEEE single (bits 0-31) with the
// 4-bit patch index as its tag (bits 32-35). A unit compares the distances: a negative one (bit
// 31 set: the patch lies behind, or failed the hull test, Culler::select) is "greater" than any
// positive one (L308), and equal distances are ordered by their tag, so the network's order is
// a total order and its outputs are those of any exact sort (Culler::select): the test shows it.
// The prototype's Culler was "a scaled-down (12-bit) version" (L316): `key_bits` below 36 keeps
// only the distance's top key_bits - 4 bits, so nearby distances tie and the tag decides.
#include <array>
#include <cstdint>
#include <utility>

#include "firmware/kernels/bezier_wang_blocks.hpp"

namespace rtsim::kernels {

struct CullerNetwork {
  static constexpr int kStages = 10;  ///< log2(16) (log2(16) + 1) / 2 (L318)

  /// What a unit compares: validity first (a flagged key sorts after every valid one), then the
  /// distance's kept bits, then the tag.
  struct Key {
    bool valid = false;
    std::uint32_t distance = 0;  ///< the kept top bits of the single's pattern
    std::uint8_t tag = 0;
    bool operator<(const Key& o) const {
      if (valid != o.valid) return valid;
      if (distance != o.distance) return distance < o.distance;
      return tag < o.tag;
    }
  };

  template <typename T>
  static Key key(T distance, int tag, int key_bits) {
    Key k;
    k.tag = static_cast<std::uint8_t>(tag);
    k.valid = distance >= T(0);  // NaN and the "behind" flag are not
    if (k.valid) k.distance = Culler::kept_bits(distance, key_bits);
    return k;
  }

  /// The network on `keys` with `key_bits`-bit keys (Culler::kMinKeyBits .. kKeyBits): the
  /// indices of the (at most) four nearest valid candidates in out, nearest first; the number.
  template <typename T>
  static int select(const std::array<T, Culler::kCandidates>& keys,
                    std::array<int, Culler::kSurvivors>& out, int key_bits) {
    std::array<Key, Culler::kCandidates> k;
    for (int i = 0; i < Culler::kCandidates; ++i) k[i] = key(keys[i], i, key_bits);
    // Bitonic sort, ascending: for block size 2, 4, 8, 16, merge with strides size/2 .. 1; a
    // unit's direction (upsort or downsort) follows the bit of its block. 4 + 3 + 2 + 1 = 10
    // stages.
    for (int size = 2; size <= Culler::kCandidates; size *= 2)
      for (int stride = size / 2; stride > 0; stride /= 2)
        for (int i = 0; i < Culler::kCandidates; ++i) {
          const int j = i ^ stride;
          if (j <= i) continue;
          const bool ascending = (i & size) == 0;
          if ((k[j] < k[i]) == ascending) std::swap(k[i], k[j]);
        }
    int kept = 0;
    for (; kept < Culler::kSurvivors && k[kept].valid; ++kept) out[kept] = k[kept].tag;
    return kept;
  }
};

}  // namespace rtsim::kernels
