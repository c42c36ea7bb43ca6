#pragma once
// report.html: one self-contained page (no file beside it is needed: pictures are embedded as
// base64 PNG data URIs, the style is inline) with the image, the headline numbers, plots drawn
// by the analysis/ scripts and the parameters used with their sources. Written by
// `rtsim run --report`; HtmlReport and run_analysis_script are the pieces any other report
// (a sweep's) is built from.
//
// Plots come from Debian's /usr/bin/python3 with python3-matplotlib running analysis/*.py. If
// that fails (no Python, no matplotlib), the report is written without plots and says why.
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "app/number_text.hpp"
#include "params/registry.hpp"

namespace rtsim::app {

/// Where the plotting tools are.
struct ReportTools {
  /// Interpreter; empty: $RTSIM_PYTHON, else /usr/bin/python3 (Debian's, where matplotlib
  /// installs) if it exists, else python3 on PATH.
  std::string python;
  /// analysis/ folder; empty: $RTSIM_ANALYSIS_DIR, else the source tree's analysis/.
  std::filesystem::path analysis_dir;
  /// Scratch folder for the PNGs (created if missing; the caller removes it).
  std::filesystem::path scratch_dir;

  /// The same with every empty field filled in as documented above.
  ReportTools resolved() const;
};

/// Result of running one analysis script.
struct ScriptResult {
  bool ok = false;
  std::string message;  ///< on failure: what went wrong (the script's last stderr lines)
};

/// Runs `python analysis_dir/script args...` with its output into scratch_dir/script.log.
ScriptResult run_analysis_script(const ReportTools& tools, const std::string& script,
                                 const std::vector<std::string>& args);

/// A self-contained HTML page built section by section. Text is escaped.
class HtmlReport {
 public:
  explicit HtmlReport(std::string title);

  void heading(const std::string& text);
  void paragraph(const std::string& text);
  /// A highlighted remark (e.g. why there are no plots).
  void note(const std::string& text);
  /// Two columns: name, value.
  void key_values(const std::vector<std::pair<std::string, std::string>>& rows);
  /// `emphasised` rows (by index) are bold (e.g. parameters not at their default).
  void table(const std::vector<std::string>& head,
             const std::vector<std::vector<std::string>>& rows,
             const std::vector<bool>& emphasised = {});
  /// Embeds the PNG file as a data URI. Throws std::runtime_error if it cannot be read.
  /// `pixelated`: a rendered frame, drawn at least 512 pixels wide with its pixels kept sharp.
  void image(const std::filesystem::path& png, const std::string& alt, const std::string& caption,
             bool pixelated = false);
  /// Number of images embedded so far.
  int images() const { return images_; }
  /// Appends `html` as it is (the caller escapes its text): pieces the methods above do not
  /// cover, such as preformatted text or a grid of thumbnails. `images`: <img> elements in it.
  void raw(const std::string& html, int images = 0) {
    body_ += html;
    images_ += images;
  }

  std::string html() const;
  /// Writes html() to `path` (the caller stages it: app/output_set.hpp).
  void write(const std::filesystem::path& path) const;

 private:
  std::string title_;
  std::string body_;
  int images_ = 0;
};

/// Standard base64 (RFC 4648) of `bytes`.
std::string base64(const std::string& bytes);
/// `s` with & < > " ' escaped for HTML text and attribute values.
std::string html_escape(const std::string& s);

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
