// SPDX-License-Identifier: MIT
#pragma once
// Closest names to a misspelt one ("smi.kdee" -> "smi.kde", "Normal" -> "normal"): the one
// suggestion logic of smi-lua's messages (member names of the smi tables, `smi-lua doc NAME`,
// a study's unknown option).
#include <string>
#include <vector>

namespace smi {

/// Edit distance (insertions, deletions, substitutions, transpositions of neighbours), ignoring
/// ASCII case: "Normal" and "normal" are 0 apart, "kdee" and "kde" 1.
std::size_t name_distance(const std::string& a, const std::string& b);

/// Up to `max` candidates closest to `name`, nearest first (ties in the candidates' order), of those
/// within a distance of a third of the name's length (at least 1, at most 3) or holding the name
/// as a prefix or part after its last '.' / ':' (e.g. "kde" finds "smi.kde").
std::vector<std::string> closest(const std::string& name, const std::vector<std::string>& candidates,
                                 std::size_t max = 3);

}  // namespace smi
