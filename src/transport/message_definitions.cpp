// A type's definition with its dependencies, as rosbag2 writes it into an MCAP schema.

#include "message_definitions.hpp"

#include <sstream>
#include <stdexcept>
#include <vector>

#include "comply/transport/cdr.hpp"

namespace comply::transport {
namespace {

// The standard types comply's messages use, as ROS 2 defines them.
constexpr std::string_view kTime = "int32 sec\nuint32 nanosec\n";
constexpr std::string_view kHeader = "builtin_interfaces/Time stamp\nstring frame_id\n";
// A recording's camera frames (compressed_image.hpp); the comments of ROS 2's file left out.
constexpr std::string_view kCompressedImage =
    "std_msgs/Header header\nstring format\nuint8[] data\n";

bool isPrimitive(std::string_view type) {
  static constexpr std::string_view kPrimitives[] = {
      "bool",   "byte",  "char",   "int8",    "uint8",   "int16",  "uint16", "int32",
      "uint32", "int64", "uint64", "float32", "float64", "string", "wstring"};
  for (const std::string_view primitive : kPrimitives) {
    if (type == primitive || type.starts_with(std::string(primitive) + "<=")) {
      return true;
    }
  }
  return false;
}

/// "pkg/Type" of a field type as written in a .msg of `package`.
std::string qualified(std::string type, std::string_view package) {
  if (const std::size_t bracket = type.find('['); bracket != std::string::npos) {
    type.erase(bracket);
  }
  if (type == "Header") {
    return "std_msgs/Header";
  }
  if (const std::size_t slash = type.find('/'); slash != std::string::npos) {
    return type;
  }
  return std::string(package) + "/" + type;
}

/// "pkg/Type" (or "pkg/msg/Type") -> the .msg text.
std::string_view textOf(const std::string& type) {
  if (type == "builtin_interfaces/Time") {
    return kTime;
  }
  if (type == "std_msgs/Header") {
    return kHeader;
  }
  if (type == "sensor_msgs/CompressedImage") {
    return kCompressedImage;
  }
  const std::size_t slash = type.rfind('/');
  if (type.starts_with("comply_msgs/")) {
    const auto& texts = complyMessageTexts();
    if (const auto found = texts.find(type.substr(slash + 1)); found != texts.end()) {
      return found->second;
    }
  }
  throw std::out_of_range("no message definition for " + type);
}

/// The non-primitive field types of `text`, in order of appearance.
std::vector<std::string> usedTypes(std::string_view text, std::string_view package) {
  std::vector<std::string> types;
  std::istringstream lines{std::string(text)};
  std::string line;
  while (std::getline(lines, line)) {
    const std::size_t comment = line.find('#');
    std::istringstream words(line.substr(0, comment));
    std::string type;
    std::string name;
    if (!(words >> type >> name) || name.find('=') != std::string::npos) {
      continue;  // blank, comment or constant
    }
    std::string bare = type.substr(0, type.find('['));
    if (!isPrimitive(bare)) {
      types.push_back(qualified(type, package));
    }
  }
  return types;
}

void appendDependencies(const std::string& type, std::vector<std::string>& seen) {
  const std::string package = type.substr(0, type.find('/'));
  for (const std::string& used : usedTypes(textOf(type), package)) {
    bool known = false;
    for (const std::string& s : seen) {
      known = known || s == used;
    }
    if (!known) {
      seen.push_back(used);
      appendDependencies(used, seen);
    }
  }
}

}  // namespace

std::string ros2MessageDefinition(std::string_view type_name) {
  std::string type(type_name);
  if (const std::size_t at = type.find("/msg/"); at != std::string::npos) {
    type.erase(at, 4);
  }
  std::string definition(textOf(type));
  std::vector<std::string> dependencies;
  appendDependencies(type, dependencies);
  for (const std::string& dependency : dependencies) {
    if (!definition.ends_with('\n')) {
      definition += '\n';
    }
    definition += std::string(80, '=') + "\nMSG: " + dependency + "\n";
    definition += textOf(dependency);
  }
  return definition;
}

}  // namespace comply::transport
