#include "platform/machines/ullner_pipeline/description_fault.hpp"

#include <algorithm>
#include <bit>
#include <cctype>

#include "common/input_error.hpp"
#include "platform/machines/machine_support.hpp"

namespace rtsim::platform::ullner_pipeline {

namespace {

/// A number's word on the wire, XORed: the single it travels as, its bits flipped.
double corrupt_number(double x, std::uint32_t mask) {
  return static_cast<double>(
      std::bit_cast<float>(std::bit_cast<std::uint32_t>(static_cast<float>(x)) ^ mask));
}

}  // namespace

std::string DescriptionFault::name(const std::string& chain) const {
  return chain + ".engine" + std::to_string(engine) + ".in";
}

void DescriptionFault::apply(DescriptionInFlight& m) {
  tasks::RayDescription& d = m.description;
  ++applied;
  if (word == 12) {
    d.i ^= xor_mask;
    return;
  }
  double* fields[12] = {&d.r0.x,
                        &d.r0.y,
                        &d.r0.z,
                        &d.r1_minus_r0.x,
                        &d.r1_minus_r0.y,
                        &d.r1_minus_r0.z,
                        &d.p_r.x,
                        &d.p_r.y,
                        &d.p_r.z,
                        &d.t,
                        &d.u,
                        &d.v};
  *fields[word] = corrupt_number(*fields[word], xor_mask);
  if (word < 6) m.ray = kernels::UllnerRay<double>::make(d.r0, d.r1_minus_r0);
}

std::vector<DescriptionFault> description_faults(const std::string& chain, std::uint64_t engines,
                                                 std::vector<MemoryFault>& faults) {
  const std::string prefix = chain + ".engine";
  std::vector<DescriptionFault> out;
  for (const MemoryFault& f : take_faults(faults, [&](const std::string& name) {
         return name.starts_with(prefix) && name.ends_with(".in");
       })) {
    const std::string arg = "--fault " + f.memory + ":" + std::to_string(f.word);
    const std::string digits = f.memory.substr(prefix.size(), f.memory.size() - prefix.size() - 3);
    const bool number = !digits.empty() && digits.size() <= 9 &&
                        std::all_of(digits.begin(), digits.end(), [](char c) {
                          return std::isdigit(static_cast<unsigned char>(c));
                        });
    if (!number || std::stoull(digits) >= engines)
      throw InputError(arg, 0,
                       "the chain has processors " + prefix + "0.in to " + prefix +
                           std::to_string(engines - 1) + ".in (" + std::to_string(engines) +
                           ", pipeline.engines)");
    if (f.word >= tasks::RayDescription::kWords)
      throw InputError(arg, 0,
                       "a ray description has 13 words (0-2 r0, 3-5 r1 - r0, 6-8 p_r, 9 t, 10 u, "
                       "11 v, 12 the identity)");
    out.push_back({.engine = std::stoull(digits),
                   .word = static_cast<unsigned>(f.word),
                   .xor_mask = f.xor_mask});
  }
  return out;
}

}  // namespace rtsim::platform::ullner_pipeline
