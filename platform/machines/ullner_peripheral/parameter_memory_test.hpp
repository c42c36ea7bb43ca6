#pragma once
// The intersection pipeline's test of one polygon (seed 000 Fig. 2-12, L480-L546) on the words
// the fetch stage read out of the parameter memories: line k holds polygon k's twenty parameters,
// pole thresholds and flags as the host loaded them (firmware/kernels/ullner_quad_words.hpp).
// The hit's shading normal is interpolated by the host from its own copy of the corner normals
// (seed 000 L452-L456); everything the pipe decides -- t, u, v and their validity bits, the
// geometric normal n_p -- comes from the words. A corrupted word changes the image.
//
// The words are widened to double once per line, not once per test: the decoded lines are a
// copy of what the memories hold, rebuilt whenever anything was written to them (the host's
// load, a fault), like the 640 bits the fetch stage latches (L891). Decoding at every test cost
// +40% of the brute-force peripheral's run time for nothing the model needs.
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
      : memory_(memory) {
    // Each slot's host copy by pointer, in a compact array: a candidate's test then touches
    // its decoded line only, not the (large) shape record, until it hits (the corner normals).
    host_copies_.reserve(geometry.shapes.size());
    for (const auto& shape : geometry.shapes)
      host_copies_.push_back(std::get_if<kernels::UllnerQuadKernel>(&shape.shape));
  }

  bool test(std::uint32_t slot, const Ray& ray, double t_min, double t_max, SurfaceHit& out,
            TraceCounters& counters) const override {
    ++counters.intersection_tests;
    counters.cost += kernels::UllnerQuadKernel::kTestCost;
    if (memory_.words_written() != decoded_after_) decode();
    return host_copies_[slot]->intersect_with(decoded_[slot], ray, t_min, t_max, out);
  }

 private:
  /// Widens every line of the memories as they are now.
  void decode() const {
    const auto& words = memory_.contents();
    const std::size_t lines = words.size() / kernels::kUllnerStoredWords;
    decoded_.resize(lines);
    for (std::size_t k = 0; k < lines; ++k)
      decoded_[k] = kernels::load_words(std::span<const std::uint32_t, kernels::kUllnerStoredWords>(
          words.data() + k * kernels::kUllnerStoredWords, kernels::kUllnerStoredWords));
    decoded_after_ = memory_.words_written();
  }

  const modules::Memory& memory_;
  mutable std::vector<kernels::UllnerQuadParams<double>> decoded_;
  /// words_written() when decoded_ was made (none yet: every count differs from this).
  mutable std::uint64_t decoded_after_ = ~std::uint64_t{0};
  std::vector<const kernels::UllnerQuadKernel*> host_copies_;  ///< by slot
};

}  // namespace rtsim::platform::ullner
