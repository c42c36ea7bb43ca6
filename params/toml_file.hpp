#pragma once
// Parsing a TOML text (a config file, a sweep file) with toml++, after a check that its keys are
// not nested deeper than rtsim can take: toml++ builds one table per part of a dotted key and
// recurses through them (parsing, then freeing), so a 62 KB key of 31,000 parts overflowed the
// stack. Values nested in arrays and inline tables toml++ bounds itself (TOML_MAX_NESTED_VALUES).
#include <toml++/toml.h>

#include <cstddef>
#include <string>
#include <string_view>

namespace rtsim::params {

/// Most parts a table may lie below the root, counting a header's dotted parts, a key's and
/// those of every key of inline tables around it: a parameter name has at most 4 parts
/// (`pert.link.prim_to_shade.bit_rate`), a sweep file's keys 3.
inline constexpr std::size_t kMaxTomlKeyDepth = 64;

/// The line (1-based) of the first key nested deeper than `max_depth`, or 0. Reads just enough
/// of the syntax to tell keys from values (strings, comments, arrays, inline tables); a text it
/// cannot follow is left to toml++, which reports the error.
std::size_t first_too_deep_key(std::string_view text, std::size_t max_depth = kMaxTomlKeyDepth);

/// toml::parse with the depth check first; InputError (origin, line, what) for either.
toml::table parse_toml(std::string_view text, const std::string& origin);

}  // namespace rtsim::params
