// `rtsim sweep --mpi` over MPI (OpenMPI from Debian), whose calls are in a module loaded by
// --mpi only (app/mpi/mpi_api.hpp); see app/sweep_mpi.hpp for the protocol's shape.
//
// Messages are JSON text in char buffers:
//   worker -> 0  kTagReady   {"slots": J}                    one per free slot: "give me a point"
//   worker -> 0  kTagResult  {"slots": J, "job": i, "outcome": {...}}   a result, and a request
//   0 -> worker  kTagAssign  {"job": i, "key": K, "args": [...], "work_dir": D}
//   0 -> worker  kTagStop    {}                              no more points for that slot
// Every request gets exactly one reply, so a worker is done when it has had J stops.
//
// Only the main thread calls MPI (MPI_THREAD_FUNNELED); threads of a small pool run the `rtsim
// run` processes. Blocking receives in OpenMPI spin a core, and a core here is worth a point:
// the main threads poll (MPI_Iprobe) and wait between polls instead, woken at once when one of
// their own points ends (its result goes out, and the next point starts, without a poll's delay).
#include "app/sweep_mpi.hpp"

#include <chrono>
#include <condition_variable>
#include <cstdlib>
#include <deque>
#include <exception>
#include <filesystem>
#include <mutex>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>
#include <string>
#include <thread>
#include <utility>

#include "app/module_symbol.hpp"
#include "app/mpi/mpi_api.hpp"

namespace rtsim::app::mpi {

namespace {

namespace fs = std::filesystem;
using Json = nlohmann::json;

constexpr int kTagReady = 1;
constexpr int kTagResult = 2;
constexpr int kTagAssign = 3;
constexpr int kTagStop = 4;

// Pause of an idle main thread between polls for messages: short against a point (a tenth of a
// second or more), since a point handed to another rank waits for a poll on both ranks. At this
// interval each rank's main thread of the fig2-18 sweep used about 0.2 s of CPU over its 1.9 s
// (MPI_Init included); 5 ms ran no faster or slower there (docs/sweeps.md).
constexpr auto kPollInterval = std::chrono::milliseconds(1);

constexpr const char* kModule = "librtsim_mpi.so";

/// The module's table, loaded by the first Session. RTLD_GLOBAL: Open MPI's own plugins look
/// for its symbols globally.
const rtsim_mpi_api* load_api(std::string* tried = nullptr) {
  static const rtsim_mpi_api* api = nullptr;
  if (api) return api;
  std::string paths;
  if (auto fn = reinterpret_cast<rtsim_mpi_api_fn>(
          find_module_symbol(kModule, kRtsimMpiApiSymbol, true, paths)))
    api = fn();
  if (tried) *tried = paths;
  return api;
}

const rtsim_mpi_api& api() { return *load_api(); }

void check(int rc, const char* what) {
  if (rc != 0) throw std::runtime_error(std::string("MPI: ") + what + " failed");
}

void send_text(const std::string& text, int dest, int tag) {
  check(api().send_text(text.data(), static_cast<int>(text.size()), dest, tag), "MPI_Send");
}

struct Message {
  int source = 0;
  int tag = 0;
  std::string text;
};

constexpr int kAnySource = -1;

// The next message from `source` (or any), if one has arrived.
std::optional<Message> poll(int source) {
  int arrived = 0, from = 0, tag = 0, size = 0;
  char* data = nullptr;
  check(api().poll_text(source, &arrived, &from, &tag, &data, &size), "MPI_Iprobe/MPI_Recv");
  if (!arrived) return std::nullopt;
  Message m{from, tag, std::string(data, static_cast<std::size_t>(size))};
  std::free(data);
  return m;
}

/// A fixed pool of threads that run requests through the run queue, one process each.
class LocalRunner {
 public:
  LocalRunner(runs::RunQueueOptions options, int slots) : options_(std::move(options)) {
    for (int i = 0; i < slots; ++i) threads_.emplace_back([this] { loop(); });
  }
  ~LocalRunner() {
    {
      std::lock_guard lock(mutex_);
      closing_ = true;
    }
    wake_.notify_all();
    for (auto& t : threads_) t.join();
  }

  void submit(std::size_t job, runs::RunRequest request, fs::path work_dir) {
    {
      std::lock_guard lock(mutex_);
      queue_.push_back({job, std::move(request), std::move(work_dir)});
      ++in_flight_;
    }
    wake_.notify_one();
  }

  /// Requests submitted and not yet taken back by take_finished().
  int in_flight() const {
    std::lock_guard lock(mutex_);
    return in_flight_;
  }

  /// Waits until a request has finished or `timeout` has passed.
  void wait_finished(std::chrono::milliseconds timeout) {
    std::unique_lock lock(mutex_);
    finished_changed_.wait_for(lock, timeout, [this] { return !finished_.empty(); });
  }

  std::vector<std::pair<std::size_t, sweep::PointOutcome>> take_finished() {
    std::lock_guard lock(mutex_);
    std::vector<std::pair<std::size_t, sweep::PointOutcome>> out;
    out.swap(finished_);
    in_flight_ -= static_cast<int>(out.size());
    return out;
  }

 private:
  struct Job {
    std::size_t index;
    runs::RunRequest request;
    fs::path work_dir;
  };

  void loop() {
    for (;;) {
      Job job;
      {
        std::unique_lock lock(mutex_);
        wake_.wait(lock, [this] { return closing_ || !queue_.empty(); });
        if (queue_.empty()) return;
        job = std::move(queue_.front());
        queue_.pop_front();
      }
      runs::RunQueueOptions o = options_;
      o.work_dir = job.work_dir;
      sweep::PointOutcome outcome = sweep::outcome_of(runs::run_request(job.request, o));
      {
        std::lock_guard lock(mutex_);
        finished_.emplace_back(job.index, std::move(outcome));
      }
      finished_changed_.notify_all();
    }
  }

  runs::RunQueueOptions options_;
  mutable std::mutex mutex_;
  std::condition_variable wake_;
  std::condition_variable finished_changed_;
  std::deque<Job> queue_;
  std::vector<std::pair<std::size_t, sweep::PointOutcome>> finished_;
  int in_flight_ = 0;
  bool closing_ = false;
  std::vector<std::thread> threads_;
};

}  // namespace

bool built_with_mpi() { return load_api() != nullptr; }

Session::Session() {
  std::string tried;
  if (!load_api(&tried))
    throw std::runtime_error(
        "this rtsim has no MPI module (" + std::string(kModule) + "; looked for " + tried +
        "): install Debian's libopenmpi-dev and openmpi-bin (scripts/quickstart.sh does) and "
        "re-run cmake");
  check(api().init(&rank_, &size_), "MPI_Init_thread");
}

Session::~Session() {
  // An exception on one rank would leave the others waiting for it forever: end them all.
  api().finish(std::uncaught_exceptions() > 0 ? 1 : 0);
}

int Session::share_status(int status) {
  check(api().bcast_int(&status), "MPI_Bcast");
  return status;
}

void Session::dispatch(
    const std::vector<runs::RunRequest>& requests, const runs::RunQueueOptions& local,
    const std::function<void(std::size_t, const sweep::PointOutcome&)>& on_done) {
  const int local_slots = std::max(1, local.jobs);
  LocalRunner runner(local, local_slots);
  std::size_t next = 0;
  std::size_t finished = 0;
  std::vector<int> slots(static_cast<std::size_t>(size_), 0);  // per rank, from its messages
  std::vector<int> stops(static_cast<std::size_t>(size_), 0);  // stops sent to it

  const auto all_stopped = [&] {
    for (int w = 1; w < size_; ++w)
      if (slots[w] == 0 || stops[w] < slots[w]) return false;
    return true;
  };
  // Interrupted (rtsim sweep's handler stopped the runs): no point is handed out any more; the
  // ones handed out end (stopped) and are reported, every worker is sent its stops.
  std::size_t handed_out = requests.size();
  const auto reply = [&](int worker) {
    if (runs::runs_stopped()) handed_out = std::min(handed_out, next);
    if (next < handed_out) {
      const auto& r = requests[next];
      const Json job = {
          {"job", next}, {"key", r.key}, {"args", r.args}, {"work_dir", local.work_dir.string()}};
      send_text(job.dump(), worker, kTagAssign);
      ++next;
    } else {
      send_text("{}", worker, kTagStop);
      ++stops[worker];
    }
  };

  while (finished < std::min(handed_out, requests.size()) || !all_stopped()) {
    if (runs::runs_stopped()) handed_out = std::min(handed_out, next);
    bool busy = false;
    for (auto& [job, outcome] : runner.take_finished()) {
      on_done(job, outcome);
      ++finished;
      busy = true;
    }
    while (runner.in_flight() < local_slots && next < handed_out) {
      runner.submit(next, requests[next], local.work_dir);
      ++next;
      busy = true;
    }
    while (auto m = poll(kAnySource)) {
      busy = true;
      const Json j = Json::parse(m->text);
      slots[m->source] = j.at("slots").get<int>();
      if (m->tag == kTagResult) {
        on_done(j.at("job").get<std::size_t>(), sweep::PointOutcome::from_json(j.at("outcome")));
        ++finished;
      }
      reply(m->source);
    }
    if (!busy) runner.wait_finished(kPollInterval);
  }
}

void Session::work(const runs::RunQueueOptions& options) {
  const int slots = std::max(1, options.jobs);
  LocalRunner runner(options, slots);
  const std::string ready = Json{{"slots", slots}}.dump();
  for (int s = 0; s < slots; ++s) send_text(ready, 0, kTagReady);
  int stops = 0;
  while (stops < slots) {
    bool busy = false;
    for (auto& [job, outcome] : runner.take_finished()) {
      const Json result = {{"slots", slots}, {"job", job}, {"outcome", outcome.to_json()}};
      send_text(result.dump(), 0, kTagResult);
      busy = true;
    }
    while (auto m = poll(0)) {
      busy = true;
      if (m->tag == kTagStop) {
        ++stops;
        continue;
      }
      const Json j = Json::parse(m->text);
      runs::RunRequest r;
      r.key = j.at("key").get<std::string>();
      r.args = j.at("args").get<std::vector<std::string>>();
      runner.submit(j.at("job").get<std::size_t>(), std::move(r),
                    fs::path(j.at("work_dir").get<std::string>()));
    }
    if (!busy) runner.wait_finished(kPollInterval);
  }
}

}  // namespace rtsim::app::mpi
