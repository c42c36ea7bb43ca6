// `rtsim sweep SWEEP.toml`: every point of a sweep file is one `rtsim run` process, run on the
// local cores (the run queue) or over MPI ranks (--mpi); one results table at the end.
// docs/sweeps.md describes the file, the outputs and resuming.
#include <fcntl.h>
#include <signal.h>
#include <sys/file.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <mutex>
#include <stdexcept>
#include <thread>
#include <unordered_map>

#include "app/cli.hpp"
#include "app/commands.hpp"
#include "app/fork_server.hpp"
#include "app/image_files.hpp"
#include "app/interrupt_cleanup.hpp"
#include "app/mpi_launcher.hpp"
#include "app/output_set.hpp"
#include "app/progress_bar.hpp"
#include "app/sweep_mpi.hpp"
#include "app/sweep_report.hpp"
#include "common/input_error.hpp"
#include "platform/runs/run_queue.hpp"
#include "platform/sweep/image_sharing.hpp"
#include "platform/sweep/point_outcome.hpp"
#include "platform/sweep/results_table.hpp"
#include "platform/sweep/sweep_check.hpp"
#include "platform/sweep/sweep_file.hpp"
#include "platform/sweep/sweep_points.hpp"

namespace rtsim::app {

namespace fs = std::filesystem;

namespace {

// Failed points listed in the summary; the table has them all.
constexpr std::size_t kFailuresShown = 10;

fs::path this_executable() {
  std::error_code ec;
  fs::path p = fs::read_symlink("/proc/self/exe", ec);
  if (ec) throw std::runtime_error("cannot find this program's path (/proc/self/exe)");
  return p;
}

fs::path executable_of(const SweepArgs& args) {
  return args.rtsim.empty() ? this_executable() : fs::absolute(args.rtsim);
}

int default_jobs() { return static_cast<int>(std::max(1u, std::thread::hardware_concurrency())); }

fs::path out_dir_of(const SweepArgs& args) {
  if (!args.out_dir.empty()) return fs::absolute(args.out_dir);
  return fs::absolute(fs::path("out") / "sweeps" / fs::path(args.file).stem());
}

/// The sweep read, checked and expanded; throws InputError before anything is written.
struct Plan {
  sweep::SweepFile file;
  std::vector<sweep::Point> points;
};

/// Without `load_scenes`, the scenes are not loaded to check them (sweep::CheckOptions).
Plan make_plan(const SweepArgs& args, bool load_scenes = true) {
  Plan plan;
  plan.file = sweep::read_sweep_file(args.file);
  plan.points = sweep::expand_points(plan.file);
  sweep::check_sweep(plan.file, plan.points, sweep::CheckOptions{load_scenes});
  sweep::share_images(plan.file, plan.points);
  if (args.baseline >= 0 && !args.report)
    throw InputError("--baseline", 0, "marks a point in report.html: give --report too");
  if (args.baseline >= static_cast<int>(plan.points.size()))
    throw InputError("--baseline " + std::to_string(args.baseline), 0,
                     "no such point: the sweep has points 0 to " +
                         std::to_string(plan.points.size() - 1) + " (--list shows them)");
  return plan;
}

/// What the swept settings of a point are, for messages: "peripheral.grid.divisions=3 ...".
std::string describe_point(const sweep::Point& p) {
  const std::string s = p.swept_text(" ");
  return s.empty() ? "the only point" : s;
}

/// The command as a user would type it again (for the report).
std::string command_line(const SweepArgs& a, const fs::path& out) {
  std::string s = "rtsim sweep " + a.file;
  if (a.mpi) s += " --mpi";
  if (a.jobs > 0) s += " --jobs " + std::to_string(a.jobs);
  if (a.force) s += " --force";
  return s + " --report --out " + out.string();
}

/// The lock a sweep holds on its --out folder while it runs (flock: released when the process
/// ends, however it ends). A second sweep into the same folder is refused.
constexpr const char* kLockName = ".rtsim-sweep.lock";

void lock_output_folder(const fs::path& out) {
  const fs::path path = out / kLockName;
  const int fd = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd < 0) throw InputError("--out " + out.string(), 0, "cannot create " + path.string());
  if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
    std::string holder;
    std::getline(std::ifstream(path), holder);
    ::close(fd);
    throw InputError("--out " + out.string(), 0,
                     "another rtsim sweep is writing into this folder" +
                         (holder.empty() ? std::string() : " (" + holder + ")") +
                         "; wait for it to end, or give another --out");
  }
  // Held until the process ends: the descriptor stays open.
  const std::string who = "pid " + std::to_string(::getpid());
  (void)!::ftruncate(fd, 0);
  (void)!::write(fd, who.data(), who.size());
}

/// The signal that interrupted the sweep (0: none).
std::atomic<int> interrupted_by{0};

int list_points(const Plan& plan, const fs::path& out) {
  for (const auto& p : plan.points) {
    const bool done = sweep::find_done(out / "points" / p.key, p).has_value();
    std::cout << p.key << (done ? "  done  " : "        ") << p.command_line() << "\n";
  }
  return kExitOk;
}

/// Creates `out`/points and takes the folder's lock (another sweep writing into it is an error).
void prepare_output_folder(const fs::path& out, const fs::path& points_dir) {
  check_output_folder(out);
  std::error_code ec;
  fs::create_directories(points_dir, ec);
  if (ec || !fs::is_directory(points_dir, ec))
    throw InputError("--out " + out.string(), 0,
                     "cannot create " + points_dir.string() + ": " +
                         (ec ? ec.message() : std::string("not a folder")));
  lock_output_folder(out);
}

/// The points to run now: every point not done before (all with --force). Request i runs point
/// point_of[i].
struct Pending {
  std::vector<runs::RunRequest> requests;
  std::vector<std::size_t> point_of;
};

/// The pending points, with the outcome of each point done before filled in.
Pending pending_points(const SweepArgs& args, const Plan& plan, const fs::path& points_dir,
                       std::vector<sweep::PointOutcome>& outcomes) {
  Pending pending;
  for (const auto& p : plan.points) {
    if (!args.force) {
      if (auto done = sweep::find_done(points_dir / p.key, p)) {
        outcomes[p.index] = std::move(*done);
        continue;
      }
    }
    runs::RunRequest r;
    r.key = p.key;
    r.args = p.args;
    pending.requests.push_back(std::move(r));
    pending.point_of.push_back(p.index);
  }
  return pending;
}

/// Keeps a point that ran well: its stats.json (a rank without a shared file system wrote it on
/// its own disk), modules.csv (every module instance, for the classes the results table keeps
/// as aggregates) and the marker that lets a re-run skip it. A point that cannot be recorded
/// (a full disk) fails; the sweep goes on.
void record_point(const fs::path& dir, const sweep::Point& p, sweep::PointOutcome& o) {
  if (!o.ok) return;
  try {
    std::error_code ec;
    if (!fs::exists(dir / "stats.json", ec)) {
      fs::create_directories(dir);
      sweep::write_file_atomically(dir / "stats.json", o.stats_text);
    }
    sweep::write_file_atomically(dir / "modules.csv",
                                 sweep::modules_csv(nlohmann::ordered_json::parse(o.stats_text)));
    sweep::write_marker(dir, p, o);
  } catch (const std::exception& e) {
    o.ok = false;
    o.error = std::string("ran, but cannot record it: ") + e.what();
  }
}

/// Runs the pending points `jobs` at a time (forks of this process, another rtsim binary, or
/// the ranks of an MPI session), recording each as it finishes, with a progress bar.
void run_points(const SweepArgs& args, const Plan& plan, const Pending& pending,
                const fs::path& points_dir, int jobs, mpi::Session* session, ForkServers* servers,
                std::vector<sweep::PointOutcome>& outcomes) {
  ProgressBar bar(args.quiet ? std::string() : "sweep",
                  /*lines_when_not_a_terminal=*/!args.quiet);
  std::mutex record_mutex;
  long finished = 0;
  // Called from the queue's threads.
  const auto record = [&](std::size_t request, const sweep::PointOutcome& o) {
    std::lock_guard lock(record_mutex);
    const sweep::Point& p = plan.points[pending.point_of[request]];
    outcomes[p.index] = o;
    record_point(points_dir / p.key, p, outcomes[p.index]);
    if (!args.quiet) bar.update(++finished, static_cast<long>(pending.requests.size()));
  };

  runs::RunQueueOptions q;
  q.executable = executable_of(args);
  q.work_dir = points_dir;
  q.jobs = jobs;
  q.log_in_run_dir = true;
  if (session) {
    // This rank's points are forks of its fork servers, started before MPI.
    if (servers) q.run_and_wait = fork_server_runner(*servers);
    session->dispatch(pending.requests, q, record);
    return;
  }
  std::unordered_map<std::string, std::size_t> request_of_key;  // run_all reports by key
  for (std::size_t i = 0; i < pending.requests.size(); ++i)
    request_of_key[pending.requests[i].key] = i;
  q.on_finished = [&](const runs::RunOutcome& run, int, int) {
    record(request_of_key.at(run.request.key), sweep::outcome_of(run));
  };
  // Points are forks of this process (no program start-up each), unless another rtsim binary
  // was asked for.
  if (args.rtsim.empty()) {
    q.in_process = run_cli_in_forked_child;
    // Once here, not in every point, if a point writes an image.
    if (std::any_of(pending.requests.begin(), pending.requests.end(),
                    [](const runs::RunRequest& r) { return writes_image(r.args); }))
      preload_image_module();
  }
  (void)runs::run_all(pending.requests, q);
}

/// What execute() tells the user at the end.
struct SweepEnd {
  std::size_t points = 0, failed = 0, reused = 0;
  double wall_s = 0.0;
  std::string report_error;  ///< report.html could not be written
};

/// Writes report.html over every point of the table, run now or before, failed or not; the
/// error text if it cannot.
std::string write_report(const SweepArgs& args, const Plan& plan, const fs::path& out,
                         const std::vector<sweep::PointOutcome>& outcomes,
                         const sweep::ResultsTable& table, const SweepEnd& end, std::size_t run_now,
                         mpi::Session* session) {
  try {
    OutputSet set(out);
    SweepReportInputs in;
    in.file = &plan.file;
    in.points = &plan.points;
    in.outcomes = &outcomes;
    in.table = &table;
    in.results_jsonl = out / "results.jsonl";
    in.points_dir = out / "points";
    in.command_line = command_line(args, out);
    in.wall_s = end.wall_s;
    in.run_now = run_now;
    in.ranks = session ? session->size() : 0;
    if (args.baseline >= 0) in.baseline = static_cast<std::size_t>(args.baseline);
    ReportTools tools;
    tools.scratch_dir = set.staged_path(".report-plots");
    // The plots take seconds (a Python each): the bar says the report is being made.
    ProgressBar bar(args.quiet ? std::string() : "report plots");
    in.progress = [&bar](std::size_t done, std::size_t total) {
      bar.update(static_cast<long>(done), static_cast<long>(total));
    };
    write_sweep_report(in, set.stage("report.html"), tools);
    bar.finish();
    set.commit();
    return {};
  } catch (const std::exception& e) {
    return e.what();
  }
}

/// The closing lines: how many points are ok, the failed ones (the first kFailuresShown) and
/// where the outputs are.
void print_summary(const SweepArgs& args, const Plan& plan, const fs::path& out,
                   const std::vector<sweep::PointOutcome>& outcomes, const SweepEnd& end) {
  const std::size_t n = end.points;
  std::cout << "rtsim sweep: " << n << (n == 1 ? " point: " : " points: ") << n - end.failed
            << " ok (" << end.reused << " done before), " << end.failed << " failed; " << end.wall_s
            << " s wall\n";
  std::size_t shown = 0;
  for (const auto& p : plan.points) {
    const auto& o = outcomes[p.index];
    if (o.ok) continue;
    if (shown++ == kFailuresShown) {
      std::cout << "  ... and " << end.failed - kFailuresShown << " more (results.csv has all)\n";
      break;
    }
    std::cout << "  failed  point " << p.key << " (" << describe_point(p) << "): " << o.error
              << "\n";
  }
  std::cout << "  table  " << (out / "results.csv").string() << "  "
            << (out / "results.jsonl").string() << "\n"
            << "  points " << (out / "points").string() << "/NNNN/ (stats.json, images, run.log)\n";
  if (args.report && end.report_error.empty())
    std::cout << "  report " << (out / "report.html").string() << "\n";
}

/// Runs the sweep (rank 0 under MPI): resume, run, table, summary.
int execute(const SweepArgs& args, const Plan& plan, mpi::Session* session, ForkServers* servers) {
  const fs::path out = out_dir_of(args);
  const fs::path points_dir = out / "points";
  SweepEnd end;
  end.points = plan.points.size();
  prepare_output_folder(out, points_dir);

  std::vector<sweep::PointOutcome> outcomes(end.points);
  const Pending pending = pending_points(args, plan, points_dir, outcomes);
  end.reused = end.points - pending.requests.size();
  const int jobs = args.jobs > 0 ? args.jobs : (session ? 1 : default_jobs());
  if (!args.quiet) {
    std::cout << "rtsim sweep: " << (plan.file.name.empty() ? args.file : plan.file.name) << ": "
              << end.points << (end.points == 1 ? " point, " : " points, ")
              << pending.requests.size() << " to run (" << end.reused << " done before), ";
    if (session)
      std::cout << session->size() << " MPI ranks, " << jobs << " at a time on each";
    else
      std::cout << jobs << " at a time";
    std::cout << "\n  out  " << out.string() << "\n";
    const auto sharing = std::count_if(plan.points.begin(), plan.points.end(),
                                       [](const sweep::Point& p) { return p.image_from; });
    if (sharing > 0)
      std::cout << "  images  " << sharing << " of the points differ from an earlier one only in "
                << "what the image does not depend on: they run timing-only and get its image "
                   "(share-images = false renders every point's)\n";
    std::cout << std::flush;
  }

  // Ctrl-C, SIGTERM, SIGHUP: the running points are stopped (each removes its partial
  // outputs), no new one starts, and the table of what is done is written below.
  set_interrupt_handler([](int sig) {
    interrupted_by.store(sig);
    const std::string message = std::string("\nrtsim sweep: interrupted (") + sigabbrev_np(sig) +
                                "): stopping the running points\n";
    (void)!::write(STDERR_FILENO, message.data(), message.size());
    runs::stop_runs(SIGTERM);
  });
  const auto start = std::chrono::steady_clock::now();
  run_points(args, plan, pending, points_dir, jobs, session, servers, outcomes);
  end.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  {
    std::vector<bool> ok(outcomes.size());
    for (std::size_t i = 0; i < outcomes.size(); ++i) ok[i] = outcomes[i].ok;
    if (const std::size_t unfilled = sweep::fill_shared_images(plan.points, points_dir, ok))
      std::cerr << "rtsim sweep: warning: " << unfilled
                << " point folder(s) have no image: the point that rendered the image they share "
                   "failed, or its folder is not on this machine, or the disk is full (their "
                   "results are unaffected; share-images = false renders every point's)\n";
  }
  const int interrupted = interrupted_by.load();
  if (interrupted != 0) {
    // What was stopped or never started is not a failure of the point: it is still to run.
    for (const std::size_t i : pending.point_of)
      if (!outcomes[i].ok) {
        outcomes[i].interrupted = true;
        outcomes[i].error = "interrupted: not run to the end";
      }
  }

  const auto table = sweep::make_results_table(plan.file, plan.points, outcomes);
  sweep::write_file_atomically(out / "results.csv", sweep::to_csv(table));
  sweep::write_file_atomically(out / "results.jsonl", sweep::to_jsonl(table));
  for (const auto& o : outcomes) end.failed += o.ok ? 0 : 1;
  if (interrupted != 0) {
    std::cerr << "rtsim sweep: interrupted: " << end.points - end.failed << " of " << end.points
              << " points done; run the same command to resume\n"
              << "  table  " << (out / "results.csv").string() << " (the points done so far)\n";
    end_by_signal(interrupted);
  }

  if (args.report)
    end.report_error =
        write_report(args, plan, out, outcomes, table, end, pending.requests.size(), session);
  if (!args.quiet) print_summary(args, plan, out, outcomes, end);
  if (!end.report_error.empty()) {
    std::cerr << "rtsim: error: report.html: " << end.report_error << "\n";
    return kExitFailure;
  }
  return end.failed > 0 ? kExitFailure : kExitOk;
}

/// Every rank on this host (`--one-host jobs`): rank 0 runs the sweep as a local one with every
/// rank's slots, on every CPU the ranks were given, and MPI never starts; the other ranks leave at
/// once. The table, the points' folders and the exit status are the local sweep's.
int run_sweep_one_host(const SweepArgs& args, const OneHostRanks& host) {
  if (host.rank != 0) return kExitOk;
  SweepArgs local = args;
  local.mpi = false;
  local.jobs = one_host_jobs(host, args.jobs);
  const int cpus = take_launcher_cpus();
  if (!args.quiet)
    std::cout << one_host_note("sweep", "points", host, local.jobs, cpus) << std::flush;
  const Plan plan = make_plan(local);
  return execute(local, plan, nullptr, nullptr);
}

int run_sweep_mpi(const SweepArgs& args) {
  if (args.one_host == "jobs")
    if (const auto host = one_host_ranks()) return run_sweep_one_host(args, *host);
  // Every rank reads the sweep before MPI starts (milliseconds): rank 0 reads and checks it for
  // the run (its scenes loaded, as a local sweep does), the others read it without loading the
  // scenes, to know whether its points write images. A rank that cannot read it says nothing
  // here: rank 0 reports the error once MPI is up, and the others wait for its word.
  const int hinted_rank = launcher_rank();
  const bool scenes_loaded = hinted_rank <= 0;
  Plan plan;
  std::exception_ptr plan_error;
  try {
    plan = make_plan(args, scenes_loaded);
  } catch (const std::exception&) {
    plan_error = std::current_exception();
  }
  const int jobs = args.jobs > 0 ? args.jobs : 1;
  // If this rank's first points will likely write an image, its servers load the image library
  // now, while MPI starts. Points are handed out in order, rank 0 taking the first `jobs` itself
  // and rank r about the (r * jobs + 1)-th on: so rank r loads it at once when more than
  // r * jobs points write images (with shared images, the default, a timing sweep has one such
  // point per image). The rank comes from the launcher's environment before MPI_Init (where
  // none says, it counts as 0). Otherwise a server loads it when its first point that writes an
  // image comes.
  const auto image_points =
      plan_error ? 0
                 : std::count_if(plan.points.begin(), plan.points.end(),
                                 [](const sweep::Point& p) { return writes_image(p.args); });
  const bool images = image_points > static_cast<long>(std::max(hinted_rank, 0)) * jobs;
  // Each of this rank's slots gets a fork server before MPI starts (app/fork_server.hpp): a
  // point is then a fork, not a program start, unless another rtsim binary was asked for.
  std::unique_ptr<ForkServers> servers;
  if (args.rtsim.empty())
    servers = std::make_unique<ForkServers>(jobs, run_cli_in_forked_child, images);
  mpi::Session session;
  if (session.rank() != 0) {
    // Rank 0 reads and checks the sweep; the others wait for its word, then run points.
    if (const int status = session.share_status(0); status != 0) return status;
    runs::RunQueueOptions q;
    q.executable = executable_of(args);
    q.jobs = jobs;
    q.log_in_run_dir = true;
    if (servers) q.run_and_wait = fork_server_runner(*servers);
    // mpirun passes an interrupt on to every rank: a worker stops its points and reports them,
    // so rank 0 can write the table of what is done (a worker dying by the signal would make
    // mpirun end rank 0 first).
    set_interrupt_handler([](int) { runs::stop_runs(SIGTERM); });
    session.work(q);
    return kExitOk;
  }
  try {
    if (plan_error) std::rethrow_exception(plan_error);
    // The launcher named another rank than MPI did: rank 0 loads the scenes to check them now.
    if (!scenes_loaded) plan = make_plan(args);
  } catch (const InputError& e) {
    session.share_status(kExitBadInput);
    std::cerr << "rtsim: error: " << e.what() << "\n";
    return kExitBadInput;
  }
  session.share_status(0);
  return execute(args, plan, &session, servers.get());
}

}  // namespace

int run_sweep(const SweepArgs& args) {
  if (args.mpi && !args.list) return run_sweep_mpi(args);
  const Plan plan = make_plan(args);
  if (args.list) return list_points(plan, out_dir_of(args));
  return execute(args, plan, nullptr, nullptr);
}

}  // namespace rtsim::app
