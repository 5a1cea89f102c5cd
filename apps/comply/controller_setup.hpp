#pragma once
// Builds a wrapper configuration for the command line: from a controller YAML file, or, without
// one, the defaults for a robot and a plugin.

#include <string>

#include "comply/pipeline/config.hpp"

namespace comply::app {

/// `config_file` empty: the documented defaults for `robot` and `plugin`. Otherwise the file, with
/// `robot` and `plugin` (when non-empty) overriding what it names. Throws with a clear message.
pipeline::WrapperConfig controllerConfig(const std::string& robot, const std::string& plugin,
                                         const std::string& config_file = {});

}  // namespace comply::app
