#pragma once
// "Did you mean ...?" for mistyped names: parameters, enum values, builtin scenes.
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace rtsim {

/// Damerau-Levenshtein distance in its optimal-string-alignment form: inserting, deleting or
/// substituting a character, or swapping two adjacent ones, each cost 1. Works on bytes.
std::size_t edit_distance(std::string_view a, std::string_view b);

/// Up to `max_count` of `candidates` close to `unknown`, closest first (ties by name).
///
/// A dotted name is compared whole and also by its last segment, so a right leaf under a wrong
/// path ("pert0.bic.id_registers" for "pert0.shell.bic.id_registers") is found as well as a typo.
/// A candidate's score is min(whole distance, last-segment distance + 1); it is offered only if
/// the whole distance is at most max(1, length/4) (and not every character of `unknown` changed),
/// or the last segments differ by at most (last-segment length)/4 edits, so unrelated names are
/// not suggested.
std::vector<std::string> closest_names(std::string_view unknown,
                                       const std::vector<std::string_view>& candidates,
                                       std::size_t max_count = 3);

/// "; did you mean 'NAME'?" for the closest of `candidates` to `unknown`, or "" if none is
/// close: the tail of a message that names one suggestion.
std::string did_you_mean(std::string_view unknown, const std::vector<std::string_view>& candidates);

}  // namespace rtsim
