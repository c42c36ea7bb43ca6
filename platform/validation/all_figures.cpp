#include "platform/validation/all_figures.hpp"

#include "platform/validation/array_figures.hpp"
#include "platform/validation/gaudet_figures.hpp"
#include "platform/validation/pipeline_figures.hpp"
#include "platform/validation/pxpl5_figures.hpp"
#include "platform/validation/ullner_figures.hpp"
#include "platform/validation/vax_figures.hpp"
#include "platform/validation/wang_figures.hpp"

namespace rtsim::validation {

Plan make_validation_plan(const PlanOptions& options) {
  Plan plan;
  add_ullner_figures(plan, options);
  add_vax_figures(plan, options);
  add_gaudet_figures(plan, options);
  add_pipeline_figures(plan, options);
  add_array_figures(plan, options);
  add_wang_figures(plan, options);
  add_pxpl5_figures(plan, options);
  return plan;
}

}  // namespace rtsim::validation
