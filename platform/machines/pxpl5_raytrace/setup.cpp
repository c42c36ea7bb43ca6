// The by-pass code's parameter, named once.
#include "platform/machines/pxpl5_raytrace/setup.hpp"

#include "modules/module_params.hpp"

namespace rtsim::platform::pxpl5 {

namespace {

const modules::ChoiceParam kBypass(
    {.name = "bypass",
     .default_value = "none",
     .allowed = {"none", "all", "all-but-master", "casters-and-master"},
     .description =
         "By-pass code: nodes that keep their message passing and drop their compute, to "
         "measure each part's greatest rate: all (the pipeline's, Fig. 4), all-but-master (the "
         "master GP's, Fig. 5), casters-and-master (the compositing, resampling and display back "
         "end's, Fig. 6). A by-passed caster sends samples of no radiance: the image is black",
     .source = "seed 004 L333-L350",
     .affects_image = true});

}  // namespace

void Bypass::declare_params(params::ParamRegistry& r) {
  modules::ParamDecls(r, "", false).add(kBypass);
}

Bypass Bypass::read(const params::ParamRegistry& r) {
  Bypass b;
  b.code = modules::ModuleParams(r, "").get(kBypass);
  b.casters = b.code != "none";
  b.master = b.code == "all" || b.code == "casters-and-master";
  b.back_end = b.code == "all" || b.code == "all-but-master";
  return b;
}

}  // namespace rtsim::platform::pxpl5
