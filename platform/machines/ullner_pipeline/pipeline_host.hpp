#pragma once
// The host of Ullner's ray-tracing pipeline: the peripheral's host (ullner::Host, the same two
// tasks, seed 000 L715) with what the pipeline asks of it:
//  * it loads the scene by shifting polygon descriptions into the chain, dummies "very far away
//    from the scene model" first for the spare processors (L717-L719);
//  * it keeps many rays in flight (L715): up to host.rays_in_flight, by default each with room
//    reserved for its answer (host.result_slots fewer: the chain can be held up);
//  * it computes the lighting itself: the pipeline "has no provision for assisting with the
//    lighting model computations" (L715).
#include "platform/machines/ullner_peripheral/host.hpp"
#include "platform/machines/ullner_pipeline/polygon_load.hpp"

namespace rtsim::platform::ullner_pipeline {

class PipelineHost final : public ullner::Host {
 public:
  /// Its parameters under `host`: the peripheral host's processor, its window of rays in
  /// flight and where it puts the dummy polygons.
  static void declare_params(const modules::ParamDecls& host);

  /// `attached`: the chain's input register and its first link; `engines`: processors in the
  /// chain (spares get dummies); `description_time`: a polygon description on a link.
  PipelineHost(sc_core::sc_module_name name, MachineRun& run,
               const ullner::HostAttachment& attached, std::uint64_t engines,
               const Bounds& modelling_space);
  /// The window of rays in flight a host with parameters `host` keeps (its attachment's).
  /// Whether it takes waiting answers before making rays (host.answers_first).
  static bool answers_first(const modules::ModuleParams& host);
  /// Its result queue's slots when fewer than the rays in flight, else 0 (host.result_slots).
  static std::uint64_t result_slots(const modules::ModuleParams& host);
  static std::uint64_t rays_in_flight(const modules::ModuleParams& host);

  /// Descriptions the chain shifted back out during the load (its previous contents).
  std::uint64_t returned() const { return returned_; }

  /// The dummy polygon: a square one modelling-space extent wide, `distance` extents from the
  /// space's centre along +z.
  static kernels::UllnerQuadParams<double> dummy(const Bounds& modelling_space, double distance);

 private:
  void load_scene() override;

  std::uint64_t engines_;
  Bounds modelling_space_;
  double dummy_distance_;
  std::uint64_t returned_ = 0;
};

}  // namespace rtsim::platform::ullner_pipeline
