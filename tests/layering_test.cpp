// The layers include only downwards (DESIGN.md "The three layers"; docs/adding-a-machine.md):
// common -> params -> firmware (with the scene data it consumes) -> scenes (readers,
// generators) -> modules -> platform -> app. A file may include its own folder's headers and
// those of any folder before it, never one after it. Every #include "FOLDER/..." of every source
// under those folders is checked, so a new back-arrow fails here with the file and line.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;

const std::vector<std::string> kLayers = {"common",  "params",   "firmware", "scenes",
                                          "modules", "platform", "app"};

int rank_of(const std::string& folder) {
  for (std::size_t i = 0; i < kLayers.size(); ++i)
    if (kLayers[i] == folder) return static_cast<int>(i);
  return -1;
}

TEST(Layering, NoFolderIncludesOneAboveIt) {
  const fs::path root = RTSIM_SOURCE_DIR;
  const std::regex include_line(R"re(^\s*#\s*include\s*"([a-z_]+)/)re");
  std::size_t files = 0, includes = 0;
  std::vector<std::string> back_arrows;
  for (const std::string& layer : kLayers) {
    ASSERT_TRUE(fs::is_directory(root / layer)) << (root / layer);
    for (const auto& e : fs::recursive_directory_iterator(root / layer)) {
      const std::string ext = e.path().extension().string();
      if (!e.is_regular_file() || (ext != ".cpp" && ext != ".hpp")) continue;
      ++files;
      std::ifstream in(e.path());
      std::size_t line_number = 0;
      for (std::string line; std::getline(in, line);) {
        ++line_number;
        std::smatch m;
        if (!std::regex_search(line, m, include_line)) continue;
        const int to = rank_of(m[1]);
        if (to < 0) continue;  // a library's header ("nlohmann/json.hpp" is in <>; OIIO...)
        ++includes;
        if (to > rank_of(layer))
          back_arrows.push_back(fs::relative(e.path(), root).string() + ":" +
                                std::to_string(line_number) + ": " + line);
      }
    }
  }
  std::printf("%zu files, %zu includes between the project's folders\n", files, includes);
  EXPECT_GT(includes, 500u);
  std::string text;
  for (const auto& b : back_arrows) text += "\n  " + b;
  EXPECT_TRUE(back_arrows.empty()) << back_arrows.size() << " includes of a layer above:" << text;
}

}  // namespace
