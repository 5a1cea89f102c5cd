#pragma once
// Shared set-up of the simulation tests: controller configs and task files for the runs.

#include <filesystem>
#include <string>

#include "comply/pipeline/config.hpp"
#include "controller_setup.hpp"
#include "task_file.hpp"

namespace comply::testing {

inline const std::filesystem::path kSourceDir = COMPLY_TEST_SOURCE_DIR;

/// A task from YAML text, for a Cartesian or joint controller of `dof` joints.
inline app::TaskFile taskFromYaml(const std::string& yaml, bool cartesian, int dof) {
  return app::parseTaskFile(yaml, "test task", kSourceDir / "examples" / "sim", cartesian, dof);
}

/// config/sim/cartesian_impedance.yaml on `robot`.
inline pipeline::WrapperConfig simCartesianConfig(const std::string& robot) {
  return app::simControllerConfig(
      robot, "", (kSourceDir / "config" / "sim" / "cartesian_impedance.yaml").string());
}

}  // namespace comply::testing
