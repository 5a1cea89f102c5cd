#pragma once
// `comply validate`: synthetic inputs through model + plugin (and optionally the whole wrapper)
// on the host, before deployment. Each input sample holds `q`, `dq`, optionally `effort`, and a
// `command` object with the command schema's field names. Per sample the output holds the model
// quantities, the law's torque and, with --wrapper, the wrapper's torque for the samples fed as
// a sequence of cycles.

#include <cstddef>
#include <iosfwd>
#include <nlohmann/json.hpp>
#include <string>

#include "comply/core/input_error.hpp"

namespace comply::app {

/// Most samples one validate run takes: each becomes a few kilobytes of output in memory.
inline constexpr std::size_t kMaxValidateSamples = 100'000;

struct ValidateOptions {
  std::string robot;
  std::string plugin;
  std::string config_file;
  std::string inputs;
  std::string expected;
  std::string out;
  double tolerance = 1e-9;  ///< max absolute error per output before the run fails
  double period_s = 0.001;  ///< cycle period of the --wrapper sequence
  bool wrapper = false;
};

/// Runs every sample and returns the output document. Throws InputError for an unusable input
/// file, the message naming the file, sample and field.
nlohmann::json runValidation(const ValidateOptions& options);

/// Max absolute error per output key between `actual` and `expected` documents (only keys the
/// expected samples hold). Throws InputError on a mismatch in shape or an unknown key.
std::map<std::string, double> compareOutputs(const nlohmann::json& actual,
                                             const nlohmann::json& expected);

/// The command line entry: 0 = done (and within tolerance), 1 = above tolerance, 2 = bad input.
int validateCommand(const ValidateOptions& options, std::ostream& out, std::ostream& err);

}  // namespace comply::app
