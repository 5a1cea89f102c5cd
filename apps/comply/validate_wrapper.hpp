#pragma once
// `comply validate --wrapper`: the samples fed to the whole wrapper as consecutive cycles. The
// sample type and the command parsing live here because the law-only run shares them, and a
// sample must mean the same command to both.

#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "comply/core/input_error.hpp"
#include "comply/core/state.hpp"
#include "comply/pipeline/resolved_controller.hpp"
#include "comply/schema/json.hpp"
#include "validate_command.hpp"

namespace comply::app {

/// One input sample: the measured joint state and the command given with it.
struct ValidateSample {
  JointState state;
  bool has_effort = false;
  nlohmann::json command = nlohmann::json::object();
};

/// Parses a sample's command on top of `base`; a malformed command throws InputError.
template <typename Command>
Command parseSampleCommand(const nlohmann::json& object, int dof, const Command& base,
                           const std::string& where) {
  schema::ReadOptions<Command> options;
  options.base = base;
  options.source = where + ": command";
  return schema::fromJson(object, dof, options).command;
}

/// The samples as consecutive cycles of one wrapper, activated at the first sample, run by the
/// control loop every host uses. Adds wrapper_torque, wrapper_state and, for a rejected command,
/// wrapper_rejected to each sample of `outputs`.
void runWrapper(const std::shared_ptr<const pipeline::ResolvedController>& resolved,
                const std::vector<ValidateSample>& samples, double period_s,
                const std::string& inputs_path, nlohmann::json& outputs);

}  // namespace comply::app
