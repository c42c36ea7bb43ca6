#pragma once
// A fault for tests on pxpl5-raytrace (fault.corrupt_samples): the samples message with a given
// number, counted over all casters from 1, has its first sample changed on its way to its
// compositor (black, or white if it was black). The image must change: it is built from what
// crossed the ring.
#include <cstdint>

#include "params/registry.hpp"
#include "platform/machines/pxpl5_raytrace/messages.hpp"

namespace rtsim::platform::pxpl5 {

class SamplesFault {
 public:
  static void declare_params(params::ParamRegistry& r);
  explicit SamplesFault(const params::ParamRegistry& r);

  /// Counts samples message `m` (of `spp` rays a sample) and changes it if it is the one.
  void on_send(Message& m, int spp);
  /// Samples messages the casters sent.
  std::uint64_t messages() const { return messages_; }

 private:
  std::uint64_t target_;  ///< 0: none
  std::uint64_t messages_ = 0;
};

}  // namespace rtsim::platform::pxpl5
