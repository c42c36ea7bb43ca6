// `rtsim validate`: reproduce the seeds' figures by running this binary's `run` and `render`
// subcommands as separate processes (SystemC allows one simulation per process), and compare.
#include <signal.h>
#include <stdlib.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <mutex>
#include <stdexcept>

#include "app/analysis_scripts.hpp"
#include "app/cli.hpp"
#include "app/commands.hpp"
#include "app/fork_server.hpp"
#include "app/image_files.hpp"
#include "app/interrupt_cleanup.hpp"
#include "app/mpi_launcher.hpp"
#include "app/progress_bar.hpp"
#include "app/sweep_mpi.hpp"
#include "common/seed_citation.hpp"
#include "platform/runs/run_queue.hpp"
#include "platform/sweep/point_outcome.hpp"
#include "platform/validation/figure_registry.hpp"
#include "platform/validation/sensitivity.hpp"
#include "platform/validation/validation.hpp"

namespace rtsim::app {

namespace fs = std::filesystem;
namespace val = rtsim::validation;

namespace {

/// A fresh folder `parent/prefixXXXXXX` (mkdtemp).
fs::path make_temp_dir(const fs::path& parent, const std::string& prefix) {
  fs::create_directories(parent);
  std::string templ = (parent / (prefix + "XXXXXX")).string();
  if (::mkdtemp(templ.data()) == nullptr)
    throw std::runtime_error("cannot create a temporary folder in " + parent.string());
  return templ;
}

/// Written to a temporary name and renamed (DESIGN.md "Outputs").
void write_file(const fs::path& path, const std::string& text) {
  const fs::path tmp = path.string() + ".partial";
  {
    std::ofstream out(tmp, std::ios::binary);
    out << text;
    if (!out) throw std::runtime_error("cannot write " + tmp.string());
  }
  fs::rename(tmp, path);
}

std::string seed_of(const val::Figure& f) {
  if (!f.seed_display.empty()) return f.seed_display;
  if (f.seed_from_run) return "from the run";
  return f.unit.empty() ? val::format_number(f.seed_value)
                        : val::format_number(f.seed_value) + " " + f.unit;
}

void print_list(const val::Plan& plan) {
  // Sweeps have dozens of runs that differ in one parameter: show the first and a count.
  constexpr std::size_t kRunsShown = 2;
  for (const auto& f : plan.figures) {
    std::cout << f.id << "  " << f.title << "  (" << cite_seeds(f.seed_ref) << ")\n"
              << "    class:     " << val::class_name(f.figure_class) << "\n"
              << "    seed:      " << seed_of(f) << " -- " << f.seed_text << "\n"
              << "    tolerance: " << f.tolerance.describe() << " -- " << f.tolerance.why << "\n"
              << "    workload:  " << f.workload << "\n";
    if (!f.assumptions.empty()) {
      std::cout << "    assumes:  ";
      for (const auto& a : f.assumptions) std::cout << " " << a.param;
      std::cout << "\n";
    }
    for (std::size_t i = 0; i < f.runs.size() && i < kRunsShown; ++i) {
      if (const auto* r = plan.find_run(f.runs[i]))
        std::cout << "    run:       " << r->command_line() << "\n";
    }
    if (f.runs.size() > kRunsShown)
      std::cout << "    ... and " << f.runs.size() - kRunsShown << " more runs of the sweep\n";
  }
}

fs::path this_executable() {
  std::error_code ec;
  fs::path p = fs::read_symlink("/proc/self/exe", ec);
  if (ec) throw std::runtime_error("cannot find this program's path (/proc/self/exe)");
  return p;
}

/// A run done on an MPI rank, as the run queue would have recorded it here.
val::RunOutcome outcome_from_rank(const runs::RunRequest& request, const fs::path& work_dir,
                                  const sweep::PointOutcome& p) {
  val::RunOutcome o;
  o.request = request;
  o.out_dir = work_dir / request.key;
  o.log = work_dir / (request.key + ".log");
  o.exit_code = p.exit_code;
  o.wall_s = p.wall_s;
  o.status = p.ok ? "exit status 0" : p.error;
  o.failure = p.ok ? "" : p.error;
  if (p.ok) {
    try {
      o.stats = nlohmann::json::parse(p.stats_text);
    } catch (const std::exception& e) {
      o.failure = std::string("its stats.json does not read as JSON: ") + e.what();
    }
  }
  return o;
}

/// Every request run: forks of this process (or another rtsim binary) on this machine, or
/// spread over the ranks of an MPI session as `rtsim sweep --mpi` spreads its points.
val::RunResults execute_runs(const std::vector<runs::RunRequest>& requests,
                             const ValidateArgs& args, const fs::path& executable,
                             const fs::path& work_dir, mpi::Session* session,
                             ForkServers* servers) {
  ProgressBar bar("validate");
  runs::RunQueueOptions q;
  q.executable = executable;
  q.work_dir = work_dir;
  q.jobs = args.jobs;
  if (session != nullptr) {
    if (servers) q.run_and_wait = fork_server_runner(*servers);
    val::RunResults results;
    std::mutex m;
    int done = 0;
    session->dispatch(requests, q, [&](std::size_t i, const sweep::PointOutcome& p) {
      std::lock_guard lock(m);
      results[requests[i].key] = outcome_from_rank(requests[i], work_dir, p);
      bar.update(++done, static_cast<int>(requests.size()));
    });
    return results;
  }
  // Runs are forks of this process, unless another rtsim binary was asked for.
  if (args.rtsim.empty()) {
    q.in_process = run_cli_in_forked_child;
    preload_image_module();  // once here, not in every run
  }
  q.on_finished = [&bar](const val::RunOutcome&, int done, int total) { bar.update(done, total); };
  return runs::run_all(requests, q);
}

/// The picture of the sensitivity (analysis/sensitivity_map.py); the reason if there is none.
std::string draw_sensitivity(const fs::path& json, const fs::path& png, const fs::path& out_dir) {
  ReportTools tools;
  tools.scratch_dir = out_dir / ".sensitivity-plot";
  const auto r = run_analysis_script(tools, "sensitivity_map.py", {json.string(), png.string()});
  std::error_code ec;
  fs::remove_all(tools.scratch_dir, ec);
  return r.ok ? std::string() : r.message;
}

int validate(const ValidateArgs& args, const val::Plan& plan, mpi::Session* session,
             ForkServers* servers);

int run_validate_mpi(const ValidateArgs& args, const val::Plan* plan) {
  // Every rank on this host (--one-host jobs): rank 0 validates locally with every rank's
  // slots, MPI never starts, the others leave at once (as `rtsim sweep --mpi`).
  if (args.one_host == "jobs")
    if (const auto host = one_host_ranks()) {
      if (host->rank != 0) return kExitOk;
      if (plan == nullptr) return kExitBadInput;  // said already
      ValidateArgs local = args;
      local.mpi = false;
      local.jobs = one_host_jobs(*host, args.jobs);
      std::cout << one_host_note("validate", "runs", *host, local.jobs, take_launcher_cpus())
                << std::flush;
      return validate(local, *plan, nullptr, nullptr);
    }
  // The runs are forks of fork servers started before MPI (app/fork_server.hpp), unless
  // another rtsim binary was asked for.
  std::unique_ptr<ForkServers> servers;
  if (args.rtsim.empty() && plan != nullptr)
    servers = std::make_unique<ForkServers>(args.jobs, run_cli_in_forked_child);
  mpi::Session session;
  if (session.rank() != 0) {
    // Rank 0 builds and checks the plan; the others wait for its word, then run what it hands
    // out, in the folders it names.
    if (const int status = session.share_status(0); status != 0) return status;
    runs::RunQueueOptions q;
    q.executable = args.rtsim.empty() ? this_executable() : fs::absolute(args.rtsim);
    q.jobs = args.jobs;
    if (servers) q.run_and_wait = fork_server_runner(*servers);
    set_interrupt_handler([](int) { runs::stop_runs(SIGTERM); });
    session.work(q);
    return kExitOk;
  }
  if (plan == nullptr) {
    session.share_status(kExitBadInput);
    return kExitBadInput;
  }
  session.share_status(0);
  return validate(args, *plan, &session, servers.get());
}

}  // namespace

int run_validate(const ValidateArgs& args) {
  val::PlanOptions options;
  options.quick = args.quick;
  val::Plan plan;
  try {
    plan = val::select_figures(val::make_validation_plan(options), args.only);
  } catch (const std::invalid_argument& e) {
    std::cerr << "rtsim validate: --only: " << e.what() << "\n";
    if (args.mpi && !args.list) return run_validate_mpi(args, nullptr);
    return kExitBadInput;
  }
  if (args.list) {
    print_list(plan);
    return kExitOk;
  }
  if (args.mpi) return run_validate_mpi(args, &plan);
  return validate(args, plan, nullptr, nullptr);
}

namespace {

int validate(const ValidateArgs& args, const val::Plan& plan, mpi::Session* session,
             ForkServers* servers) {
  const fs::path executable = args.rtsim.empty() ? this_executable() : fs::absolute(args.rtsim);
  const bool temporary_out = args.out_dir.empty();
  const fs::path out_dir = temporary_out
                               ? make_temp_dir(fs::temp_directory_path(), "rtsim-validate-")
                               : fs::absolute(args.out_dir);
  fs::create_directories(out_dir);
  const fs::path work_dir = make_temp_dir(out_dir, "runs-");
  // Ctrl-C or SIGTERM before the results are written: the run folders go (and the temporary
  // --out with them); the runs themselves end with this process (their parent-death signal).
  const std::uint64_t interrupt_id = remove_on_interrupt(temporary_out ? out_dir : work_dir);

  // With --sensitivity, the assumptions' moves run in the same batch as the figures' runs.
  val::SensitivityPlan sensitivity;
  if (args.sensitivity)
    sensitivity =
        val::make_sensitivity_plan(plan, val::SensitivityOptions{.factors = args.factors});
  std::vector<runs::RunRequest> requests = plan.runs;
  requests.insert(requests.end(), sensitivity.runs.begin(), sensitivity.runs.end());

  std::cout << "rtsim validate: " << plan.figures.size() << " figures, " << plan.runs.size()
            << " runs";
  if (args.sensitivity) {
    std::size_t moves = 0;
    for (const auto& p : sensitivity.perturbations) moves += p.skipped.empty() ? 1 : 0;
    std::cout << " and " << sensitivity.runs.size() << " more for " << moves
              << " moves of the figures' assumptions";
  }
  std::cout << ", " << args.jobs << " at a time";
  if (session != nullptr) std::cout << " on each of " << session->size() << " MPI ranks";
  std::cout << ", " << (args.quick ? "quick" : "full") << " mode\n" << std::flush;

  const auto start = std::chrono::steady_clock::now();
  const val::RunResults results =
      execute_runs(requests, args, executable, work_dir, session, servers);
  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  const auto rows = val::evaluate(plan, results);
  const auto passed = static_cast<int>(
      std::count_if(rows.begin(), rows.end(), [](const auto& r) { return r.pass(); }));
  // Exit 0: every figure expected to pass passed (known open ones fail as documented).
  const bool all_pass =
      std::all_of(rows.begin(), rows.end(), [](const auto& r) { return r.as_expected(); });
  int failed_runs = 0;

  nlohmann::ordered_json doc;
  doc["tool"] = "rtsim";
  doc["version"] = RTSIM_VERSION;
  doc["command"] = "validate";
  doc["mode"] = args.quick ? "quick" : "full";
  doc["executable"] = executable.string();
  doc["jobs"] = args.jobs;
  doc["wall_time_s"] = wall;
  doc["figures"] = rows.size();
  doc["passed"] = passed;
  doc["failed"] = static_cast<int>(rows.size()) - passed;
  // Per class: how many rows, and how many pass (DESIGN.md "Validation").
  nlohmann::ordered_json classes;
  for (auto c :
       {val::FigureClass::kMeasured, val::FigureClass::kDerived, val::FigureClass::kQualitative}) {
    int n = 0, ok = 0;
    for (const auto& r : rows) {
      if (r.figure_class != c) continue;
      ++n;
      if (r.pass()) ++ok;
    }
    classes[val::class_name(c)] = {{"rows", n}, {"passed", ok}};
  }
  doc["classes"] = classes;
  auto class_errors = nlohmann::ordered_json::array();
  for (const auto& r : rows)
    if (!r.class_error.empty()) class_errors.push_back(r.id);
  doc["class_errors"] = class_errors;
  auto open_failing = nlohmann::ordered_json::array();
  for (const auto& r : rows)
    if (!r.pass() && r.as_expected()) open_failing.push_back(r.id);
  doc["known_open_failing"] = open_failing;
  doc["pass"] = all_pass;
  doc["rows"] = val::rows_to_json(rows);
  auto runs = nlohmann::ordered_json::array();
  for (const auto& r : requests) {
    const auto& o = results.at(r.key);
    if (!o.failure.empty()) ++failed_runs;
    nlohmann::ordered_json j;
    j["key"] = r.key;
    j["command"] = r.command_line();
    j["exit_code"] = o.exit_code;
    j["wall_time_s"] = o.wall_s;
    j["failure"] = o.failure;
    runs.push_back(std::move(j));
  }
  doc["runs"] = runs;

  write_file(out_dir / "validation.json", doc.dump(2) + "\n");
  write_file(out_dir / "validation.csv", val::rows_to_csv(rows));
  std::vector<std::string> written = {"validation.json", "validation.csv"};
  for (const auto& a : plan.artifacts) {
    write_file(out_dir / a.file_name, a.contents(results));
    written.push_back(a.file_name);
  }
  std::string sensitivity_text, no_picture;
  if (args.sensitivity) {
    const auto entries = val::evaluate_sensitivity(plan, rows, sensitivity, results);
    nlohmann::ordered_json sdoc;
    sdoc["tool"] = "rtsim";
    sdoc["version"] = RTSIM_VERSION;
    sdoc["command"] = "validate --sensitivity";
    sdoc["mode"] = args.quick ? "quick" : "full";
    sdoc["factors"] = args.factors;
    sdoc["wall_time_s"] = wall;
    sdoc["runs"] = sensitivity.runs.size();
    const auto parts = val::sensitivity_to_json(rows, sensitivity, entries);
    for (const auto& [k, v] : parts.items()) sdoc[k] = v;
    const fs::path json = out_dir / "validation-sensitivity.json";
    write_file(json, sdoc.dump(2) + "\n");
    written.push_back("validation-sensitivity.json");
    sensitivity_text = val::format_sensitivity(rows, entries);
    no_picture = entries.empty()
                     ? "no figure of this selection names an assumption that moves"
                     : draw_sensitivity(json, out_dir / "validation-sensitivity.png", out_dir);
    if (no_picture.empty()) written.push_back("validation-sensitivity.png");
  }

  std::cout << "\n" << val::format_table(rows);
  if (all_pass) {
    std::cout << "every figure expected to pass passes\n";
  } else {
    std::cout << "expected to pass but failed:";
    for (const auto& r : rows)
      if (!r.as_expected()) std::cout << " " << r.id;
    std::cout << "\n";
  }
  if (!sensitivity_text.empty()) std::cout << "\n" << sensitivity_text;
  if (!no_picture.empty()) std::cout << "no validation-sensitivity.png: " << no_picture << "\n";
  std::cout << "wall time " << val::format_number(wall) << " s\n";

  // Run folders go unless asked for; a failed run's folder stays so its log can be read.
  const bool keep_runs = args.keep || failed_runs > 0;
  forget_on_interrupt(interrupt_id);
  if (!keep_runs) fs::remove_all(work_dir);
  if (temporary_out && !keep_runs) {
    fs::remove_all(out_dir);
  } else {
    std::cout << "results in " << out_dir.string() << ":";
    for (const auto& w : written) std::cout << " " << w;
    std::cout << "\n";
    if (keep_runs) {
      std::cout << "runs in " << work_dir.string();
      if (!args.keep) std::cout << " (kept: " << failed_runs << " run(s) failed)";
      std::cout << "\n";
    }
  }
  return all_pass ? kExitOk : kExitFailure;
}

}  // namespace

}  // namespace rtsim::app
