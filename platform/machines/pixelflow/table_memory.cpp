#include "platform/machines/pixelflow/table_memory.hpp"

#include "common/input_error.hpp"
#include "platform/machines/machine_run.hpp"

namespace rtsim::platform::pixelflow {

namespace {
const modules::TimeParam kWriteTime(
    {.name = "write_time",
     .default_value = "760 us",
     .description = "one table write: the regions_per_write regions the node has accepted "
                    "stored into its table-lookup memory (a serial resource: it does not scale "
                    "with the nodes, L160)",
     .source = "derived: seed 004 L126, 8 table writes of a 512 x 512 map take 6.08 ms"});
const modules::DataSizeParam kCapacity(
    {.name = "capacity",
     .default_value = "16 MiB",
     .min = "1 MiB",
     .max = "1 GiB",
     .description = "table-lookup memory a node has: every texture and every map of the frame "
                    "must fit (a frame that does not is refused)",
     .source = "seed 004 L15"});
const modules::CountParam kRegionsPerWrite(
    {.name = "regions_per_write",
     .default_value = "4",
     .min = "1",
     .max = "1024",
     .unit = "regions",
     .description = "regions a table write stores at once (the node accepts this many before "
                    "each store)",
     .source = "seed 004 L122-L124: the hardware stores 4 values at once"});
}  // namespace

void TableMemory::declare_params(const modules::ParamDecls& d) {
  d.add(kCapacity);
  d.add(kWriteTime);
  d.add(kRegionsPerWrite);
}

TableMemory::TableMemory(sc_core::sc_module_name name, MachineRun& run, const PassPlan& plan,
                         std::size_t textures_bytes)
    : modules::Processor(name, run.trace()),
      params_(run.registry(), this->name()),
      in("in", params_.get(kRegionsPerWrite)),
      plan_(plan),
      write_time_(params_.get(kWriteTime)) {
  for (const auto& p : plan.passes) {
    if (p.kind == PassKind::Shadow) maps_.shadow.emplace_back(p.view);
    if (p.kind == PassKind::Reflection) maps_.reflection.emplace(p.view, run.scene().background);
  }
  // Every shader holds every texture and every map (L57): they must fit in its table memory.
  double bytes = static_cast<double>(textures_bytes);
  for (const auto& p : plan.passes) {
    if (p.kind == PassKind::Shadow) bytes += 4.0 * p.view.width * p.view.height;
    if (p.kind == PassKind::Reflection) bytes += 3.0 * p.view.width * p.view.height;
  }
  const double capacity = params_.get(kCapacity).bytes();
  if (bytes > capacity)
    throw InputError(this->name(), 0,
                     "the frame's textures and maps take " +
                         std::to_string(static_cast<long long>(bytes)) +
                         " bytes of table memory, more than a node's " +
                         std::to_string(static_cast<long long>(capacity)) +
                         " (shader.table.capacity; seed 004 L15: 16 MB): lower maps.size or have "
                         "fewer lights");
  shadows_begun_ = maps_.shadow.empty();
  maps_stored_ = plan.map_passes().empty();
  SC_THREAD(run);
}

void TableMemory::run() {
  const std::size_t group = in.fifo.capacity();
  const std::vector<int> maps = plan_.map_passes();
  int shadows_left = static_cast<int>(maps_.shadow.size());
  for (std::size_t m = 0; m < maps.size(); ++m) {
    const Pass& pass = plan_.passes[static_cast<std::size_t>(maps[m])];
    const int regions = pass.grid.count();
    for (int first = 0; first < regions; first += static_cast<int>(group)) {
      const int count = std::min(static_cast<int>(group), regions - first);
      // Accept `count` regions, then store them in one write.
      for (int i = 0; i < count; ++i) {
        const sc_core::sc_time since = clock_.now();
        modules::wait_for_item(in.fifo, clock_);
        sc_core::sc_time taken;
        const TableRegion r = in.fifo.get(clock_.now(), taken);
        clock_.catch_up(taken);
        waited_since(since, Wait::kWork);
        if (r.depths) maps_.shadow[static_cast<std::size_t>(pass.light)].store(*r.depths);
        if (r.colours && maps_.reflection)
          for (int y = 0; y < r.at.height; ++y)
            for (int x = 0; x < r.at.width; ++x) {
              const ColourBytes& c =
                  (*r.colours)[static_cast<std::size_t>(y * raster::kRegionWidth + x)];
              maps_.reflection->set(r.at.x0 + x, r.at.y0 + y, Color(c[0], c[1], c[2]) / 255.0);
            }
        ++regions_;
      }
      const bool last = first + count >= regions;
      if (last && pass.kind == PassKind::Shadow && --shadows_left == 0) {
        clock_.sync();
        shadows_begun_ = true;
        ready_.notify(sc_core::SC_ZERO_TIME);
      }
      compute_for(write_time_, "table write", {{"regions", count}});
      ++writes_;
      if (last) stored_at_.emplace_back(maps[m], clock_.now());
    }
  }
  clock_.sync();
  maps_stored_ = true;
  ready_.notify(sc_core::SC_ZERO_TIME);
}

}  // namespace rtsim::platform::pixelflow
