#include "comply/host/task_file.hpp"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <stdexcept>

#include "comply/core/text_file.hpp"
#include "comply/schema/json.hpp"
#include "task_file_reading.hpp"

namespace comply::host {
namespace {

using nlohmann::json;
using task_reading::checkUnitQuaternion;
using task_reading::numbers;
using task_reading::positiveNumber;
using task_reading::TaskError;

// Most waypoints a task may list: waypoints are interpolated at the command rate, so even the
// longest run (600 s) needs far fewer; a generated file with more is a mistake.
constexpr std::size_t kMaxWaypoints = 100'000;

std::filesystem::path scenePath(const json& value, const std::filesystem::path& folder,
                                const std::string& where, const TaskError& error) {
  if (!value.is_string()) {
    error.fail(where, "must be a file path");
  }
  const std::filesystem::path path(value.get<std::string>());
  return path.is_absolute() ? path : folder / path;
}

void readScene(const json& scene, const std::filesystem::path& folder, TaskFile& task,
               const TaskError& error) {
  const std::set<std::string> known{"tool", "objects", "substeps", "seed"};
  for (const auto& [key, value] : scene.items()) {
    if (known.count(key) == 0) {
      error.fail("task.scene", "unknown key '" + key + "' (known: tool, objects, substeps, seed)");
    }
  }
  if (scene.contains("tool")) {
    task.scene.tool = scenePath(scene["tool"], folder, "task.scene.tool", error);
  }
  if (scene.contains("objects")) {
    const json& objects = scene["objects"];
    if (!objects.is_array()) {
      error.fail("task.scene.objects", "must be a list of file paths");
    }
    for (std::size_t i = 0; i < objects.size(); ++i) {
      task.scene.objects.push_back(
          scenePath(objects[i], folder, "task.scene.objects[" + std::to_string(i) + "]", error));
    }
  }
  const auto count = [&](const std::string& key, double minimum) {
    const json& value = scene[key];
    if (!value.is_number() || value.get<double>() < minimum ||
        value.get<double>() != std::floor(value.get<double>())) {
      error.fail("task.scene." + key, "must be a whole number >= " + std::to_string(int(minimum)));
    }
    return value.get<double>();
  };
  if (scene.contains("substeps")) {
    task.substeps = static_cast<int>(count("substeps", 1));
  }
  if (scene.contains("seed")) {
    task.seed = static_cast<std::uint64_t>(count("seed", 0));
  }
}

void readCamera(const json& camera, TaskFile& task, const TaskError& error) {
  for (const auto& [key, value] : camera.items()) {
    if (key == "lookat") {
      const std::vector<double> lookat = numbers(value, 3, "task.camera.lookat", error);
      std::copy(lookat.begin(), lookat.end(), task.camera.lookat);
    } else if (key == "distance_m") {
      task.camera.distance_m = positiveNumber(camera, key, 0.0, "task.camera", error);
    } else if (key == "azimuth_deg" || key == "elevation_deg") {
      if (!value.is_number()) {
        error.fail("task.camera." + key, "must be a number");
      }
      (key == "azimuth_deg" ? task.camera.azimuth_deg : task.camera.elevation_deg) =
          value.get<double>();
    } else {
      error.fail("task.camera", "unknown key '" + key +
                                    "' (known: lookat, distance_m, azimuth_deg, elevation_deg)");
    }
  }
}

Eigen::Vector3d vector3(const json& value, const std::string& where, const TaskError& error) {
  const std::vector<double> v = numbers(value, 3, where, error);
  return {v[0], v[1], v[2]};
}

// The darboux frame needs a surface normal that the other two frames ignore, so the two keys are
// checked together.
void readPathFrame(const json& path, task::PathCommandOptions& options, const TaskError& error) {
  const std::string frame = path.value("frame", std::string("frenet"));
  if (frame == "frenet") {
    options.frame = task::FrameSource::kFrenet;
  } else if (frame == "darboux") {
    options.frame = task::FrameSource::kDarboux;
    if (!path.contains("surface_normal")) {
      error.fail("task.path", "frame darboux needs surface_normal [x, y, z]");
    }
    const Eigen::Vector3d normal =
        vector3(path["surface_normal"], "task.path.surface_normal", error);
    if (normal.norm() < 1e-9) {
      error.fail("task.path.surface_normal", "must not be zero");
    }
    options.surface_normal = [unit = normal.normalized()](const Eigen::Vector3d&) { return unit; };
  } else if (frame == "fixed") {
    options.frame = task::FrameSource::kFixed;
  } else {
    error.fail("task.path.frame", "must be frenet, darboux or fixed");
  }
}

// Orientation, gains and offset are all given in the task frame, so they are read as one group.
void readPathTaskFrame(const json& path, double quaternion_tolerance,
                       task::PathCommandOptions& options, const TaskError& error) {
  const auto quaternion = [&](const char* key) {
    const std::vector<double> q = numbers(path[key], 4, std::string("task.path.") + key, error);
    checkUnitQuaternion(q, quaternion_tolerance, std::string("task.path.") + key, error);
    return schema::fromXyzw(q.data()).normalized();
  };
  if (path.contains("task_frame")) {
    options.fixed_task_frame = quaternion("task_frame");
  }
  if (path.contains("orientation")) {
    options.orientation = quaternion("orientation");
  }
  for (const char* key : {"stiffness_translational", "stiffness_rotational"}) {
    if (path.contains(key)) {
      const Eigen::Vector3d k = vector3(path[key], std::string("task.path.") + key, error);
      if ((k.array() < 0.0).any()) {
        error.fail(std::string("task.path.") + key, "must be >= 0 per task axis");
      }
      (std::string(key) == "stiffness_translational" ? options.stiffness_translational
                                                     : options.stiffness_rotational) = k;
    }
  }
  if (path.contains("damping_ratio")) {
    options.damping_ratio = positiveNumber(path, "damping_ratio", 1.0, "task.path", error);
  }
  if (path.contains("offset")) {
    options.offset_in_task_frame = vector3(path["offset"], "task.path.offset", error);
  }
}

void readPath(const json& path, double quaternion_tolerance, TaskFile& task,
              const TaskError& error) {
  const std::set<std::string> known{"start_time_s",
                                    "speed_m_per_s",
                                    "points",
                                    "frame",
                                    "surface_normal",
                                    "task_frame",
                                    "stiffness_translational",
                                    "stiffness_rotational",
                                    "damping_ratio",
                                    "offset",
                                    "orientation"};
  for (const auto& [key, value] : path.items()) {
    if (known.count(key) == 0) {
      error.fail("task.path", "unknown key '" + key + "'");
    }
  }
  task::PathCommandOptions& options = task.path_options;
  if (!path.contains("start_time_s") || !path["start_time_s"].is_number() ||
      path["start_time_s"].get<double>() < 0.0) {
    error.fail("task.path", "needs start_time_s, a number >= 0 [s]");
  }
  options.start_time_s = path["start_time_s"].get<double>();
  options.speed_m_per_s =
      positiveNumber(path, "speed_m_per_s", options.speed_m_per_s, "task.path", error);
  if (!path.contains("points") || !path["points"].is_array() || path["points"].size() < 2) {
    error.fail("task.path.points", "needs a list of at least two [x, y, z] points");
  }
  std::vector<Eigen::Vector3d> points;
  for (std::size_t i = 0; i < path["points"].size(); ++i) {
    points.push_back(
        vector3(path["points"][i], "task.path.points[" + std::to_string(i) + "]", error));
  }
  task.path_points = points;
  readPathFrame(path, options, error);
  readPathTaskFrame(path, quaternion_tolerance, options, error);
  try {
    (void)task::Path(points);
  } catch (const std::invalid_argument& invalid) {
    error.fail("task.path.points", invalid.what());
  }
}

/// The command fields of a waypoint (every key left in `object`), typed and checked now so that a
/// bad task fails before the run; `keys` says which were given.
template <typename Command>
Command commandFields(const json& object, int dof, const std::string& where, schema::FieldSet& keys,
                      const TaskError& error, double quaternion_tolerance) {
  schema::ReadOptions<Command> options;
  options.allow_shorthand = true;
  options.source = error.source();
  options.key_prefix = where + ".";
  schema::Parsed<Command> parsed = schema::fromJson(object, dof, options);
  schema::CheckOptions check;
  check.quaternion_tolerance = quaternion_tolerance;
  const schema::CheckResult result = schema::checkFields(parsed.command, dof, check);
  if (!result.ok()) {
    error.fail(where + "." + result.field, result.message);
  }
  keys = parsed.keys;
  return parsed.command;
}

Waypoint readWaypoint(json object, std::size_t index, bool cartesian, int dof,
                      double quaternion_tolerance, const TaskError& error) {
  const std::string where = "waypoint " + std::to_string(index);
  if (!object.is_object()) {
    error.fail(where, "must be a map of keys");
  }
  Waypoint waypoint;
  if (!object.contains("time_s") || !object["time_s"].is_number() ||
      object["time_s"].get<double>() < 0.0) {
    error.fail(where, "needs time_s, a number >= 0 [s]");
  }
  waypoint.time_s = object["time_s"].get<double>();
  object.erase("time_s");
  if (object.contains("interpolate")) {
    const json& value = object["interpolate"];
    if (value == "linear") {
      waypoint.interpolate = Interpolation::kLinear;
    } else if (value == "smooth") {
      waypoint.interpolate = Interpolation::kSmooth;
    } else if (value == "step") {
      waypoint.interpolate = Interpolation::kStep;
    } else {
      error.fail(where + ".interpolate", "must be linear, smooth or step");
    }
    object.erase("interpolate");
  }
  const std::size_t length = cartesian ? 3 : static_cast<std::size_t>(dof);
  if (object.contains("position") && object.contains("position_offset")) {
    error.fail(where, "give position or position_offset, not both");
  }
  for (const char* key : {"position", "position_offset"}) {
    if (object.contains(key)) {
      (std::string(key) == "position" ? waypoint.position : waypoint.position_offset) =
          numbers(object[key], length, where + "." + key, error);
      object.erase(key);
    }
  }
  if (object.contains("orientation")) {
    if (!cartesian) {
      error.fail(where, "orientation is a Cartesian target; this controller takes joint targets");
    }
    waypoint.orientation = numbers(object["orientation"], 4, where + ".orientation", error);
    checkUnitQuaternion(*waypoint.orientation, quaternion_tolerance, where + ".orientation", error);
    object.erase("orientation");
  }
  for (const char* motion : {"velocity", "twist"}) {
    if (object.contains(motion)) {
      error.fail(where, std::string(motion) +
                            " is derived from the waypoint times; give positions and times");
    }
  }
  if (cartesian) {
    waypoint.command = commandFields<CartesianCommand>(object, dof, where, waypoint.keys, error,
                                                       quaternion_tolerance);
  } else {
    waypoint.command =
        commandFields<JointCommand>(object, dof, where, waypoint.keys, error, quaternion_tolerance);
  }
  return waypoint;
}

}  // namespace

TaskFile parseTaskFile(const std::string& yaml_text, const std::string& source,
                       const std::filesystem::path& folder, bool cartesian, int dof,
                       double quaternion_tolerance) {
  const TaskError error(source);
  YAML::Node root;
  try {
    root = YAML::Load(yaml_text);
  } catch (const YAML::Exception& yaml_error) {
    error.fail("", std::string("not valid YAML: ") + yaml_error.what());
  }
  if (!root.IsMap() || !root["task"] || !root["task"].IsMap()) {
    error.fail(
        "", "needs a top-level 'task' map (see include/comply/host/task_file.hpp or examples/sim)");
  }
  const json task_json = schema::yamlToJson(root["task"], source, "task");

  TaskFile task;
  task.path = source;
  const std::set<std::string> known{"duration_s",        "command_rate_hz", "scene", "camera",
                                    "snapshot_every_ms", "waypoints",       "path"};
  for (const auto& [key, value] : task_json.items()) {
    if (known.count(key) == 0) {
      error.fail("task", "unknown key '" + key +
                             "' (known: duration_s, command_rate_hz, scene, camera, "
                             "snapshot_every_ms, waypoints, path)");
    }
  }
  task.duration_s = positiveNumber(task_json, "duration_s", task.duration_s, "task", error);
  if (task.duration_s > kMaxSimDurationS) {
    error.fail("task.duration_s", "at most " + std::to_string(static_cast<int>(kMaxSimDurationS)) +
                                      " s (the log is kept in memory); longer runs: comply run");
  }
  task.command_rate_hz =
      positiveNumber(task_json, "command_rate_hz", task.command_rate_hz, "task", error);
  if (task_json.contains("snapshot_every_ms")) {
    const json& value = task_json["snapshot_every_ms"];
    if (!value.is_number() || value.get<double>() < 0.0) {
      error.fail("task.snapshot_every_ms", "must be a number >= 0 (0: start and end only)");
    }
    task.snapshot_every_ms = value.get<double>();
  }
  if (task_json.contains("scene")) {
    readScene(task_json["scene"], folder, task, error);
  }
  if (task_json.contains("camera")) {
    readCamera(task_json["camera"], task, error);
  }
  if (task_json.contains("path")) {
    if (!cartesian) {
      error.fail("task.path",
                 "a path streams Cartesian commands; this controller takes joint ones");
    }
    readPath(task_json["path"], quaternion_tolerance, task, error);
  }
  if (!task_json.contains("waypoints") || !task_json["waypoints"].is_array() ||
      task_json["waypoints"].empty()) {
    error.fail("task", "needs a non-empty list 'waypoints'");
  }
  if (task_json["waypoints"].size() > kMaxWaypoints) {
    error.fail("task.waypoints", "has " + std::to_string(task_json["waypoints"].size()) +
                                     " entries, more than " + std::to_string(kMaxWaypoints));
  }
  const json& waypoints = task_json["waypoints"];
  for (std::size_t i = 0; i < waypoints.size(); ++i) {
    task.waypoints.push_back(
        readWaypoint(waypoints[i], i, cartesian, dof, quaternion_tolerance, error));
    if (i > 0 && task.waypoints[i].time_s < task.waypoints[i - 1].time_s) {
      error.fail("waypoint " + std::to_string(i), "time_s goes backwards");
    }
  }
  return task;
}

TaskFile loadTaskFile(const std::filesystem::path& file, bool cartesian, int dof,
                      double quaternion_tolerance) {
  const TextFile text = readTextFile(file);
  if (!text.ok()) {
    throw std::runtime_error("task file: " + text.error);
  }
  return parseTaskFile(text.text, file.string(), file.parent_path(), cartesian, dof,
                       quaternion_tolerance);
}

}  // namespace comply::host
