#pragma once
// The intersection pipeline's test of one polygon (seed 000 Fig. 2-12, L480-L546) on the words
// the fetch stage read out of the parameter memories: line k holds polygon k's twenty parameters,
// pole thresholds and flags as the host loaded them (firmware/kernels/ullner_quad_words.hpp).
// The hit's shading normal is interpolated by the host from its own copy of the corner normals
// (seed 000 L452-L456); everything the pipe decides -- t, u, v and their validity bits, the
// geometric normal n_p -- comes from the words. A corrupted word changes the image.
#include <span>
#include <vector>

#include "firmware/kernels/ullner_quad_words.hpp"
#include "modules/memory.hpp"
#include "platform/functional/candidate_test.hpp"
#include "platform/functional/scene_geometry.hpp"

namespace rtsim::platform::ullner {

class ParameterMemoryTest final : public functional::CandidateTest {
 public:
  /// `memory`: the parameter memories (one line of kUllnerStoredWords per polygon);
  /// `geometry`: the host's copy of the scene, for the corner normals.
  ParameterMemoryTest(const modules::Memory& memory, const functional::SceneGeometry& geometry)
      : memory_(memory), geometry_(geometry) {}

  bool test(std::uint32_t slot, const Ray& ray, double t_min, double t_max, SurfaceHit& out,
            TraceCounters& counters) const override {
    ++counters.intersection_tests;
    counters.cost += kernels::UllnerQuadKernel::kTestCost;
    const auto& host_copy = std::get<kernels::UllnerQuadKernel>(geometry_.shapes[slot].shape);
    const std::span<const std::uint32_t, kernels::kUllnerStoredWords> line(
        memory_.contents().data() + std::size_t{slot} * kernels::kUllnerStoredWords,
        kernels::kUllnerStoredWords);
    return host_copy.intersect_with(kernels::load_words(line), ray, t_min, t_max, out);
  }

 private:
  const modules::Memory& memory_;
  const functional::SceneGeometry& geometry_;
};

}  // namespace rtsim::platform::ullner
