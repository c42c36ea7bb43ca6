#pragma once
// One self-contained HTML page (no file beside it is needed: pictures are embedded as base64
// PNG data URIs, the style is inline), built section by section: the pieces every report of
// rtsim's is made of (a run's, a sweep's).
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace rtsim::app {

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

/// The bytes of the file `p` (an image to embed, a stats.json to read); std::runtime_error if it
/// cannot be read.
std::string read_whole_file(const std::filesystem::path& p);
/// Standard base64 (RFC 4648) of `bytes`.
std::string base64(const std::string& bytes);
/// `s` with & < > " ' escaped for HTML text and attribute values.
std::string html_escape(const std::string& s);

}  // namespace rtsim::app
