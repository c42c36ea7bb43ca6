#pragma once
// Pieces every machine model shares.
#include <vector>

#include "modules/memory.hpp"
#include "platform/machine.hpp"

namespace rtsim::platform {

/// Converts the scene with the functional renderer's geometry conversion and builds its tracer.
FunctionalTwin make_functional_twin(scenes::Scene& scene, const functional::RenderSettings& s);

/// Ullner's machines intersect convex quadrilaterals only (seed 000 L267): an InputError naming
/// the first sphere, cone or patch of `scene` otherwise.
void require_polygons(const std::string& machine, const scenes::Scene& scene);

/// A machine whose data sets would be empty without a primitive (its packets, its processors'
/// memories) refuses a scene in which every primitive was rejected as degenerate: an InputError
/// naming how many were rejected and the first reason. `rtsim render` and vax-750 draw such a
/// scene as an empty image.
void require_surviving_primitives(const std::string& machine, const scenes::Scene& scene,
                                  const FunctionalTwin& twin, const std::string& what_is_empty);

/// Sets the global TLM quantum from the parameter `quantum`. Call before building modules.
void begin_simulation(const params::ParamRegistry& registry);
/// Declares `quantum`, the TLM global quantum begin_simulation sets (every machine's).
void declare_quantum_param(params::ParamRegistry& registry);

/// Elaboration: injects `faults` into the named ones of `memories` (the memories whose words
/// the machine's answers are computed from). A fault naming another memory, or a word past the
/// memory's end, is an InputError ("--fault ..."): nothing has run yet.
/// `in_flight`: the names of the machine's points that corrupt words in flight (not memories),
/// offered with the memories when a name is unknown.
void inject_faults(const std::string& machine, const std::vector<MemoryFault>& faults,
                   const std::vector<modules::Memory*>& memories,
                   const std::vector<std::string>& in_flight = {});
/// The faults of `faults` whose name `in_flight` accepts (a point where messages are corrupted on
/// their way, not a memory at rest), taken out of `faults` in order; the rest stay for
/// inject_faults.
template <class Accepts>
std::vector<MemoryFault> take_faults(std::vector<MemoryFault>& faults, Accepts in_flight) {
  std::vector<MemoryFault> taken;
  std::erase_if(faults, [&](const MemoryFault& f) {
    if (!in_flight(f.memory)) return false;
    taken.push_back(f);
    return true;
  });
  return taken;
}
/// stats.json `faults`: [{memory, word, xor_mask, applied}] (empty: none injected).
nlohmann::ordered_json faults_json(const std::vector<modules::Memory*>& memories);
/// The units of faults_json's numbers (modules/stat_unit.hpp; stats.json `faults`).
modules::UnitSchema faults_units();

}  // namespace rtsim::platform
