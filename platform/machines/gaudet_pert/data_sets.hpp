#pragma once
// The control processor's preprocessing (seed 001 L928): the three disjoint data sets of the
// scene (§4.4, L656-L714) as Broadcast Processor memory images, with the ID list laid out in
// the broadcast order asked for (Fig. 6-11, L1019).
#include <cstdint>
#include <vector>

#include "firmware/accel/gaudet_data_sets.hpp"
#include "platform/functional/scene_geometry.hpp"
#include "platform/machines/gaudet_pert/broadcast_mode.hpp"

namespace rtsim::platform::gaudet {

/// One data set as a BP memory holds it.
struct DataSetImage {
  accel::BroadcastImage image;
  std::vector<std::uint32_t> order;         ///< packet IDs in broadcast order
  std::vector<std::uint32_t> memory;        ///< ID list in `order`, then the packets
  std::vector<std::uint32_t> packet_words;  ///< by ID
};

struct PertDataSets {
  DataSetImage shell, prim, shade;
};

/// Depth-first order of the SHELL packets: packet 0, then for each parent shell in it the
/// subtree of its children's packet, recursively (pre-order).
std::vector<std::uint32_t> depth_first_shell_order(const accel::ShellTree& tree);

/// PRIM records of the twin's shapes (spheres; triangles as 3-vertex polygons). Throws
/// std::invalid_argument for a shape the PERT cannot hold.
accel::PrimEncoder shape_prim_encoder(const functional::SceneGeometry& geometry,
                                      const accel::RecordWords& words);

PertDataSets make_pert_data_sets(const accel::ShellTree& tree,
                                 const functional::SceneGeometry& geometry,
                                 const scenes::Scene& scene, const accel::RecordWords& words,
                                 BroadcastOrder order, std::uint64_t seed);

}  // namespace rtsim::platform::gaudet
