#pragma once
// A message between the processors of Ullner's ray-tracing array (Fig. 2-27, L791-L799): the
// type k, the pixel (r, c), the ray's origin r0 and direction r_d, and its colour contribution c,
// "three vector and three scalar fields". Types (L799-L815): new (on its way to the subvolume it
// first strikes), vision (reflected and refracted rays too, L817), shadow, result (a contribution
// on its way to its pixel's processor). The model adds:
//  * the position along the ray's subvolume walk where the next processor resumes it (the DDA's
//    state: one word for the count of subvolumes walked; the thesis leaves how a processor knows
//    where a ray entered its column open);
//  * the ray's far limit (a shadow ray stops at its light) and its generation (the shading's
//    depth limit), one word each;
//  * the termination detector's credit (two words), and a fifth type, credit, which returns it.
#include <cstdint>
#include <string>
#include <systemc>
#include <vector>

#include "firmware/accel/uniform_grid.hpp"
#include "firmware/math.hpp"
#include "firmware/shading/traced_ray.hpp"
#include "modules/latency_probe.hpp"

namespace rtsim::platform::ullner_array {

enum class MessageType : std::uint8_t { kNew, kVision, kShadow, kResult, kCredit };

/// The types' names in MessageType order, as statistics name them ("sent_vision").
inline std::vector<std::string> message_type_names() {
  return {"new", "vision", "shadow", "result", "credit"};
}

struct RayMessage {
  MessageType type = MessageType::kNew;
  /// Pixel (as y * width + x), r0, r_d, c: the ray as the firmware carries it (its weight or,
  /// for a shadow ray, its light contribution is the colour field c).
  shading::TracedRay ray;
  Color contribution{0.0};   ///< result: the colour to add to the pixel
  std::uint32_t resume = 0;  ///< subvolumes of the ray's walk already searched
  /// The simulator's note of where the walk stopped (accel::DdaPlace: the subvolume `resume`
  /// counts up to, and the t the ray entered it), valid while `walk_at` equals `resume`: the next
  /// processor goes on from there instead of walking again from the ray's origin. Worked out from
  /// the words above, so not on the wire; a fault in flight drops it (walk_at = kNoWalk).
  static constexpr std::uint32_t kNoWalk = 0xffffffffu;
  std::uint32_t walk_at = kNoWalk;
  std::uint64_t credit = 0;   ///< the termination detector's share carried
  bool first_sample = false;  ///< a pixel's first vision ray: its answer fills the AOVs
  sc_core::sc_time created;   ///< when its ray was made (ray latency)
  /// --latency-probe: its ray's journey (forked for what it spawns), and the time up to which
  /// the journey is accounted. Not on the wire.
  modules::LatencyProbe::Journey journey = modules::LatencyProbe::kNoJourney;
  sc_core::sc_time cursor;
  /// Links it and the messages of its ray tree before it have crossed (the model's watchdog,
  /// ArrayContext::hop_limit). Not on the wire.
  std::uint32_t hops = 0;
  accel::CellIndex walk_cell{};  ///< with walk_at: the subvolume the walk stopped in
  double walk_t_enter = 0.0;     ///< with walk_at: the t at which the ray entered it
  /// The traces' names: this message (1, 2, ... in the order they are made), its ray tree (its
  /// vision ray's number; 0 for credit), and the links it has crossed itself. Not on the wire.
  std::uint64_t id = 0;
  std::uint64_t tree = 0;
  std::uint32_t links = 0;

  /// k, r, c, r0 (3), r_d (3), c (3) = 12 words (Fig. 2-27), + resume, far limit, generation,
  /// credit (2) = 17 words.
  static constexpr unsigned kWords = 17;
  static constexpr std::uint64_t kWireBits = 32 * kWords;
};

}  // namespace rtsim::platform::ullner_array
