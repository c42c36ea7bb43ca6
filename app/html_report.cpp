#include "app/html_report.hpp"

#include <fstream>
#include <sstream>
#include <stdexcept>

namespace rtsim::app {

namespace fs = std::filesystem;

std::string read_whole_file(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  if (!f) throw std::runtime_error("cannot read " + p.string());
  std::ostringstream s;
  s << f.rdbuf();
  return s.str();
}

std::string base64(const std::string& bytes) {
  static constexpr char kAlphabet[] =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  std::size_t i = 0;
  for (; i + 2 < bytes.size(); i += 3) {
    const auto a = static_cast<unsigned char>(bytes[i]);
    const auto b = static_cast<unsigned char>(bytes[i + 1]);
    const auto c = static_cast<unsigned char>(bytes[i + 2]);
    out += kAlphabet[a >> 2];
    out += kAlphabet[((a & 3) << 4) | (b >> 4)];
    out += kAlphabet[((b & 15) << 2) | (c >> 6)];
    out += kAlphabet[c & 63];
  }
  if (i + 1 == bytes.size()) {
    const auto a = static_cast<unsigned char>(bytes[i]);
    out += kAlphabet[a >> 2];
    out += kAlphabet[(a & 3) << 4];
    out += "==";
  } else if (i + 2 == bytes.size()) {
    const auto a = static_cast<unsigned char>(bytes[i]);
    const auto b = static_cast<unsigned char>(bytes[i + 1]);
    out += kAlphabet[a >> 2];
    out += kAlphabet[((a & 3) << 4) | (b >> 4)];
    out += kAlphabet[(b & 15) << 2];
    out += '=';
  }
  return out;
}

std::string html_escape(const std::string& s) {
  std::string out;
  out.reserve(s.size());
  for (char c : s) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&#39;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

HtmlReport::HtmlReport(std::string title) : title_(std::move(title)) {}

void HtmlReport::heading(const std::string& text) {
  body_ += "<h2>" + html_escape(text) + "</h2>\n";
}

void HtmlReport::paragraph(const std::string& text) {
  body_ += "<p>" + html_escape(text) + "</p>\n";
}

void HtmlReport::note(const std::string& text) {
  body_ += "<p class=\"note\">" + html_escape(text) + "</p>\n";
}

void HtmlReport::key_values(const std::vector<std::pair<std::string, std::string>>& rows) {
  body_ += "<table class=\"kv\">\n";
  for (const auto& [k, v] : rows)
    body_ += "<tr><th>" + html_escape(k) + "</th><td>" + html_escape(v) + "</td></tr>\n";
  body_ += "</table>\n";
}

void HtmlReport::table(const std::vector<std::string>& head,
                       const std::vector<std::vector<std::string>>& rows,
                       const std::vector<bool>& emphasised) {
  body_ += "<table>\n<tr>";
  for (const auto& h : head) body_ += "<th>" + html_escape(h) + "</th>";
  body_ += "</tr>\n";
  for (std::size_t r = 0; r < rows.size(); ++r) {
    const bool em = r < emphasised.size() && emphasised[r];
    body_ += em ? "<tr class=\"set\">" : "<tr>";
    for (const auto& c : rows[r]) body_ += "<td>" + html_escape(c) + "</td>";
    body_ += "</tr>\n";
  }
  body_ += "</table>\n";
}

void HtmlReport::image(const fs::path& png, const std::string& alt, const std::string& caption,
                       bool pixelated) {
  const std::string data = read_whole_file(png);
  body_ += std::string("<figure><img") + (pixelated ? " class=\"frame\"" : "") + " alt=\"" +
           html_escape(alt) + "\" src=\"data:image/png;base64," + base64(data) + "\">";
  if (!caption.empty()) body_ += "<figcaption>" + html_escape(caption) + "</figcaption>";
  body_ += "</figure>\n";
  ++images_;
}

std::string HtmlReport::html() const {
  // The small script only checks that every picture decoded: it marks the page with the count
  // (data-images-decoded, read by the headless-browser test) and logs a console error for a
  // picture that did not; and with the page's width as laid out (data-page-width: the test
  // opens it 1280 px wide and sees that nothing runs off).
  return "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
         "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n"
         "<title>" +
         html_escape(title_) +
         "</title>\n<style>\n"
         "body{font-family:sans-serif;max-width:1100px;margin:1.5em auto;padding:0 1em;"
         "color:#222}\n"
         "h1{font-size:1.5em}h2{font-size:1.2em;margin-top:1.6em;border-bottom:1px solid #ccc}\n"
         "table{border-collapse:collapse;font-size:.9em;margin:.5em 0}\n"
         "td,th{border:1px solid #ddd;padding:.2em .5em;text-align:left;vertical-align:top}\n"
         "th{background:#f4f4f4}table.kv th{width:16em}tr.set td{font-weight:bold}\n"
         "figure{margin:1em 0}img{max-width:100%;border:1px solid #eee}\n"
         "img.frame{min-width:512px;image-rendering:pixelated}\n"
         "figcaption{font-size:.85em;color:#555}\n"
         ".note{background:#fff6d5;border-left:4px solid #e0b000;padding:.4em .8em}\n"
         "</style>\n</head>\n<body>\n<h1>" +
         html_escape(title_) + "</h1>\n" + body_ +
         "<script>\n"
         "window.addEventListener('load', function () {\n"
         "  var imgs = document.querySelectorAll('img'), ok = 0;\n"
         "  for (var i = 0; i < imgs.length; i++) {\n"
         "    if (imgs[i].complete && imgs[i].naturalWidth > 0) ok++;\n"
         "    else console.error('report: picture did not decode: ' + imgs[i].alt);\n"
         "  }\n"
         "  document.body.setAttribute('data-images-decoded', String(ok));\n"
         "  document.body.setAttribute('data-page-width',\n"
         "                             String(document.documentElement.scrollWidth));\n"
         "});\n"
         "</script>\n</body>\n</html>\n";
}

void HtmlReport::write(const fs::path& path) const {
  std::ofstream f(path, std::ios::binary | std::ios::trunc);
  f << html();
  f.close();
  if (!f) throw std::runtime_error("cannot write " + path.string());
}

}  // namespace rtsim::app
