#pragma once
// `rtsim run --sample-error E`: the sample size chosen from a target error. A pilot run, a fork
// of this process so that it gets its own simulation (SystemC allows one a process), simulates
// about ten windows of the frame in detail and renders nothing else; from the spread of its
// windows FrameSample::every_for picks the largest K whose 99.7% interval is expected to be
// within E of the frame time.
#include <nlohmann/json.hpp>
#include <string>

#include "platform/machine.hpp"

namespace rtsim::app {

/// "1%", "0.5 %" or a fraction ("0.01"): the target, in (0, 0.5]. InputError otherwise.
double parse_sample_error(const std::string& text);

struct SamplePlan {
  /// The units of `json`'s numbers (modules/stat_unit.hpp; stats.json `sample.plan`).
  static modules::UnitSchema units();
  int every = 1;                ///< the K chosen (1: the whole frame in detail)
  nlohmann::ordered_json json;  ///< stats.json sample.plan: the target, the pilot and its cost
  double pilot_wall_s = 0.0;
};

/// Runs the pilot (`opts` as the run will be, without outputs) in a forked child and chooses K.
/// `units` is the frame's work units (Machine::sample_units). Throws InputError if the frame has
/// too few windows for a pilot, std::runtime_error if the pilot fails.
SamplePlan plan_sample(const platform::Machine& machine, scenes::Scene& scene,
                       platform::FunctionalTwin& twin, const params::ParamRegistry& registry,
                       const platform::RunOptions& opts, int units, double target);

}  // namespace rtsim::app
