#pragma once
// Loading the pipeline (seed 000 L717-L719): the host presents a polygon description to the
// first processor, which "passes its current polygon to the second processor before accepting
// the new polygon"; every processor does the same, so the chain shifts by one position and "the
// description formerly held in the final processor is shifted back to the host".
#include <array>
#include <cstdint>
#include <systemc>

#include "firmware/kernels/ullner_description_words.hpp"

namespace rtsim::platform::ullner_pipeline {

/// "Five vector and five scalar values, as they did in the ray tracing peripheral ... an
/// additional value that serves to identify the polygon" (L717): the 20 parameters and the word
/// of the identity and the families' bits (ullner_description_words.hpp).
struct PolygonDescription {
  static constexpr unsigned kIdWord = kernels::kUllnerDescriptionIdWord;
  static constexpr unsigned kWords = kernels::kUllnerDescriptionWords;
  static constexpr std::uint64_t kWireBits = 32 * kWords;
  std::array<std::uint32_t, kWords> words{};
};

/// pipeline.model = engines: the description a processor passes to the next during the load
/// (its previous polygon), and when it arrives there; the first processor's acceptance.
struct LoadWave {
  PolygonDescription description;
  sc_core::sc_time at = sc_core::SC_ZERO_TIME;
  sc_core::sc_time accepted = sc_core::SC_ZERO_TIME;
};

/// A processor's polygon registers (the chain's register memory): it passes the description it
/// holds on and takes the one it received in its place.
struct RegisterFile {
  virtual ~RegisterFile() = default;
  /// Processor `line`'s registers take `words`; `words` becomes what they held.
  virtual void exchange(std::uint64_t line, PolygonDescription& words) = 0;
};

/// One presentation: the description the host sends in, and what comes back out of the far end.
struct PolygonLoad {
  PolygonDescription presented;
  PolygonDescription returned;                           ///< set by the chain
  sc_core::sc_time returned_at = sc_core::SC_ZERO_TIME;  ///< when it reaches the host
};

}  // namespace rtsim::platform::ullner_pipeline
