#pragma once
// `comply inspect FILE`: what a recording holds (channels, message counts, rates, time span,
// dropped records), read from its start so that a file cut short by a crash is shown too.

#include <iosfwd>
#include <string>

namespace comply::app {

struct InspectOptions {
  std::string file;
  bool json = false;  ///< one JSON object instead of the table
};

/// Prints it; returns the exit code (0 ok, 1 the file is incomplete, 2 not readable).
int inspectCommand(const InspectOptions& options, std::ostream& out, std::ostream& err);

}  // namespace comply::app
