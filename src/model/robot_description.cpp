#include "comply/model/robot_description.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cstdlib>
#include <sstream>

#include "comply/core/install_paths.hpp"
#include "comply/core/text_file.hpp"
#include "comply/model/model_error.hpp"

namespace comply::model {
namespace {

constexpr const char* kRobotFile = "robot.yaml";

[[noreturn]] void fail(const std::filesystem::path& file, const std::string& message) {
  throw ModelError(ModelErrc::kInvalidDescription, file.string() + ": " + message);
}

std::string requireString(const YAML::Node& root, const char* key,
                          const std::filesystem::path& file) {
  const YAML::Node node = root[key];
  if (!node || !node.IsScalar()) {
    fail(file, std::string("missing or non-scalar key '") + key + "'");
  }
  return node.as<std::string>();
}

template <typename T>
std::vector<T> readList(const YAML::Node& root, const char* key, const std::filesystem::path& file,
                        std::size_t expected_size) {
  const YAML::Node node = root[key];
  if (!node || !node.IsSequence()) {
    fail(file, std::string("missing list '") + key + "'");
  }
  std::vector<T> values;
  try {
    values = node.as<std::vector<T>>();
  } catch (const YAML::Exception& error) {
    fail(file, std::string("list '") + key + "' has an entry of the wrong type: " + error.what());
  }
  if (expected_size != 0 && values.size() != expected_size) {
    fail(file, std::string("list '") + key + "' has " + std::to_string(values.size()) +
                   " entries, expected one per joint (" + std::to_string(expected_size) + ")");
  }
  return values;
}

bool looksLikePath(std::string_view name_or_path) {
  // A name that cannot even be looked at (a symlink loop) is a path too; one that is not there is
  // a robot's name to search for.
  std::error_code error;
  const bool folder = std::filesystem::is_directory(name_or_path, error);
  return name_or_path.find('/') != std::string_view::npos || name_or_path.find('.') == 0 ||
         folder || (error && error != std::errc::no_such_file_or_directory);
}

RobotDescription parseFolder(const std::filesystem::path& folder) {
  const std::filesystem::path file = folder / kRobotFile;
  if (!std::filesystem::is_regular_file(file)) {
    throw ModelError(ModelErrc::kFileNotFound,
                     "no " + std::string(kRobotFile) + " in '" + folder.string() + "'");
  }
  const TextFile text = readTextFile(file);
  if (!text.ok()) {
    fail(file, text.error);
  }
  YAML::Node root;
  try {
    root = YAML::Load(text.text);
  } catch (const YAML::Exception& error) {
    fail(file, std::string("not valid YAML: ") + error.what());
  }
  RobotDescription robot;
  robot.folder = std::filesystem::absolute(folder);
  robot.name = requireString(root, "name", file);
  robot.description = root["description"] ? root["description"].as<std::string>() : robot.name;
  robot.urdf_path = robot.folder / requireString(root, "urdf", file);
  robot.joints = readList<std::string>(root, "joints", file, 0);
  if (robot.joints.empty()) {
    fail(file, "'joints' is empty");
  }
  const std::size_t dof = robot.joints.size();
  robot.base_frame = requireString(root, "base_frame", file);
  robot.flange_frame = requireString(root, "flange_frame", file);
  robot.tcp_frame = requireString(root, "tcp_frame", file);
  robot.home = readList<double>(root, "home", file, dof);
  if (const YAML::Node friction = root["friction"]) {
    const std::string model = friction["model"] ? friction["model"].as<std::string>() : "";
    if (model != "sigmoid") {
      fail(file, "friction.model must be 'sigmoid', got '" + model + "'");
    }
    robot.friction = SigmoidFriction{readList<double>(friction, "phi1", file, dof),
                                     readList<double>(friction, "phi2", file, dof),
                                     readList<double>(friction, "phi3", file, dof)};
  }
  if (const YAML::Node dynamics = root["joint_dynamics"]) {
    robot.joint_dynamics = JointDynamics{readList<double>(dynamics, "damping", file, dof),
                                         readList<double>(dynamics, "armature", file, dof),
                                         readList<double>(dynamics, "frictionloss", file, dof)};
  }
  return robot;
}

}  // namespace

ModelOptions RobotDescription::modelOptions(const std::string& tip) const {
  ModelOptions options;
  options.joint_names = joints;
  options.base_frame = base_frame;
  options.tip_frame = tip.empty() ? tcp_frame : tip;
  return options;
}

Model RobotDescription::loadModel(const std::string& tip) const {
  return loadModel(modelOptions(tip));
}

Model RobotDescription::loadModel(const ModelOptions& options) const {
  return urdf_xml.empty() ? Model::fromUrdfFile(urdf_path, options)
                          : Model::fromUrdfString(urdf_xml, options);
}

std::vector<std::filesystem::path> robotSearchPath() {
  return searchPath("COMPLY_ROBOT_PATH", COMPLY_ROBOTS_RELDIR, COMPLY_DEFAULT_ROBOTS_DIR);
}

std::vector<std::string> availableRobots() {
  std::vector<std::string> names;
  for (const auto& folder : robotSearchPath()) {
    std::error_code error;
    for (const auto& entry : std::filesystem::directory_iterator(folder, error)) {
      if (std::filesystem::is_regular_file(entry.path() / kRobotFile)) {
        names.push_back(entry.path().filename().string());
      }
    }
  }
  std::sort(names.begin(), names.end());
  names.erase(std::unique(names.begin(), names.end()), names.end());
  return names;
}

RobotDescription loadRobotDescription(std::string_view name_or_path) {
  if (looksLikePath(name_or_path)) {
    const std::filesystem::path folder(name_or_path);
    std::error_code error;
    if (!std::filesystem::is_directory(folder, error)) {
      throw ModelError(ModelErrc::kFileNotFound,
                       "robot folder '" + folder.string() + "' " +
                           (error ? "cannot be read: " + fileErrorText(error) : "does not exist"));
    }
    return parseFolder(folder);
  }
  for (const auto& folder : robotSearchPath()) {
    const std::filesystem::path candidate = folder / std::string(name_or_path);
    if (std::filesystem::is_regular_file(candidate / kRobotFile)) {
      return parseFolder(candidate);
    }
  }
  std::string known;
  for (const auto& name : availableRobots()) {
    known += (known.empty() ? "" : ", ") + name;
  }
  throw ModelError(ModelErrc::kUnknownRobot,
                   "no robot named '" + std::string(name_or_path) +
                       "' (available: " + (known.empty() ? "none" : known) +
                       "); pass a folder path or add its parent to COMPLY_ROBOT_PATH");
}

}  // namespace comply::model
