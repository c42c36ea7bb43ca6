#pragma once
// Transaction traces in the Chrome "Trace Event Format" (JSON), which ui.perfetto.dev and
// chrome://tracing open:
//   {"traceEvents":[ ...events... ],"displayTimeUnit":"ns","otherData":{...}}
//
// - Events are streamed to disk as they arrive; memory does not grow with the event count
//   (only with the number of tracks).
// - One track per module. The first segment of a SystemC hierarchical name ("peripheral" of
//   "peripheral.pipeline") is a process (pid) and the full name a thread (tid) of it, so the
//   module hierarchy shows as nested tracks. Both get name and sort-index metadata events
//   ("ph":"M"), so the tracks appear in the order they were created.
// - Times are simulated seconds (double) or sc_core::sc_time; the file holds microseconds with
//   six decimals (picoseconds), as JSON numbers. sc_time values are written exactly.
// - Every event is written unless `max_events` is not 0: then at most that many
//   slice/instant/counter events are written and later ones are counted and dropped. Metadata
//   events do not count. close() writes the counts into "otherData"
//   ({"rtsim_events_written":N,"rtsim_events_dropped":D,"rtsim_max_events":M}, M = 0: no limit),
//   with whatever other_data() added.
// - The file is written as PATH.partial and renamed to PATH by close() (also from the
//   destructor); abandon() deletes it instead, so a failed run leaves no half-written trace.
// - Deterministic: the same calls give the same bytes (no wall-clock stamps, locale-free
//   number formatting). Events may be out of time order (temporally decoupled initiators); the
//   format allows it and the viewers sort.
// Used by every machine (MachineTrace).
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <functional>
#include <initializer_list>
#include <limits>
#include <map>
#include <string>
#include <string_view>
#include <systemc>
#include <type_traits>
#include <utility>
#include <vector>

namespace rtsim::modules {

class PerfettoTrace {
 public:
  /// A numeric argument shown with a slice (e.g. {"ray", 17}, {"polygons", 1000}).
  /// Any arithmetic value is accepted ({"ray", i} with an int i): the format stores numbers as
  /// doubles anyway.
  struct Arg {
    template <typename Number>
    requires std::is_arithmetic_v<Number> Arg(std::string_view n, Number v)
        : name(n), value(static_cast<double>(v)) {}
    std::string_view name;
    double value;
  };

  /// Opens PATH.partial for writing (throws std::runtime_error naming the path if it cannot).
  /// max_events 0: no limit.
  PerfettoTrace(std::filesystem::path path, std::size_t max_events);
  ~PerfettoTrace();
  PerfettoTrace(const PerfettoTrace&) = delete;
  PerfettoTrace& operator=(const PerfettoTrace&) = delete;

  /// The track of a module by its hierarchical name; creates it (and its process) on first use,
  /// returns the same id afterwards. Ids are 0, 1, 2, ... in creation order. An empty name or a
  /// name with an empty first segment is std::invalid_argument.
  int track(std::string_view hierarchical_name);

  /// A complete event ("ph":"X") on `track`: `name` from start_s for duration_s seconds.
  /// Non-finite or negative times/durations are std::invalid_argument, an unknown track
  /// std::out_of_range (programming errors, not input errors).
  void slice(int track, std::string_view name, double start_s, double duration_s);
  void slice(int track, std::string_view name, double start_s, double duration_s,
             std::initializer_list<Arg> args);
  void slice(int track, std::string_view name, const sc_core::sc_time& start,
             const sc_core::sc_time& duration, std::initializer_list<Arg> args = {});

  /// A flow event ("ph":"s" starts flow `id`, "t" steps it) at `t` on `track`, category "flow":
  /// the viewers bind it to the slice of the track that encloses `t` (emit it at a slice's start)
  /// and draw an arrow from each event of a flow to the next. Ids are the caller's (a message's).
  enum class FlowPhase : char { kStart = 's', kStep = 't' };
  void flow(int track, std::string_view name, std::uint64_t id, FlowPhase phase,
            const sc_core::sc_time& t);
  /// An instant event ("ph":"i", thread scope) at t_s.
  void instant(int track, std::string_view name, double t_s);
  void instant(int track, std::string_view name, const sc_core::sc_time& t);

  /// A counter sample ("ph":"C"), e.g. a queue depth. Counters belong to the track's process in
  /// the format, so the counter is named "<track name>.<name>" to keep modules apart; the value
  /// is the argument "value".
  void counter(int track, std::string_view name, double t_s, double value);
  void counter(int track, std::string_view name, const sc_core::sc_time& t, double value);

  /// A key of "otherData", written by close(): `json_value` is JSON text (not checked).
  void other_data(std::string_view key, std::string json_value);

  /// Writes the end of the file and renames it to its final path. Idempotent.
  void close();
  /// Closes and deletes the partial file instead (a failed run). Idempotent; no-op after close().
  void abandon();

  bool is_open() const { return open_; }
  const std::filesystem::path& path() const { return path_; }
  std::size_t max_events() const { return max_events_; }
  std::size_t events_written() const { return written_; }  ///< excluding metadata
  std::size_t events_dropped() const { return dropped_; }
  /// The earliest time (simulated seconds) of a slice, instant or flow event the cap dropped: the
  /// trace holds every one before it. Infinity when none was dropped. (Counters are written after
  /// the simulation, so a cap reached during it drops them all: counted apart.)
  double first_dropped_s() const { return first_dropped_us_ * 1e-6; }
  /// Calls `told(bytes)` once, while events are written, when the file has passed `bytes`.
  void on_size(std::uint64_t bytes, std::function<void(std::uint64_t)> told) {
    size_limit_ = bytes;
    size_told_ = std::move(told);
  }
  /// The counter events the cap dropped.
  std::size_t counters_dropped() const { return counters_dropped_; }
  /// Number of tracks created so far.
  std::size_t track_count() const { return tracks_.size(); }

 private:
  struct Track {
    std::string name;
    std::string counter_prefix;  ///< name + "."
    int pid = 0;
    int tid = 0;
  };

  const Track& track_at(int track) const;
  /// Counts the event at `ts` (µs, as written), a counter's or another; false when it must be
  /// dropped.
  bool admit(std::string_view ts, bool counter = false);
  void begin_event();
  void write_common(const Track& t, std::string_view name, char phase, std::string_view ts);
  void write_args(std::initializer_list<Arg> args);
  void write_slice(int track, std::string_view name, std::string_view ts, std::string_view dur,
                   std::initializer_list<Arg> args);
  void write_instant(int track, std::string_view name, std::string_view ts);
  void write_counter(int track, std::string_view name, std::string_view ts, double value);
  void write_metadata(std::string_view what, int pid, int tid, std::string_view key,
                      std::string_view string_value, long long int_value);

  std::filesystem::path path_;
  std::filesystem::path partial_path_;
  std::ofstream out_;
  std::size_t max_events_;
  std::size_t written_ = 0;
  std::size_t dropped_ = 0;
  double first_dropped_us_ = std::numeric_limits<double>::infinity();
  std::size_t counters_dropped_ = 0;
  std::uint64_t size_limit_ = 0;  ///< on_size: 0 for none
  std::function<void(std::uint64_t)> size_told_;
  std::uint64_t events_since_size_check_ = 0;
  bool first_event_ = true;
  bool open_ = false;
  std::vector<Track> tracks_;
  std::map<std::string, int, std::less<>> track_of_name_;
  std::map<std::string, int, std::less<>> pid_of_process_;
  /// Process names without their trailing number ("pert" of "pert11"), by first appearance.
  std::map<std::string, int, std::less<>> stem_rank_;
  /// Where a process sorts in the viewer: by its stem's first appearance, then its number, so
  /// pert0, pert1, ..., pert11 read in order whatever order they were created in.
  int process_sort_index(std::string_view process);
  std::string scratch_;
  std::vector<std::pair<std::string, std::string>> other_data_;
};

/// Time formatting used by PerfettoTrace, exposed for tests: seconds -> microseconds with six
/// decimals ("1.500000" for 1.5e-6 s); integer picoseconds -> the same, exactly.
std::string perfetto_us_from_seconds(double seconds);
std::string perfetto_us_from_ps(std::uint64_t picoseconds);
/// JSON string escaping (quotes included); invalid UTF-8 bytes become U+FFFD.
std::string perfetto_json_string(std::string_view s);

}  // namespace rtsim::modules
