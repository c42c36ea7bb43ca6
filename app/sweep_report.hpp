#pragma once
// report.html of a sweep (`rtsim sweep FILE --report`): one self-contained page
// (app/html_report.hpp's HtmlReport) with the sweep file's text, its machines, scenes and axes, the
// results table (every point: swept values, headline stats, wall time, status and error), sweep
// plots drawn by analysis/sweep_plot.py from results.jsonl, thumbnails of the points' images, and
// every parameter of each machine with where it was set and its documented source.
//
// Written by rank 0 after the table (under MPI after gathering, when resuming over every
// point): failed points are listed, not fatal. A plot that cannot be drawn adds a note.
#include <array>
#include <cstddef>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "app/analysis_scripts.hpp"
#include "app/html_report.hpp"
#include "platform/sweep/point_outcome.hpp"
#include "platform/sweep/results_table.hpp"
#include "platform/sweep/sweep_file.hpp"
#include "platform/sweep/sweep_points.hpp"

namespace rtsim::app {

/// At most this many thumbnails (the first points, in point order, that wrote image.png).
inline constexpr std::size_t kSweepThumbnails = 24;
/// At most this many rows of the results table on the page (results.csv has them all).
inline constexpr std::size_t kSweepTableRows = 2000;
/// At most this many plots.
inline constexpr std::size_t kSweepPlots = 24;

/// One plot for analysis/sweep_plot.py.
struct SweepPlotSpec {
  std::string x;               ///< column on the horizontal axis (an axis's first member)
  std::vector<std::string> y;  ///< columns drawn (one line per column and group)
  std::string group;           ///< one line per value of this column; empty: none
  std::string ratio_to;        ///< "COL=VALUE": speed-up over that row of each group; or empty
  bool logx = false;
  bool logy = false;
  std::string title;
  std::string ylabel;   ///< empty: sweep_plot.py's
  std::string caption;  ///< under the picture
  /// Shaded ranges: {y column, low column, high column} (a class's min..max around its mean).
  std::vector<std::array<std::string, 3>> bands{};

  /// sweep_plot.py's arguments after INPUT and OUT.
  std::vector<std::string> script_args() const;
};

/// The plots for a sweep: for each axis (its first member on x; the scene or machine list, or
/// else another short axis, as the lines), the simulated frame time; the speed-up over the
/// axis's first value when the axis counts units (its name holds "count", e.g. pert_count); each
/// `*time_per_ray_s` stat; the busiest modules' utilisation; the ray latency (mean, p99); and the
/// wall time per point. Only columns with a value in some successful row are drawn; at most
/// kSweepPlots plots.
std::vector<SweepPlotSpec> choose_sweep_plots(const sweep::SweepFile& file,
                                              const sweep::ResultsTable& table);

/// What the sweep report is made of.
struct SweepReportInputs {
  const sweep::SweepFile* file = nullptr;                      ///< required
  const std::vector<sweep::Point>* points = nullptr;           ///< required
  const std::vector<sweep::PointOutcome>* outcomes = nullptr;  ///< required, one per point
  const sweep::ResultsTable* table = nullptr;                  ///< required
  std::filesystem::path results_jsonl;  ///< the table as written (sweep_plot.py's input)
  std::filesystem::path points_dir;     ///< OUT/points: each point's image.png
  std::string command_line;             ///< how the sweep was started
  double wall_s = 0;                    ///< wall time of this invocation
  std::size_t run_now = 0;              ///< points run by this invocation (the rest resumed)
  int ranks = 0;                        ///< MPI ranks; 0: a local run
  std::optional<std::size_t> baseline;  ///< --baseline: the point every other is compared with
  /// Told of each plot made (plots made, plots in all); empty: nothing said.
  std::function<void(std::size_t, std::size_t)> progress;
};

/// Writes the page to `out_html` (the caller stages it). Throws std::runtime_error only if the
/// page cannot be written; a missing plot or image adds a note.
void write_sweep_report(const SweepReportInputs& in, const std::filesystem::path& out_html,
                        const ReportTools& tools);

}  // namespace rtsim::app
