#include "platform/machines/gaudet_pert/data_sets.hpp"

#include <numeric>
#include <stdexcept>

#include "common/splitmix64.hpp"

namespace rtsim::platform::gaudet {
namespace {

void depth_first(const accel::ShellTree& tree, std::uint32_t packet,
                 std::vector<std::uint32_t>& out) {
  out.push_back(packet);
  for (const accel::Shell& s : tree.shell_packet(packet))
    if (!s.leaf) depth_first(tree, s.child_index, out);
}

DataSetImage lay_out(accel::BroadcastImage image, std::vector<std::uint32_t> order) {
  DataSetImage d;
  d.order = std::move(order);
  const auto ids = image.id_list();
  const std::uint32_t e = image.id_list_entry_words();
  const auto mem = image.memory();
  d.memory.assign(mem.begin(), mem.end());
  // The ID list in broadcast order; packets stay where they are (their addresses are in it).
  for (std::size_t i = 0; i < d.order.size(); ++i) {
    const accel::IdListEntry& entry = ids[d.order[i]];
    d.memory[i * e + 0] = entry.id;
    d.memory[i * e + 1] = entry.address;
    d.memory[i * e + 2] = entry.size_words;
    for (std::uint32_t k = 3; k < e; ++k) d.memory[i * e + k] = 0;
  }
  for (const auto& entry : ids) d.packet_words.push_back(entry.size_words);
  d.image = std::move(image);
  return d;
}

std::vector<std::uint32_t> id_order(std::size_t n) {
  std::vector<std::uint32_t> v(n);
  std::iota(v.begin(), v.end(), 0u);
  return v;
}

/// Fisher-Yates with splitmix64: the same seed gives the same order everywhere.
void shuffle(std::vector<std::uint32_t>& v, std::uint64_t seed) {
  SplitMix64 rng(seed);
  for (std::size_t i = v.size(); i > 1; --i) {
    const std::size_t j = static_cast<std::size_t>(rng.next() % i);
    std::swap(v[i - 1], v[j]);
  }
}

}  // namespace

std::vector<std::uint32_t> depth_first_shell_order(const accel::ShellTree& tree) {
  std::vector<std::uint32_t> out;
  if (tree.shell_packet_count() > 0) depth_first(tree, 0, out);
  return out;
}

accel::PrimEncoder shape_prim_encoder(const functional::SceneGeometry& g,
                                      const accel::RecordWords& words) {
  return [&g, words](std::uint32_t slot, std::vector<std::uint32_t>& out) {
    const functional::ShapeRecord& rec = g.shapes.at(slot);
    if (const auto* s = std::get_if<kernels::SphereKernel>(&rec.shape)) {
      accel::RecordWriter w(out, words.prim_header + words.sphere, "PRIM");
      w.word(slot);
      w.word(rec.material);
      w.word(static_cast<std::uint32_t>(accel::PrimType::Sphere));
      w.coord(s->center());
      w.f32(s->radius());
      w.finish();
    } else if (const auto* t = std::get_if<kernels::TriangleKernel>(&rec.shape)) {
      accel::RecordWriter w(
          out, words.prim_header + words.polygon_fixed + 3 * words.polygon_per_vertex, "PRIM");
      w.word(slot);
      w.word(rec.material);
      w.word(static_cast<std::uint32_t>(accel::PrimType::Polygon));
      w.word(3);
      for (int i = 0; i < 3; ++i) w.coord(t->vertex(i));
      w.finish();
    } else {
      throw std::invalid_argument("a PERT holds spheres and polygons only");
    }
  };
}

PertDataSets make_pert_data_sets(const accel::ShellTree& tree,
                                 const functional::SceneGeometry& geometry,
                                 const scenes::Scene& scene, const accel::RecordWords& words,
                                 BroadcastOrder order, std::uint64_t seed) {
  auto shell = accel::shell_data_set(tree, words);
  auto prim = accel::prim_data_set(tree, shape_prim_encoder(geometry, words), words);
  auto shade = accel::shade_data_set(scene.materials, words);
  // Shell packets are numbered breadth-first (shell_tree.hpp); the PRIM and SHADE arrays are
  // flat, so breadth- and depth-first are both their ID order; random shuffles every set.
  auto shell_order = id_order(shell.packet_count());
  auto prim_order = id_order(prim.packet_count());
  auto shade_order = id_order(shade.packet_count());
  if (order == BroadcastOrder::kDepth) shell_order = depth_first_shell_order(tree);
  if (order == BroadcastOrder::kRandom) {
    shuffle(shell_order, seed);
    shuffle(prim_order, seed + 1);
    shuffle(shade_order, seed + 2);
  }
  return {lay_out(std::move(shell), std::move(shell_order)),
          lay_out(std::move(prim), std::move(prim_order)),
          lay_out(std::move(shade), std::move(shade_order))};
}

}  // namespace rtsim::platform::gaudet
