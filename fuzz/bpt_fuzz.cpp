// libFuzzer target: the .bpt reader (scenes/bpt_reader.hpp) on any bytes. docs/fuzzing.md.
// The reader may refuse input only with rtsim::InputError; whatever it accepts must be a usable
// scene (scene_checks.hpp). Any other exception, a crash, a sanitizer report, a leak or a timeout
// is a finding.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "common/input_error.hpp"
#include "fuzz/scene_checks.hpp"
#include "scenes/bpt_reader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    rtsim::fuzz::check_scene(rtsim::scenes::parse_bpt(text, "fuzz.bpt"));
  } catch (const rtsim::InputError&) {
    // Refused with a message naming file and line: the expected outcome for bad input.
  }
  return 0;
}
