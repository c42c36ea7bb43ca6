#pragma once
// A fault in flight on the chain: `--fault pipeline.engineK.in:WORD:XOR` corrupts word WORD of
// every ray description as it enters processor K (a wire of its input stuck, or a bit flipped
// on the way), not a memory at rest. The words are the description's 13 on the wire (Fig. 2-24,
// L727): 0-2 r0, 3-5 r1 - r0, 6-8 p_r, 9 t, 10 u, 11 v, 12 the identity i. A number travels as
// an IEEE single (the thesis's 32-bit words): the corrupted word is that single's bits XORed.
// Both pipeline models apply it at the same place, so they still agree.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "platform/machine.hpp"
#include "platform/machines/ullner_pipeline/description_in_flight.hpp"

namespace rtsim::platform::ullner_pipeline {

struct DescriptionFault {
  std::uint64_t engine = 0;
  unsigned word = 0;
  std::uint32_t xor_mask = 0;
  std::uint64_t applied = 0;  ///< descriptions corrupted

  /// The name it is given on the command line: "pipeline.engine7.in".
  std::string name(const std::string& chain) const;
  /// Corrupts `d` (and the ray's set-up, when r0 or r1 changed).
  void apply(DescriptionInFlight& d);
};

/// The faults of `faults` that name a processor's input of the chain `chain` (the rest are left
/// for the memories); InputError for a processor or word that does not exist.
std::vector<DescriptionFault> description_faults(const std::string& chain, std::uint64_t engines,
                                                 std::vector<MemoryFault>& faults);

}  // namespace rtsim::platform::ullner_pipeline
