// Reading the controller file's walls: and boxes: lists (wall_geometry.hpp). Each entry is
// checked on its own and named in the error ("walls[1].normal"): a wall with a zero or non-unit
// normal, a box whose min is not below its max, or a number that is not finite is refused, never
// guessed at.

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <string>

#include "comply/core/input_error.hpp"
#include "config_options.hpp"

namespace comply::pipeline::options {
namespace {

// A normal written to a few digits ([0.7071, 0.7071, 0]) is taken, renormalised; one further off
// is a mistake the file should say.
constexpr double kNormalTolerance = 1e-3;

struct EntryReporter {
  const std::string& source;
  const std::string& root;
  [[noreturn]] void fail(InputErrc code, const std::string& key, const std::string& message) const {
    throw InputError(code, source, root + "." + key, message);
  }
};

Eigen::Vector3d readPoint(const YAML::Node& entry, const char* name, const std::string& key,
                          const EntryReporter& report) {
  const YAML::Node node = entry[name];
  if (!node) {
    report.fail(InputErrc::kMissingKey, key, "is required");
  }
  std::vector<double> numbers;
  try {
    numbers = node.as<std::vector<double>>();
  } catch (const YAML::Exception&) {
    report.fail(InputErrc::kWrongType, key, "must be [x, y, z] in metres, base frame");
  }
  if (numbers.size() != 3) {
    report.fail(InputErrc::kWrongSize, key, "must be [x, y, z] in metres, base frame");
  }
  const Eigen::Vector3d point(numbers[0], numbers[1], numbers[2]);
  if (!point.allFinite()) {
    report.fail(InputErrc::kOutOfRange, key, "must be finite");
  }
  return point;
}

void onlyKeys(const YAML::Node& entry, const char* first, const char* second,
              const std::string& key, const EntryReporter& report) {
  if (!entry.IsMap()) {
    report.fail(InputErrc::kWrongType, key,
                std::string("must be a mapping with ") + first + " and " + second);
  }
  for (const auto& item : entry) {
    const auto name = item.first.as<std::string>();
    if (name != first && name != second) {
      report.fail(InputErrc::kUnknownKey, key + "." + name, "is not a known key");
    }
  }
}

WallPlane readWall(const YAML::Node& entry, const std::string& key, const EntryReporter& report) {
  onlyKeys(entry, "point", "normal", key, report);
  WallPlane wall;
  wall.point = readPoint(entry, "point", key + ".point", report);
  wall.normal = readPoint(entry, "normal", key + ".normal", report);
  const double norm = wall.normal.norm();
  if (norm == 0.0) {
    report.fail(InputErrc::kInvalidValue, key + ".normal", "must not be zero");
  }
  if (std::abs(norm - 1.0) > kNormalTolerance) {
    report.fail(InputErrc::kInvalidValue, key + ".normal",
                "must be a unit vector (its norm is " + std::to_string(norm) + ")");
  }
  wall.normal /= norm;
  return wall;
}

WallBox readBox(const YAML::Node& entry, const std::string& key, const EntryReporter& report) {
  onlyKeys(entry, "min", "max", key, report);
  WallBox box;
  box.min = readPoint(entry, "min", key + ".min", report);
  box.max = readPoint(entry, "max", key + ".max", report);
  if (!(box.min.array() < box.max.array()).all()) {
    report.fail(InputErrc::kInconsistent, key + ".min",
                "must be below max on every axis (a box the TCP is kept inside)");
  }
  return box;
}

template <typename Entry, typename Read>
std::vector<Entry> readList(const YAML::Node& parameters, const char* name,
                            const EntryReporter& report, Read read) {
  std::vector<Entry> entries;
  const YAML::Node list = parameters[name];
  if (!list || list.IsNull()) {
    return entries;
  }
  if (!list.IsSequence()) {
    report.fail(InputErrc::kWrongType, name, "must be a list");
  }
  for (std::size_t i = 0; i < list.size(); ++i) {
    entries.push_back(read(list[i], std::string(name) + "[" + std::to_string(i) + "]", report));
  }
  return entries;
}

}  // namespace

void readWalls(const YAML::Node& parameters, const std::string& source, const std::string& root,
               WallConfig& walls) {
  const EntryReporter report{source, root};
  walls.planes = readList<WallPlane>(parameters, "walls", report, readWall);
  walls.boxes = readList<WallBox>(parameters, "boxes", report, readBox);
  WallSet set;
  if (!compileWalls(walls.planes, walls.boxes, set)) {
    report.fail(InputErrc::kWrongSize, "walls",
                "with boxes: more than " + std::to_string(kMaxWallPlanes) +
                    " planes (each box counts six)");
  }
}

}  // namespace comply::pipeline::options
