#pragma once
// A fault in flight on the array's mesh: `--fault nodeK.link_D:WORD:XOR` corrupts word WORD of
// every ray message that processor K's link toward D (n, e, s, w) carries, as on a wire stuck or
// flipped. The words are the message's 17 (ray_message.hpp, Fig. 2-27): 0 the type k, 1 the
// pixel's row r, 2 its column c, 3-5 the origin r0, 6-8 the direction r_d, 9-11 the colour c
// (a ray's weight, a shadow ray's light, a result's contribution), 12 the resume position, 13
// the far limit, 14 the generation, 15-16 the credit (low, high).
//   * A number travels as an IEEE single (the thesis's 32-bit words): the corrupted word is that
//     single's bits XORed; one that is then not finite arrives as 0.
//   * A type, row or column is taken modulo the types, rows or columns there are (a processor
//     dispatches on what it reads; the model never indexes past its arrays); a generation past
//     255 arrives as 255 (the ray spawns nothing more).
//   * A corrupted type or resume position can send a message back and forth between two
//     processors for ever: the model's watchdog destroys a message that has crossed more links
//     than any walk needs (array.messages_destroyed_looping), keeping its credit where it ends.
//   * A credit corrupted breaks termination: the run ends with a message, exit status 2, and
//     writes nothing.
#include <cstdint>
#include <string>
#include <vector>

#include "modules/mesh_topology.hpp"
#include "platform/machine.hpp"
#include "platform/machines/ullner_array/ray_message.hpp"

namespace rtsim::platform::ullner_array {

struct MessageFault {
  int node = 0;
  modules::Direction direction = modules::Direction::kNorth;
  unsigned word = 0;
  std::uint32_t xor_mask = 0;
  std::uint64_t applied = 0;  ///< messages corrupted
  bool credit = false;        ///< a credit word: termination cannot be trusted

  /// "node12.link_e".
  std::string name() const;
  /// Corrupts `m`, a message of an image `width` x `height`.
  void apply(RayMessage& m, int width, int height);
};

/// The faults of `faults` that name a link of the mesh `topology` (taken out; the rest are left
/// for the memories); an InputError for a processor, link or word that does not exist.
std::vector<MessageFault> message_faults(const modules::MeshTopology& topology,
                                         std::vector<MemoryFault>& faults);

}  // namespace rtsim::platform::ullner_array
