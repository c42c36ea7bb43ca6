#pragma once
// The seeds as a reader knows them. Sources and figures cite the seed documents the way the
// code does ("seed 000 L584": line 584 of ../shared/reference/seeds/000_*.txt); what a user
// reads says whose work and which line: "Ullner 1983, line 584".
#include <string>
#include <string_view>
#include <vector>

namespace rtsim {

/// The numbers of the seeds `text` cites ("seed 000 L584" -> "000"), each once, in order.
std::vector<std::string> cited_seeds(std::string_view text);

/// A seed's citation: "000" -> "Ullner 1983"; "" for a number that is no seed.
std::string_view seed_author(std::string_view number);

/// `text` with every "seed NNN Lxxx[, Lyyy][-Lzzz]" written for a reader: "Ullner 1983, line
/// 584", "Gaudet 1985, lines 883, 961", "Ullner 1983, lines 572-588". Everything else, and a
/// seed number it does not know, stays as it is.
std::string cite_seeds(std::string_view text);

}  // namespace rtsim
