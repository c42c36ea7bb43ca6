#pragma once
// Every figure `rtsim validate` knows. Each figures file registers what it adds to the plan
// beside its machine's name, so a new machine's figures need no edit elsewhere:
//
//   void add_v4(Plan& plan, const PlanOptions& options) { ... plan.figures.push_back(...); }
//   const RegisterFigures kRegistered(kUllnerMachine, add_ullner_figures);
//
// The plan holds them by machine name, and within a machine in the order its file registers
// them (a file's static objects are built in the order they are written).
#include <string>

#include "platform/validation/validation.hpp"

namespace rtsim::validation {

/// Adds one figure (or a group that shares its runs) and the runs it reads to the plan.
using AddFigures = void (*)(Plan& plan, const PlanOptions& options);

/// Registers `add` for `machine` when the program starts: one static object beside it.
struct RegisterFigures {
  RegisterFigures(std::string machine, AddFigures add);
};

/// Every registered figure, with its runs and artifacts.
Plan make_validation_plan(const PlanOptions& options);

}  // namespace rtsim::validation
