#pragma once
// Shared set-up of the simulation tests: controller configs and task files for the runs.

#include <filesystem>
#include <ostream>
#include <string>

#include "comply/host/controller_setup.hpp"
#include "comply/host/sim_session.hpp"
#include "comply/host/task_file.hpp"
#include "comply/pipeline/config.hpp"

namespace comply::testing {

inline const std::filesystem::path kSourceDir = COMPLY_TEST_SOURCE_DIR;

/// A task from YAML text, for a Cartesian or joint controller of `dof` joints.
inline host::TaskFile taskFromYaml(const std::string& yaml, bool cartesian, int dof) {
  return host::parseTaskFile(yaml, "test task", kSourceDir / "examples" / "sim", cartesian, dof);
}

/// config/sim/cartesian_impedance.yaml on `robot`.
inline pipeline::WrapperConfig simCartesianConfig(const std::string& robot) {
  return host::simControllerConfig(
      robot, "", (kSourceDir / "config" / "sim" / "cartesian_impedance.yaml").string());
}

/// A run of config/sim/cartesian_impedance.yaml on the FR3 with the task examples/sim/<task>.
inline host::SimRunOptions fr3ExampleRun(const std::string& task) {
  host::SimRunOptions run;
  run.config = simCartesianConfig("fr3");
  run.task = host::loadTaskFile(kSourceDir / "examples" / "sim" / task, true, run.config.dof);
  return run;
}

/// An experiment's options writing into a fresh temporary `folder`, its progress into `progress`.
template <typename Options>
Options freshExperiment(const std::string& folder, std::ostream& progress) {
  Options options;
  options.out_dir = std::filesystem::temp_directory_path() / folder;
  std::filesystem::remove_all(options.out_dir);
  options.progress = &progress;
  return options;
}

}  // namespace comply::testing
