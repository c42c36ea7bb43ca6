#pragma once
// The subvolumes a broadcast polygon record's bounding box touches (the keep test's first step,
// seed 000 L858), remembered for the last record asked about. The broadcast brings each record
// to every processor in turn and each reads the same words, so the simulator works the cells out
// once a record instead of once a processor. A memo of the simulator's own work, not of the
// machine's: each processor's test is timed as before. It is keyed on the record's words, so a
// record that a fault corrupted on its way (--fault) is worked out afresh.
#include <algorithm>
#include <cstdint>
#include <span>
#include <vector>

#include "firmware/accel/uniform_grid.hpp"
#include "platform/machines/ullner_array/broadcast_record.hpp"

namespace rtsim::platform::ullner_array {

class RecordCells {
 public:
  explicit RecordCells(const accel::UniformGrid& grid) : grid_(grid) {}

  /// grid.cells_touched(polygon_bounds(record), first, last).
  bool touched(std::span<const std::uint32_t> record, accel::CellIndex& first,
               accel::CellIndex& last) {
    if (!known_ || !std::equal(record.begin(), record.end(), words_.begin(), words_.end())) {
      known_ = true;
      words_.assign(record.begin(), record.end());
      touched_ = grid_.cells_touched(polygon_bounds(record), first_, last_);
    }
    first = first_;
    last = last_;
    return touched_;
  }

 private:
  const accel::UniformGrid& grid_;
  std::vector<std::uint32_t> words_;  ///< the record last asked about
  bool known_ = false;                ///< a record has been asked about
  bool touched_ = false;
  accel::CellIndex first_{}, last_{};
};

}  // namespace rtsim::platform::ullner_array
