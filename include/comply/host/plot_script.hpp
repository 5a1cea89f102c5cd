#pragma once
// Plots are drawn by Python scripts under scripts/ (matplotlib): one helper runs them, so a missing
// matplotlib is a warning with its reason, never a failed run.

#include <iosfwd>
#include <string>
#include <vector>

namespace comply::host {

/// Runs scripts/<script> with `arguments` under Debian's python3; on failure writes a warning with
/// the script's last output line to `err` and returns false.
bool runPlotScript(const std::string& script, const std::vector<std::string>& arguments,
                   std::ostream& err);

}  // namespace comply::host
