#pragma once
// Arguments and entry points of the subcommands.
#include <algorithm>
#include <string>
#include <vector>

namespace rtsim::app {

struct ConfigArgs {
  std::vector<std::string> config_files;
  std::vector<std::string> overrides;  ///< NAME=VALUE from -p
};

struct RenderArgs {
  std::string scene = "builtin:default";
  std::string machine;  ///< "": the functional renderer's own geometry
  std::string out_dir = "out/render";
  int width = 0;
  int height = 0;
  int spp = 0;  ///< 0: take render.spp from the configuration
  int threads = 1;
  std::vector<std::string> aovs;
  bool quiet = false;
  ConfigArgs config;
};

struct RunArgs {
  std::string machine;  ///< --machine; the CLI starts it at the registry's default machine
  std::string scene = "builtin:ullner-cubes";
  std::string out_dir = "out/run";
  int width = 0;
  int height = 0;
  std::vector<std::string> aovs;
  std::vector<std::string> traces;         ///< vcd, perfetto
  std::string trace_window;                ///< "T0,T1"; "": all of time
  std::vector<std::string> trace_modules;  ///< patterns on module names; none: all
  std::size_t trace_max_events = 0;        ///< per trace file; 0: every event
  std::string quantum;                     ///< "" keeps the parameter `quantum`
  int spp = 0;                             ///< --spp N: render.spp (0: the configuration's)
  bool overhead = false;
  /// --image: the image files written: all (image.png, image.exr, AOVs), png, or none (a
  /// timing-only run: a sampled run then renders no row it does not simulate).
  std::string image = "all";
  int sample = 0;                   ///< --sample K: one row window in K in detail (0: off)
  int sample_window = 0;            ///< --sample-window R: rows a window (0: the machine's choice)
  int sample_warmup = -1;           ///< --sample-warmup W: warm-up windows (-1: the default)
  int sample_work_stride = -1;      ///< --sample-work-stride S (-1: the default)
  std::string sample_error;         ///< --sample-error E: K chosen by a pilot for this error
  bool report = false;              ///< also write report.html
  bool latency_probe = false;       ///< stats.json latency_probe: per-ray time by stage and part
  std::vector<std::string> faults;  ///< MEMORY:WORD:XOR, each a corrupted word
  bool quiet = false;
  ConfigArgs config;
};

struct DiffArgs {
  std::string a, b;        ///< run folders or stats.json files
  bool all = false;        ///< every changed statistic, not the first kStatsShown
  double tolerance = 0.0;  ///< relative: numbers closer than this are the same
  static constexpr std::size_t kStatsShown = 40;
};

struct ListArgs {
  std::string what;
  std::string machine;
  std::string format = "text";  ///< text | markdown (params) | json (params, machines)
  std::string pattern;          ///< params: only names matching this shell pattern ("": all)
  bool changed = false;         ///< params: only those whose value is not the default
  ConfigArgs config;
};

struct DescribeArgs {
  std::string machine;
  std::string scene;    ///< "": the machine's sample scene
  std::string out_dir;  ///< "": text only; else MACHINE.dot and MACHINE.svg here
  ConfigArgs config;
};

struct ValidateArgs {
  bool quick = false;
  int jobs = 1;
  std::vector<std::string> only;  ///< figure ids or groups ("V2" = V2a, V2b, ...)
  std::string out_dir;            ///< empty: a temporary folder
  bool keep = false;              ///< keep the run folders (and the temporary --out)
  bool list = false;              ///< list the figures, run nothing
  std::string rtsim;              ///< binary to run; empty: this one
  bool sensitivity = false;       ///< also move each figure's assumptions (--sensitivity)
  std::vector<double> factors = {0.5, 2.0};  ///< how numeric assumptions are moved
  bool mpi = false;                          ///< spread the runs over MPI ranks
  /// With --mpi, when every rank is on this host: "jobs" (rank 0 runs them as local jobs, no
  /// MPI) or "mpi" (hand them out over MPI as on many hosts).
  std::string one_host = "jobs";
};

struct SweepArgs {
  std::string file;     ///< the sweep file (TOML, docs/sweeps.md)
  std::string out_dir;  ///< empty: out/sweeps/<file name without extension>
  int jobs = 0;         ///< points at once (per rank with --mpi); 0: the cores (1 with --mpi)
  bool mpi = false;     ///< spread the points over MPI ranks (under mpirun / srun)
  /// With --mpi, when every rank is on this host: "jobs" (rank 0 runs them as local jobs, no
  /// MPI) or "mpi" (hand them out over MPI as on many hosts).
  std::string one_host = "jobs";
  bool force = false;   ///< run every point again, even those done before
  bool list = false;    ///< print the points' command lines, run nothing
  bool report = false;  ///< also write report.html (app/sweep_report.hpp)
  int baseline = -1;    ///< --baseline N: the report compares every point with point N
  bool quiet = false;
  std::string rtsim;  ///< binary to run for each point; empty: this one
};

/// Whether --aov asked for `name` (id, depth).
inline bool wants_aov(const std::vector<std::string>& aovs, const std::string& name) {
  return std::find(aovs.begin(), aovs.end(), name) != aovs.end();
}

int run_render(const RenderArgs& args);
int run_validate(const ValidateArgs& args);
int run_list(const ListArgs& args);
int run_diff(const DiffArgs& args);
int run_describe(const DescribeArgs& args);
int run_run(const RunArgs& args);
int run_sweep(const SweepArgs& args);

}  // namespace rtsim::app
