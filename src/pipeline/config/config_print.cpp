// `comply config --defaults`: the documented controller file, printed from the option table and
// the schema's initial commands, so that the file and the parser cannot disagree.

#include <cmath>
#include <iomanip>
#include <nlohmann/json.hpp>
#include <sstream>

#include "comply/pipeline/config.hpp"
#include "comply/schema/json.hpp"
#include "comply/schema/schema.hpp"
#include "config_options.hpp"

namespace comply::pipeline {
namespace {

constexpr std::size_t kCommentColumn = 39;

std::string formatNumber(double value) {
  std::ostringstream text;
  if (value == std::floor(value) && std::abs(value) < 1e6) {
    text << std::fixed << std::setprecision(1) << value;
  } else {
    text << value;
  }
  return text.str();
}

/// "key: value" at `indent`, the comment aligned at kCommentColumn.
void line(std::ostream& out, int indent, const std::string& text, const std::string& comment) {
  std::string row = std::string(static_cast<std::size_t>(indent), ' ') + text;
  if (!comment.empty()) {
    row += std::string(row.size() < kCommentColumn ? kCommentColumn - row.size() : 1, ' ');
    row += "# " + comment;
  }
  out << row << "\n";
}

/// A JSON value as compact YAML: a list of equal numbers (or an isotropic 3x3 block) as one.
std::string compact(const nlohmann::json& value, schema::FieldKind kind) {
  if (value.is_string()) {
    return value.get<std::string>();
  }
  std::vector<double> numbers;
  for (const auto& entry : value) {
    numbers.push_back(entry.get<double>());
  }
  const bool isotropic_block = kind == schema::FieldKind::kBlock3 && numbers.size() == 9 &&
                               numbers[0] == numbers[4] && numbers[0] == numbers[8] &&
                               numbers[1] == 0 && numbers[2] == 0 && numbers[3] == 0 &&
                               numbers[5] == 0 && numbers[6] == 0 && numbers[7] == 0;
  const bool constant =
      kind != schema::FieldKind::kBlock3 && kind != schema::FieldKind::kQuaternion &&
      std::adjacent_find(numbers.begin(), numbers.end(), std::not_equal_to<>()) == numbers.end();
  if (isotropic_block || constant) {
    return formatNumber(numbers.front());
  }
  std::string list = "[";
  for (std::size_t i = 0; i < numbers.size(); ++i) {
    list += (i == 0 ? "" : ", ") + formatNumber(numbers[i]);
  }
  return list + "]";
}

void printOptions(std::ostream& out) {
  std::vector<std::string> open_sections;
  for (const options::Option& option : options::table()) {
    std::vector<std::string> path = options::keyPath(option.key);
    const std::string leaf = path.back();
    path.pop_back();
    std::size_t common = 0;
    while (common < path.size() && common < open_sections.size() &&
           path[common] == open_sections[common]) {
      ++common;
    }
    if (option.blank_line_before) {
      out << "\n";
    }
    for (std::size_t depth = common; depth < path.size(); ++depth) {
      line(out, 4 + 2 * static_cast<int>(depth), path[depth] + ":", "");
    }
    open_sections = path;
    const int indent = 4 + 2 * static_cast<int>(path.size());
    if (!option.hasDefault()) {
      line(out, indent, "# " + leaf + ": " + option.comment, "");
    } else {
      line(out, indent, leaf + ": " + option.default_text, option.comment);
    }
  }
}

void printInitial(std::ostream& out, bool cartesian) {
  const schema::InitialCommands defaults = schema::defaultInitialCommands(1);
  const nlohmann::json values =
      cartesian ? schema::toJson(defaults.cartesian) : schema::toJson(defaults.joint);
  out << "\n";
  line(out, 4, "initial:", "gains in force until a command sets others");
  for (const schema::FieldInfo& field :
       schema::fields(cartesian ? schema::CommandKind::kCartesian : schema::CommandKind::kJoint)) {
    const bool gain =
        field.group == CommandField::kStiffness || field.group == CommandField::kDamping ||
        field.group == CommandField::kTaskFrame ||
        (field.group == CommandField::kNullspace && field.role == schema::Role::kNone);
    if (!gain || !values.contains(field.name)) {
      continue;
    }
    std::string comment(field.description);
    if (!field.unit.empty() && field.unit != "1") {
      comment += " [" + std::string(field.unit) + "]";
    }
    line(out, 6,
         std::string(field.name) + ": " + compact(values[std::string(field.name)], field.kind),
         comment);
  }
}

}  // namespace

std::string documentedDefaults(const std::string& controller_name, const std::string& plugin,
                               const std::string& robot, const std::string& tip_frame,
                               bool cartesian) {
  std::ostringstream out;
  out << "# " << plugin << " on " << robot
      << ", every wrapper option at its default.\n"
         "# `comply config --defaults` prints this file from the option table the parser reads.\n"
         "# Shaped like a ros2_control controller file: the top-level key names the controller.\n"
         "# Per-joint options take one number (every joint) or one per joint; 3x3 gain blocks "
         "take\n"
         "# 1 (isotropic), 3 (diagonal) or 9 numbers (row-major, in the task frame). The plugin's\n"
         "# own options go under plugin_parameters (controllers/README.md lists them).\n";
  out << controller_name << ":\n  ros__parameters:\n";
  line(out, 4, "plugin: " + plugin, "plugin name (libcomply_<name>.so on the plugin path) or path");
  line(out, 4, "robot: " + robot, "name under robots/ or a robot folder");
  line(out, 4,
       "# joints, base_frame, tip_frame: default to robot.yaml (joints, base_frame, tcp_frame)",
       "");
  if (!tip_frame.empty()) {
    line(out, 4, "tip_frame: " + tip_frame, "");
  }
  printOptions(out);
  printInitial(out, cartesian);
  return out.str();
}

}  // namespace comply::pipeline
