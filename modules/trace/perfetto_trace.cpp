#include "modules/trace/perfetto_trace.hpp"

#include <array>
#include <charconv>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <system_error>

namespace rtsim::modules {

namespace {

/// Picoseconds per microsecond: the file's time unit is the microsecond (the format's), with six
/// decimals so that simulated times keep picosecond resolution (SystemC's default resolution).
constexpr std::uint64_t kPsPerUs = 1'000'000;
constexpr int kUsDecimals = 6;
constexpr double kUsPerSecond = 1e6;

/// Big enough for any finite double in fixed notation with six decimals (1.8e308 has 309 digits).
constexpr std::size_t kNumberBuffer = 400;

void check_time(double value, const char* what) {
  if (!std::isfinite(value) || value < 0.0) {
    throw std::invalid_argument(std::string("PerfettoTrace: ") + what + " must be finite and >= 0");
  }
}

std::string json_number(double value, const char* what) {
  if (!std::isfinite(value)) {
    throw std::invalid_argument(std::string("PerfettoTrace: ") + what + " must be finite");
  }
  std::array<char, kNumberBuffer> buf{};
  // Shortest round-trip form: integers print as integers ("17"), no locale involved.
  const auto r = std::to_chars(buf.data(), buf.data() + buf.size(), value + 0.0);
  return std::string(buf.data(), r.ptr);
}

/// Length of the valid UTF-8 sequence starting at s[i], or 0 if it is not valid (overlong forms,
/// surrogates and code points above U+10FFFF are invalid, RFC 3629).
std::size_t utf8_sequence_length(std::string_view s, std::size_t i) {
  const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(s[k]); };
  const unsigned char c = byte(i);
  std::size_t len = 0;
  unsigned lo = 0x80, hi = 0xBF;  // allowed range of the second byte
  if (c >= 0xC2 && c <= 0xDF) {
    len = 2;
  } else if (c >= 0xE0 && c <= 0xEF) {
    len = 3;
    if (c == 0xE0) lo = 0xA0;  // overlong
    if (c == 0xED) hi = 0x9F;  // surrogates
  } else if (c >= 0xF0 && c <= 0xF4) {
    len = 4;
    if (c == 0xF0) lo = 0x90;  // overlong
    if (c == 0xF4) hi = 0x8F;  // above U+10FFFF
  } else {
    return 0;
  }
  if (i + len > s.size()) return 0;
  if (byte(i + 1) < lo || byte(i + 1) > hi) return 0;
  for (std::size_t k = 2; k < len; ++k) {
    if (byte(i + k) < 0x80 || byte(i + k) > 0xBF) return 0;
  }
  return len;
}

}  // namespace

std::string perfetto_us_from_seconds(double seconds) {
  check_time(seconds, "time");
  std::array<char, kNumberBuffer> buf{};
  // + 0.0 turns -0.0 into +0.0.
  const auto r = std::to_chars(buf.data(), buf.data() + buf.size(), seconds * kUsPerSecond + 0.0,
                               std::chars_format::fixed, kUsDecimals);
  return std::string(buf.data(), r.ptr);
}

std::string perfetto_us_from_ps(std::uint64_t picoseconds) {
  std::string out = std::to_string(picoseconds / kPsPerUs);
  std::string frac = std::to_string(picoseconds % kPsPerUs);
  out += '.';
  out.append(static_cast<std::size_t>(kUsDecimals) - frac.size(), '0');
  out += frac;
  return out;
}

std::string perfetto_json_string(std::string_view s) {
  static constexpr char kHex[] = "0123456789abcdef";
  std::string out;
  out.reserve(s.size() + 2);
  out += '"';
  for (std::size_t i = 0; i < s.size();) {
    const auto c = static_cast<unsigned char>(s[i]);
    if (c < 0x80) {
      switch (c) {
        case '"':
          out += "\\\"";
          break;
        case '\\':
          out += "\\\\";
          break;
        case '\n':
          out += "\\n";
          break;
        case '\r':
          out += "\\r";
          break;
        case '\t':
          out += "\\t";
          break;
        case '\b':
          out += "\\b";
          break;
        case '\f':
          out += "\\f";
          break;
        default:
          if (c < 0x20 || c == 0x7F) {
            out += "\\u00";
            out += kHex[c >> 4];
            out += kHex[c & 0xF];
          } else {
            out += static_cast<char>(c);
          }
      }
      ++i;
      continue;
    }
    const std::size_t len = utf8_sequence_length(s, i);
    if (len == 0) {
      out += "\\ufffd";  // replacement character for a byte that is not valid UTF-8
      ++i;
    } else {
      out.append(s.substr(i, len));
      i += len;
    }
  }
  out += '"';
  return out;
}

namespace {

/// sc_time -> "microseconds.dddddd", exactly when the time resolution is a whole number of
/// picoseconds (SystemC's default is 1 ps), otherwise through seconds.
std::string us_of(const sc_core::sc_time& t) {
  const double res_ps = sc_core::sc_get_time_resolution().to_seconds() * 1e12;
  const double whole = std::round(res_ps);
  if (whole >= 1.0 && std::fabs(res_ps - whole) <= 1e-9 * whole) {
    const auto per_tick = static_cast<std::uint64_t>(whole);
    const std::uint64_t ticks = t.value();
    if (ticks <= std::numeric_limits<std::uint64_t>::max() / per_tick) {
      return perfetto_us_from_ps(ticks * per_tick);
    }
  }
  return perfetto_us_from_seconds(t.to_seconds());
}

}  // namespace

PerfettoTrace::PerfettoTrace(std::filesystem::path path, std::size_t max_events)
    : path_(std::move(path)), max_events_(max_events) {
  partial_path_ = path_;
  partial_path_ += ".partial";
  out_.open(partial_path_, std::ios::binary | std::ios::trunc);
  if (!out_) {
    throw std::runtime_error("cannot write trace file " + partial_path_.string());
  }
  open_ = true;
  out_ << "{\"traceEvents\":[\n";
}

PerfettoTrace::~PerfettoTrace() {
  try {
    close();
  } catch (...) {
    // A destructor must not throw; close() failing leaves the .partial file behind.
  }
}

const PerfettoTrace::Track& PerfettoTrace::track_at(int track) const {
  if (track < 0 || static_cast<std::size_t>(track) >= tracks_.size()) {
    throw std::out_of_range("PerfettoTrace: unknown track " + std::to_string(track));
  }
  return tracks_[static_cast<std::size_t>(track)];
}

int PerfettoTrace::process_sort_index(std::string_view process) {
  std::size_t digits = process.size();
  while (digits > 0 && process[digits - 1] >= '0' && process[digits - 1] <= '9') --digits;
  const std::string_view stem = process.substr(0, digits);
  const std::string_view number = process.substr(digits);
  auto rank = stem_rank_.find(stem);
  if (rank == stem_rank_.end())
    rank = stem_rank_.emplace(std::string(stem), static_cast<int>(stem_rank_.size())).first;
  // Up to 100000 numbered instances a stem; a longer number sorts last among them.
  constexpr int kPerStem = 100000;
  int n = kPerStem - 1;
  if (!number.empty() && number.size() <= 5) n = std::stoi(std::string(number));
  return rank->second * kPerStem + n;
}

int PerfettoTrace::track(std::string_view hierarchical_name) {
  if (auto it = track_of_name_.find(hierarchical_name); it != track_of_name_.end()) {
    return it->second;
  }
  const std::string_view process = hierarchical_name.substr(0, hierarchical_name.find('.'));
  if (process.empty()) {
    throw std::invalid_argument("PerfettoTrace: track name " +
                                perfetto_json_string(hierarchical_name) +
                                " has an empty first segment");
  }
  // pids and tids come from one counter, so no tid equals a pid (a viewer would take a thread
  // whose tid is its pid for the process's main thread).
  const int next_id = static_cast<int>(pid_of_process_.size() + tracks_.size()) + 1;
  int pid = 0;
  if (auto it = pid_of_process_.find(process); it != pid_of_process_.end()) {
    pid = it->second;
  } else {
    pid = next_id;
    pid_of_process_.emplace(std::string(process), pid);
    if (open_) {
      write_metadata("process_name", pid, 0, "name", process, 0);
      write_metadata("process_sort_index", pid, 0, "sort_index", {}, process_sort_index(process));
    }
  }
  const int tid = static_cast<int>(pid_of_process_.size() + tracks_.size()) + 1;
  Track t;
  t.name = std::string(hierarchical_name);
  t.counter_prefix = t.name + ".";
  t.pid = pid;
  t.tid = tid;
  tracks_.push_back(std::move(t));
  const int id = static_cast<int>(tracks_.size()) - 1;
  track_of_name_.emplace(std::string(hierarchical_name), id);
  if (open_) {
    write_metadata("thread_name", pid, tid, "name", hierarchical_name, 0);
    write_metadata("thread_sort_index", pid, tid, "sort_index", {}, tid);
  }
  return id;
}

bool PerfettoTrace::admit(std::string_view ts, bool counter) {
  if (!open_ || (max_events_ != 0 && written_ >= max_events_)) {
    ++dropped_;
    if (counter) {
      ++counters_dropped_;
      return false;
    }
    // Events arrive about in time order, not exactly (temporally decoupled initiators): what the
    // file holds whole is what lies before the earliest event dropped.
    double us = 0.0;
    std::from_chars(ts.data(), ts.data() + ts.size(), us);
    if (us < first_dropped_us_) first_dropped_us_ = us;
    return false;
  }
  ++written_;
  return true;
}

void PerfettoTrace::begin_event() {
  if (!first_event_) out_ << ",\n";
  first_event_ = false;
  // Every 4096 events: has the file passed the size its owner wants to hear of?
  if (size_told_ && (++events_since_size_check_ & 4095) == 0) {
    const auto at = out_.tellp();
    if (at > 0 && static_cast<std::uint64_t>(at) > size_limit_) {
      auto told = std::move(size_told_);
      size_told_ = nullptr;
      told(static_cast<std::uint64_t>(at));
    }
  }
}

void PerfettoTrace::write_common(const Track& t, std::string_view name, char phase,
                                 std::string_view ts) {
  begin_event();
  out_ << "{\"name\":" << perfetto_json_string(name) << ",\"ph\":\"" << phase << "\",\"ts\":" << ts
       << ",\"pid\":" << t.pid << ",\"tid\":" << t.tid;
}

void PerfettoTrace::write_args(std::initializer_list<Arg> args) {
  if (args.size() == 0) return;
  out_ << ",\"args\":{";
  bool first = true;
  for (const Arg& a : args) {
    if (!first) out_ << ',';
    first = false;
    out_ << perfetto_json_string(a.name) << ':' << json_number(a.value, "argument value");
  }
  out_ << '}';
}

void PerfettoTrace::write_metadata(std::string_view what, int pid, int tid, std::string_view key,
                                   std::string_view string_value, long long int_value) {
  begin_event();
  out_ << "{\"name\":\"" << what << "\",\"ph\":\"M\",\"pid\":" << pid << ",\"tid\":" << tid
       << ",\"args\":{\"" << key << "\":";
  if (key == "name") {
    out_ << perfetto_json_string(string_value);
  } else {
    out_ << int_value;
  }
  out_ << "}}";
}

void PerfettoTrace::write_slice(int track, std::string_view name, std::string_view ts,
                                std::string_view dur, std::initializer_list<Arg> args) {
  const Track& t = track_at(track);
  for (const Arg& a : args) json_number(a.value, "argument value");  // validate before counting
  if (!admit(ts)) return;
  write_common(t, name, 'X', ts);
  out_ << ",\"dur\":" << dur;
  write_args(args);
  out_ << '}';
}

void PerfettoTrace::write_instant(int track, std::string_view name, std::string_view ts) {
  const Track& t = track_at(track);
  if (!admit(ts)) return;
  write_common(t, name, 'i', ts);
  out_ << ",\"s\":\"t\"}";
}

void PerfettoTrace::write_counter(int track, std::string_view name, std::string_view ts,
                                  double value) {
  const Track& t = track_at(track);
  const std::string v = json_number(value, "counter value");
  if (!admit(ts, /*counter=*/true)) return;
  scratch_.assign(t.counter_prefix);
  scratch_.append(name);
  write_common(t, scratch_, 'C', ts);
  out_ << ",\"args\":{\"value\":" << v << "}}";
}

void PerfettoTrace::slice(int track, std::string_view name, double start_s, double duration_s) {
  slice(track, name, start_s, duration_s, {});
}

void PerfettoTrace::slice(int track, std::string_view name, double start_s, double duration_s,
                          std::initializer_list<Arg> args) {
  check_time(duration_s, "slice duration");
  write_slice(track, name, perfetto_us_from_seconds(start_s), perfetto_us_from_seconds(duration_s),
              args);
}

void PerfettoTrace::slice(int track, std::string_view name, const sc_core::sc_time& start,
                          const sc_core::sc_time& duration, std::initializer_list<Arg> args) {
  write_slice(track, name, us_of(start), us_of(duration), args);
}

void PerfettoTrace::flow(int track, std::string_view name, std::uint64_t id, FlowPhase phase,
                         const sc_core::sc_time& t) {
  const Track& tr = track_at(track);
  const std::string ts = us_of(t);
  if (!admit(ts)) return;
  write_common(tr, name, static_cast<char>(phase), ts);
  out_ << ",\"cat\":\"flow\",\"id\":" << id << '}';
}

void PerfettoTrace::instant(int track, std::string_view name, double t_s) {
  write_instant(track, name, perfetto_us_from_seconds(t_s));
}

void PerfettoTrace::instant(int track, std::string_view name, const sc_core::sc_time& t) {
  write_instant(track, name, us_of(t));
}

void PerfettoTrace::counter(int track, std::string_view name, double t_s, double value) {
  write_counter(track, name, perfetto_us_from_seconds(t_s), value);
}

void PerfettoTrace::counter(int track, std::string_view name, const sc_core::sc_time& t,
                            double value) {
  write_counter(track, name, us_of(t), value);
}

void PerfettoTrace::other_data(std::string_view key, std::string json_value) {
  other_data_.emplace_back(std::string(key), std::move(json_value));
}

void PerfettoTrace::close() {
  if (!open_) return;
  open_ = false;
  // "otherData" is the format's place for free-form metadata about the trace as a whole.
  out_ << "\n],\n\"displayTimeUnit\":\"ns\",\n\"otherData\":{\"rtsim_events_written\":" << written_
       << ",\"rtsim_events_dropped\":" << dropped_ << ",\"rtsim_max_events\":" << max_events_;
  for (const auto& [key, json] : other_data_)
    out_ << ',' << perfetto_json_string(key) << ':' << json;
  out_ << "}}\n";
  out_.close();
  if (!out_) throw std::runtime_error("error writing trace file " + partial_path_.string());
  std::error_code ec;
  std::filesystem::rename(partial_path_, path_, ec);
  if (ec) {
    throw std::runtime_error("cannot rename " + partial_path_.string() + " to " + path_.string() +
                             ": " + ec.message());
  }
}

void PerfettoTrace::abandon() {
  if (!open_) return;
  open_ = false;
  out_.close();
  std::error_code ec;
  std::filesystem::remove(partial_path_, ec);
}

}  // namespace rtsim::modules
