#include "platform/machines/ullner_array/message_fault.hpp"

#include <algorithm>
#include <bit>
#include <cctype>
#include <cmath>

#include "common/input_error.hpp"
#include "platform/machines/machine_support.hpp"

namespace rtsim::platform::ullner_array {

namespace {

/// A number's word on the wire, XORed: the single it travels as, its bits flipped (0 if that is
/// not a finite number).
double corrupt_number(double x, std::uint32_t mask) {
  const auto v = static_cast<double>(
      std::bit_cast<float>(std::bit_cast<std::uint32_t>(static_cast<float>(x)) ^ mask));
  return std::isfinite(v) ? v : 0.0;
}

constexpr const char* kWords =
    "a ray message has 17 words (0 type, 1 row, 2 column, 3-5 origin, 6-8 direction, 9-11 "
    "colour, 12 resume, 13 far limit, 14 generation, 15-16 credit)";

}  // namespace

std::string MessageFault::name() const {
  return "node" + std::to_string(node) + ".link_" + std::string(modules::direction_name(direction));
}

void MessageFault::apply(RayMessage& m, int width, int height) {
  ++applied;
  // The simulator's note of the walk was worked out from the words before the fault: the next
  // processor walks the corrupted ray from its origin, as the machine would.
  m.walk_at = RayMessage::kNoWalk;
  shading::TracedRay& r = m.ray;
  const auto w = static_cast<std::uint32_t>(width), h = static_cast<std::uint32_t>(height);
  Color& colour = m.type == MessageType::kResult   ? m.contribution
                  : m.type == MessageType::kShadow ? r.light_contribution
                                                   : r.weight;
  switch (word) {
    case 0:
      m.type = static_cast<MessageType>((static_cast<std::uint32_t>(m.type) ^ xor_mask) %
                                        message_type_names().size());
      return;
    case 1:
      r.pixel = ((r.pixel / w) ^ xor_mask) % h * w + r.pixel % w;
      return;
    case 2:
      r.pixel = r.pixel / w * w + ((r.pixel % w) ^ xor_mask) % w;
      return;
    case 12:
      m.resume ^= xor_mask;
      return;
    case 13:
      r.t_max = corrupt_number(r.t_max, xor_mask);
      return;
    case 14:
      r.depth = static_cast<std::uint8_t>(std::min<std::uint32_t>(r.depth ^ xor_mask, 255));
      return;
    case 15:
    case 16:
      m.credit ^= static_cast<std::uint64_t>(xor_mask) << (word == 16 ? 32 : 0);
      return;
    default:
      break;
  }
  double* fields[9] = {&r.ray.origin.x,    &r.ray.origin.y,    &r.ray.origin.z,
                       &r.ray.direction.x, &r.ray.direction.y, &r.ray.direction.z,
                       &colour.x,          &colour.y,          &colour.z};
  *fields[word - 3] = corrupt_number(*fields[word - 3], xor_mask);
}

std::vector<MessageFault> message_faults(const modules::MeshTopology& topology,
                                         std::vector<MemoryFault>& faults) {
  std::vector<MessageFault> out;
  for (const MemoryFault& f : take_faults(faults, [](const std::string& name) {
         return name.starts_with("node") && name.find(".link_") != std::string::npos;
       })) {
    const std::string arg = "--fault " + f.memory + ":" + std::to_string(f.word);
    const std::size_t dot = f.memory.find(".link_");
    const std::string digits = f.memory.substr(4, dot - 4);
    const std::string dir = f.memory.substr(dot + 6);
    const bool number = !digits.empty() && digits.size() <= 9 &&
                        std::all_of(digits.begin(), digits.end(), [](char c) {
                          return std::isdigit(static_cast<unsigned char>(c));
                        });
    const auto d =
        std::find_if(modules::kDirections.begin(), modules::kDirections.end(),
                     [&](modules::Direction x) { return modules::direction_name(x) == dir; });
    if (!number || std::stoull(digits) >= static_cast<std::uint64_t>(topology.nodes()) ||
        d == modules::kDirections.end() ||
        !topology.neighbour(topology.node(static_cast<int>(std::stoull(digits))), *d))
      throw InputError(arg, 0,
                       "the array's links are nodeK.link_n, _e, _s and _w for K from 0 to " +
                           std::to_string(topology.nodes() - 1) +
                           ", where a neighbour is connected (not on a ring)");
    if (f.word >= RayMessage::kWords) throw InputError(arg, 0, kWords);
    out.push_back({.node = static_cast<int>(std::stoull(digits)),
                   .direction = *d,
                   .word = static_cast<unsigned>(f.word),
                   .xor_mask = f.xor_mask,
                   .credit = f.word >= 15});
  }
  return out;
}

}  // namespace rtsim::platform::ullner_array
