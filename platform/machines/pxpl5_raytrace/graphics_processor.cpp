#include "platform/machines/pxpl5_raytrace/graphics_processor.hpp"

#include "common/input_error.hpp"
#include "modules/module_params.hpp"

namespace rtsim::platform::pxpl5 {

namespace {

/// Where they are declared and read.
const char* const kPath = "gp";

const modules::DataSizeParam kMemory(
    {.name = "memory",
     .default_value = "8 MiB",
     .min = "1 B",
     .description = "Local memory of each GP; a ray caster must hold the whole scene",
     .source = "seed 004 L282",
     .affects_image = true});
const modules::CountParam kBytesPerPrimitive(
    {.name = "scene_bytes_per_primitive",
     .default_value = "256",
     .min = "1",
     .max = "1000000",
     .unit = "bytes",
     .description = "Memory a ray caster's copy of the scene takes per primitive (its kernel's "
                    "parameters, material and its share of the acceleration structure)",
     .source = "assumption: a triangle's or sphere's precomputed kernel and its grid references",
     .affects_image = true});

}  // namespace

void declare_gp_params(params::ParamRegistry& r) {
  const modules::ParamDecls gp(r, kPath, false);
  modules::declare_processor_params(
      gp, {.clock = "40 MHz",
           .fp_add = 1,
           .fp_mul = 1,
           .fp_div = 20,
           .fp_sqrt = 20,
           .mem_word = 1,
           .instruction = 1,
           .source = "assumption: the seed names the i860 only (L282); a 40 MHz i860 XR issuing "
                     "an add or multiply a cycle, divides and square roots by Newton "
                     "iterations"});
  gp.add(kMemory);
  gp.add(kBytesPerPrimitive);
}

modules::ProcessorTiming read_gp_timing(const params::ParamRegistry& r) {
  return modules::read_processor_timing(modules::ModuleParams(r, kPath));
}

void check_scene_fits(const std::string& scene, std::size_t primitives,
                      const params::ParamRegistry& r) {
  const modules::ModuleParams gp(r, kPath);
  const double bytes =
      static_cast<double>(primitives) * static_cast<double>(gp.get(kBytesPerPrimitive));
  const double memory = gp.get(kMemory).bytes();
  if (bytes > memory)
    throw InputError(scene, 0,
                     "pxpl5-raytrace: the scene's " + std::to_string(primitives) +
                         " primitives take " + std::to_string(static_cast<long long>(bytes)) +
                         " bytes on a ray caster (" + gp.path_of(kBytesPerPrimitive.name()) +
                         ") but a GP has " + std::to_string(static_cast<long long>(memory)) + " (" +
                         gp.path_of(kMemory.name()) +
                         "): the scene cannot be replicated, and splitting it into slabs (L310) is "
                         "not modelled");
}

}  // namespace rtsim::platform::pxpl5
