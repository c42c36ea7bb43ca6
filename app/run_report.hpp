#pragma once
// report.html of one `rtsim run --report`: the image, the headline numbers, plots drawn by the
// analysis/ scripts and the parameters used with their sources (html_report.hpp,
// analysis_scripts.hpp).
#include <filesystem>
#include <string>
#include <vector>

#include "app/analysis_scripts.hpp"
#include "app/html_report.hpp"
#include "params/registry.hpp"

namespace rtsim::app {

/// The files a run report is made from (paths may be staged files not yet committed).
struct RunReportInputs {
  std::filesystem::path stats_json;        ///< required
  std::filesystem::path image_png;         ///< empty: no image
  std::filesystem::path trace_json;        ///< Perfetto trace; empty: none
  std::vector<params::ParamEntry> params;  ///< with sources; empty: stats' `params`
  std::string command_line;                ///< how the run was started
};

/// Writes report.html for one `rtsim run`: headline numbers, the image, the utilisation
/// timeline (from the trace if given, else from stats.json's utilization_windows), the
/// ray-latency histogram, where a ray spends its time (stats.json latency_probe, from
/// --latency-probe: a per-stage table and analysis/latency_breakdown.py's plot), the module
/// table, machine-specific figures and the parameters.
/// Throws std::runtime_error if stats.json cannot be read or the page cannot be written; a
/// plot that cannot be drawn only adds a note.
void write_run_report(const RunReportInputs& in, const std::filesystem::path& out_html,
                      const ReportTools& tools);

}  // namespace rtsim::app
