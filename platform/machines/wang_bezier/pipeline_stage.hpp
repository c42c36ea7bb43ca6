#pragma once
// A stage of the Bezier pipeline (Fig. 10, L280-L288) as a module: stage 0 (PlaneGenerator and
// the first four-way split) or one of the N identical loop stages, each the chain of its
// substages (Table 4). A stage is its substages and nothing more: the job passes from one to the
// next inside it, and from its last to the next stage's first.
#include <memory>
#include <string>
#include <systemc>
#include <vector>

#include "platform/machines/wang_bezier/substage.hpp"

namespace rtsim::platform::wang_bezier {

/// A substage to build: its name in the stage, its work, its pool and its timing.
struct SubstageSpec {
  std::string name;
  SubstageWork work;
  Substage::Pool pool;
  Substage::Timing timing;
};

class PipelineStage : public sc_core::sc_module {
 public:
  /// Its substages, in the order a job passes them (made here, so they are its children).
  PipelineStage(const sc_core::sc_module_name& name, const std::vector<SubstageSpec>& specs,
                const Substage::Shared& shared)
      : sc_core::sc_module(name) {
    for (const SubstageSpec& s : specs)
      substages_.push_back(
          std::make_unique<Substage>(s.name.c_str(), s.work, s.pool, s.timing, shared));
  }
  const std::vector<std::unique_ptr<Substage>>& substages() const { return substages_; }

 private:
  std::vector<std::unique_ptr<Substage>> substages_;
};

}  // namespace rtsim::platform::wang_bezier
