#pragma once
// What the report tests (tests/report_test.cpp, tests/sweep_report_test.cpp) share: counting
// and pulling pictures out of a page, and opening it in headless Chromium.
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "tests/test_support.hpp"

namespace rtsim::test {

inline int count(const std::string& text, const std::string& what) {
  int n = 0;
  for (std::size_t p = text.find(what); p != std::string::npos; p = text.find(what, p + 1)) ++n;
  return n;
}

/// The base64 data of the page's <img> elements, in page order ("" for an <img> without inline
/// PNG data). Found by hand: std::regex recurses per character and overflows the stack on
/// 100 kB of base64.
inline std::vector<std::string> image_data(const std::string& html) {
  std::vector<std::string> out;
  const std::string prefix = "src=\"data:image/png;base64,";
  for (std::size_t p = html.find("<img"); p != std::string::npos; p = html.find("<img", p + 1)) {
    const std::size_t end_tag = html.find('>', p);
    const std::size_t src = html.find(prefix, p);
    if (src == std::string::npos || src > end_tag) {
      out.emplace_back();
      continue;
    }
    const std::size_t begin = src + prefix.size();
    out.push_back(html.substr(begin, html.find('"', begin) - begin));
  }
  return out;
}

/// Whether Debian's interpreter has what the analysis/ scripts need.
inline bool matplotlib_available() {
  return std::system("/usr/bin/python3 -c 'import matplotlib, numpy, pandas' >/dev/null 2>&1") == 0;
}

/// Debian's chromium, or "" if it is not installed.
inline std::string chromium() {
  for (const char* p : {"/usr/bin/chromium", "/usr/bin/chromium-browser"})
    if (std::filesystem::exists(p)) return p;
  return "";
}

/// What headless Chromium made of a page.
struct BrowserView {
  int exit_code = -1;
  std::string dom;      ///< the DOM after the load event
  std::string console;  ///< Chromium's log: every console message is a ":CONSOLE" line
};

/// Opens `page` in headless `browser` and dumps its DOM. --virtual-time-budget lets the load
/// event (and the page's check of its pictures) run before the dump; a profile of its own in
/// `scratch` keeps parallel runs apart.
inline BrowserView open_headless(const std::string& browser, const std::filesystem::path& page,
                                 const std::filesystem::path& scratch) {
  const std::filesystem::path dom = scratch / "dom.html", log = scratch / "chromium.log";
  const std::string cmd = "timeout 120 " + browser +
                          " --headless --disable-gpu --no-sandbox --window-size=1280,1024 "
                          "--enable-logging=stderr "
                          "--v=0 --virtual-time-budget=10000 --user-data-dir=" +
                          (scratch / "profile").string() + " --dump-dom file://" +
                          std::filesystem::absolute(page).string() + " >" + dom.string() + " 2>" +
                          log.string();
  BrowserView v;
  v.exit_code = std::system(cmd.c_str());
  v.dom = read_file(dom);
  v.console = read_file(log);
  return v;
}

}  // namespace rtsim::test
