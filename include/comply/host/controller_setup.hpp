#pragma once
// Builds a wrapper configuration for the command line: from a controller YAML file, or, without
// one, the defaults for a robot and a plugin.

#include <Eigen/Geometry>
#include <string>

#include "comply/pipeline/config.hpp"

namespace comply::host {

/// `config_file` empty: the documented defaults for `robot` and `plugin`. Otherwise the file, with
/// `robot` and `plugin` (when non-empty) overriding what it names. Throws with a clear message.
pipeline::WrapperConfig controllerConfig(const std::string& robot, const std::string& plugin,
                                         const std::string& config_file = {});

/// For runs that try one controller file on several robots (`comply sim`): like
/// controllerConfig(), but a non-empty `robot` replaces the robot the file names, as long as the
/// file leaves joints and frames to the robot's defaults (they would belong to the other robot).
pipeline::WrapperConfig simControllerConfig(const std::string& robot, const std::string& plugin,
                                            const std::string& config_file);

/// TCP pose of a robot at its home joint positions, base frame: where a simulated run starts.
struct TcpPose {
  Eigen::Vector3d position;
  Eigen::Quaterniond orientation;
};
TcpPose homeTcpPose(const std::string& robot);

}  // namespace comply::host
