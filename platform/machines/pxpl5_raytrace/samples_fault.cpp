#include "platform/machines/pxpl5_raytrace/samples_fault.hpp"

#include "firmware/shading/pixel_accumulator.hpp"
#include "modules/module_params.hpp"

namespace rtsim::platform::pxpl5 {

namespace {

const modules::IntParam kCorruptSamples(
    {.name = "fault.corrupt_samples",
     .default_value = "0",
     .min = "0",
     .max = "1000000000000",
     .unit = "messages",
     .description = "A fault for tests: the samples message with this number (counted over all "
                    "casters from 1) has its first sample changed on the ring; 0 changes none",
     .source = "test setting: fault injection, not a machine property",
     .affects_image = true});

}  // namespace

void SamplesFault::declare_params(params::ParamRegistry& r) {
  modules::ParamDecls(r, "", false).add(kCorruptSamples);
}

SamplesFault::SamplesFault(const params::ParamRegistry& r)
    : target_(static_cast<std::uint64_t>(modules::ModuleParams(r, "").get(kCorruptSamples))) {}

void SamplesFault::on_send(Message& m, int spp) {
  if (++messages_ != target_ || m.samples.empty()) return;
  // The first sample turns black, or white if it was black.
  auto& sum = m.samples.front().sum;
  const bool black = sum[0] == 0 && sum[1] == 0 && sum[2] == 0;
  const std::int64_t v =
      black ? static_cast<std::int64_t>(shading::PixelAccumulator::kScale) * spp : 0;
  sum = {v, v, v};
}

}  // namespace rtsim::platform::pxpl5
