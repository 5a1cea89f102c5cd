// Reading a controller file: the YAML text, then every option of the table (option_table.hpp)
// at its key or its default, then the names, plugin parameters and the initial block.

#include "comply/pipeline/config.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>

#include "comply/core/input_error.hpp"
#include "comply/core/text_file.hpp"
#include "comply/schema/json.hpp"
#include "config_options.hpp"

namespace comply::pipeline {
namespace {

/// Errors of one controller file: every one names the file and the full key.
class Reporter {
 public:
  Reporter(std::string source, std::string root)
      : source_(std::move(source)), root_(std::move(root)) {}
  [[noreturn]] void fail(InputErrc code, const std::string& key, const std::string& message) const {
    throw InputError(code, source_, key.empty() ? root_ : root_ + "." + key, message);
  }
  [[nodiscard]] const std::string& source() const { return source_; }
  [[nodiscard]] const std::string& root() const { return root_; }

 private:
  std::string source_;
  std::string root_;
};

/// The node at a dotted key; undefined when absent.
YAML::Node lookup(const YAML::Node& parameters, const std::string& key) {
  YAML::Node node;
  node.reset(parameters);  // reset(), not '=': assigning a YAML::Node overwrites its target
  for (const std::string& part : options::keyPath(key)) {
    if (!node.IsMap()) {
      return YAML::Node(YAML::NodeType::Undefined);
    }
    const YAML::Node next = static_cast<const YAML::Node&>(node)[part];  // const: never inserts
    if (!next.IsDefined()) {
      return YAML::Node(YAML::NodeType::Undefined);
    }
    node.reset(next);
  }
  return node;
}

std::vector<double> numberList(const YAML::Node& node) {
  return node.IsSequence() ? node.as<std::vector<double>>()
                           : std::vector<double>{node.as<double>()};
}

bool inRange(const options::Option& option, double value) {
  // Infinity too is out: an unbounded option still takes a number (0 is how options say "off").
  const bool above = option.min_exclusive ? value > option.min : value >= option.min;
  return std::isfinite(value) && above && value <= option.max;
}

options::Value readValue(const options::Option& option, const YAML::Node& node,
                         const Reporter& report) {
  using options::Kind;
  options::Value value;
  try {
    switch (option.kind) {
      case Kind::kNumber:
        value.number = node.as<double>();
        break;
      case Kind::kFlag:
        value.flag = node.as<bool>();
        break;
      case Kind::kChoice:
        value.text = node.as<std::string>();
        break;
      case Kind::kVector3:
      case Kind::kPerJoint:
        value.numbers = numberList(node);
        break;
    }
  } catch (const YAML::Exception&) {
    report.fail(InputErrc::kWrongType, option.key,
                option.kind == Kind::kPerJoint ? "must be a number or a list of numbers"
                                               : "has the wrong type");
  }
  if (option.kind == Kind::kChoice &&
      std::find(option.choices.begin(), option.choices.end(), value.text) == option.choices.end()) {
    report.fail(InputErrc::kInvalidValue, option.key, options::constraintText(option));
  }
  if (option.kind == Kind::kPerJoint && value.numbers.empty()) {
    report.fail(InputErrc::kWrongSize, option.key, "must be one number or one per joint, not none");
  }
  if (option.kind == Kind::kVector3 && value.numbers.size() != 3) {
    report.fail(InputErrc::kWrongSize, option.key, "must be [x, y, z]");
  }
  if (option.kind == Kind::kNumber && !inRange(option, value.number)) {
    report.fail(InputErrc::kOutOfRange, option.key, options::constraintText(option));
  }
  for (const double entry : value.numbers) {
    if (!inRange(option, entry)) {
      report.fail(InputErrc::kOutOfRange, option.key, options::constraintText(option));
    }
  }
  return value;
}

void readOptions(const YAML::Node& parameters, const Reporter& report, WrapperConfig& config) {
  for (const options::Option& option : options::table()) {
    // An absent key keeps the member's default, which is the row's (option_table.hpp).
    if (const YAML::Node node = lookup(parameters, option.key)) {
      option.apply(config, readValue(option, node, report));
    }
  }
}

/// Every key of `node` must be an option, a section holding options, or a special key.
void rejectUnknownKeys(const YAML::Node& node, const std::string& prefix, const Reporter& report) {
  static const std::set<std::string> kLeaves = [] {
    std::set<std::string> leaves(std::begin(options::kSpecialKeys),
                                 std::end(options::kSpecialKeys));
    for (const options::Option& option : options::table()) {
      leaves.insert(option.key);
    }
    return leaves;
  }();
  static const std::set<std::string> kSections = [] {
    std::set<std::string> sections;
    for (const options::Option& option : options::table()) {
      std::string key = option.key;
      for (std::size_t dot = key.rfind('.'); dot != std::string::npos; dot = key.rfind('.')) {
        key.resize(dot);
        sections.insert(key);
      }
    }
    return sections;
  }();
  if (!node.IsMap()) {
    report.fail(InputErrc::kWrongType, prefix.substr(0, prefix.size() - 1), "must be a mapping");
  }
  for (const auto& entry : node) {
    const std::string key = prefix + entry.first.as<std::string>();
    if (kSections.count(key) != 0) {
      rejectUnknownKeys(entry.second, key + ".", report);
    } else if (kLeaves.count(key) == 0) {
      report.fail(InputErrc::kUnknownKey, key, "is not a known option");
    }
  }
}

plugin::ParameterMap readPluginParameters(const YAML::Node& parameters, const Reporter& report) {
  plugin::ParameterMap result;
  const YAML::Node node = parameters["plugin_parameters"];
  if (!node) {
    return result;
  }
  if (!node.IsMap()) {
    report.fail(InputErrc::kWrongType, "plugin_parameters", "must be a mapping");
  }
  for (const auto& entry : node) {
    const auto name = entry.first.as<std::string>();
    plugin::ParameterValue value;
    try {
      if (entry.second.IsSequence()) {
        value.numbers = entry.second.as<std::vector<double>>();
      } else if (!YAML::convert<double>::decode(entry.second, value.numbers.emplace_back())) {
        value.numbers.clear();
        value.text = entry.second.as<std::string>();
        value.is_text = true;
      }
    } catch (const YAML::Exception&) {
      report.fail(InputErrc::kWrongType, "plugin_parameters." + name,
                  "must be a number, a list of numbers or a string");
    }
    result[name] = value;
  }
  return result;
}

void readNames(const YAML::Node& parameters, const Reporter& report, WrapperConfig& config) {
  const auto text = [&](const char* key, bool required) {
    const YAML::Node node = parameters[key];
    if (!node || !node.IsScalar()) {
      if (required) {
        report.fail(InputErrc::kMissingKey, key, "is required");
      }
      return std::string();
    }
    return node.as<std::string>();
  };
  config.plugin = text("plugin", true);
  config.robot = text("robot", true);
  config.base_frame = text("base_frame", false);
  config.tip_frame = text("tip_frame", false);
  if (const YAML::Node joints = parameters["joints"]) {
    try {
      config.joints = joints.as<std::vector<std::string>>();
    } catch (const YAML::Exception&) {
      report.fail(InputErrc::kWrongType, "joints", "must be a list of joint names");
    }
    const auto count = static_cast<int>(config.joints.size());
    if (count < 1 || count > kMaxDof) {
      // Every per-joint vector downstream has inline storage for kMaxDof entries.
      report.fail(
          InputErrc::kWrongSize, "joints",
          "has " + std::to_string(count) + " entries, expected 1 to " + std::to_string(kMaxDof));
    }
  }
}

YAML::Node controllerParameters(const std::string& yaml_text, const std::string& source,
                                const std::string& controller_name, std::string& name) {
  YAML::Node root;
  try {
    root = YAML::Load(yaml_text);
  } catch (const YAML::Exception& error) {
    throw InputError(InputErrc::kSyntax, source, "",
                     std::string("not valid YAML: ") + error.what());
  }
  if (!root || !root.IsMap() || root.size() == 0) {
    throw InputError(InputErrc::kMissingKey, source, "",
                     "expected '<controller_name>: ros__parameters: ...'");
  }
  if (controller_name.empty() && root.size() != 1) {
    throw InputError(InputErrc::kInconsistent, source, "",
                     "holds several controllers; name the one to use");
  }
  name = controller_name.empty() ? root.begin()->first.as<std::string>() : controller_name;
  if (!root[name]) {
    throw InputError(InputErrc::kMissingKey, source, "", "no controller named '" + name + "'");
  }
  const YAML::Node parameters = root[name]["ros__parameters"];
  if (!parameters || !parameters.IsMap()) {
    throw InputError(InputErrc::kMissingKey, source, name, "has no 'ros__parameters' section");
  }
  return parameters;
}

/// The tank's energies must be ordered floor <= initial <= ceiling, or it would start empty or
/// overfull: refused here, naming the option, rather than clamped without a word. And the tank
/// needs the ramps: a stiffness or frame step is clipped by the torque-rate limit, and the lag of a
/// clipped torque does work the tank cannot account for (docs/safety.md, "Streamed gains").
void checkTankBounds(const WrapperConfig& config, const Reporter& report) {
  const PassivityConfig& tank = config.passivity;
  if (tank.enabled && !config.gain_ramps.enabled) {
    report.fail(InputErrc::kInconsistent, "passivity.enabled",
                "needs gain_ramps.enabled: true (an unramped stiffness or task-frame step is "
                "clipped by the torque-rate limit, and the tank cannot account for the lag)");
  }
  if (!(tank.tank_min_j < tank.tank_max_j)) {
    report.fail(InputErrc::kInconsistent, "passivity.tank_min_j",
                "must be below passivity.tank_max_j");
  }
  if (tank.tank_initial_j < tank.tank_min_j || tank.tank_initial_j > tank.tank_max_j) {
    report.fail(InputErrc::kInconsistent, "passivity.tank_initial_j",
                "must lie between passivity.tank_min_j and passivity.tank_max_j");
  }
  if (tank.nullspace_tank_initial_j > tank.nullspace_tank_max_j) {
    report.fail(InputErrc::kInconsistent, "passivity.nullspace_tank_initial_j",
                "must not exceed passivity.nullspace_tank_max_j");
  }
}

/// The file's thresholds within its own ceilings: a command may raise them up to the ceilings,
/// never the file start above them.
void checkReflexBounds(const ReflexConfig& reflex, const Reporter& report) {
  if (reflex.force_n > reflex.max_force_n) {
    report.fail(InputErrc::kInconsistent, "reflex.force_n",
                "must not exceed reflex.max_force_n (the most a command may raise it to)");
  }
  if (reflex.torque_nm > reflex.max_torque_nm) {
    report.fail(InputErrc::kInconsistent, "reflex.torque_nm",
                "must not exceed reflex.max_torque_nm (the most a command may raise it to)");
  }
}

/// A transient contact where ISO/TS 15066 allows none (body_regions.hpp) has no limit to bound
/// by, unless the file gives its own.
void checkContactSpeed(const ContactSpeedConfig& contact, const Reporter& report) {
  if (contact.force_limit_n > 0.0 ||
      forceLimit(bodyRegionLimits(contact.body_region), contact.contact) > 0.0) {
    return;
  }
  report.fail(InputErrc::kInconsistent, "contact_speed.contact",
              "transient, but ISO/TS 15066 permits no transient contact with " +
                  std::string(nameIn(kBodyRegionNames, contact.body_region)) +
                  "; use quasi_static, or set contact_speed.force_limit_n");
}

}  // namespace

namespace options {

WrapperConfig parseParameters(const YAML::Node& parameters, const std::string& source,
                              const std::string& controller_name) {
  WrapperConfig config;
  config.source = source;
  config.name = controller_name;
  const Reporter report(source, config.name + ".ros__parameters");
  readNames(parameters, report, config);
  rejectUnknownKeys(parameters, "", report);
  readOptions(parameters, report, config);
  checkTankBounds(config, report);
  checkReflexBounds(config.reflex, report);
  checkContactSpeed(config.contact_speed, report);
  readWalls(parameters, source, report.root(), config.walls);
  config.plugin_parameters = readPluginParameters(parameters, report);
  const YAML::Node initial = parameters["initial"];
  if (initial && !initial.IsMap()) {
    report.fail(InputErrc::kWrongType, "initial", "must be a mapping");
  }
  config.initial_block = std::make_shared<const nlohmann::json>(
      initial ? schema::yamlToJson(initial, source, report.root() + ".initial")
              : nlohmann::json::object());
  return config;
}

}  // namespace options

WrapperConfig parseWrapperText(const std::string& yaml_text, const std::string& source,
                               const std::string& controller_name) {
  std::string name;
  const YAML::Node parameters = controllerParameters(yaml_text, source, controller_name, name);
  return options::parseParameters(parameters, source, name);
}

const WrapperConfig& defaultConfig() {
  static const WrapperConfig kDefaults;
  return kDefaults;
}

WrapperConfig parseWrapperConfig(const std::string& yaml_text, const std::string& source,
                                 const std::string& controller_name) {
  WrapperConfig config = parseWrapperText(yaml_text, source, controller_name);
  completeForRobot(config, std::make_shared<const model::RobotDescription>(
                               model::loadRobotDescription(config.robot)));
  return config;
}

WrapperConfig loadWrapperConfig(const std::filesystem::path& file,
                                const std::string& controller_name) {
  const TextFile text = readTextFile(file);
  if (!text.ok()) {
    throw InputError(InputErrc::kCannotRead, file.string(), "",
                     "cannot read the controller configuration: " + text.error);
  }
  return parseWrapperConfig(text.text, file.string(), controller_name);
}

}  // namespace comply::pipeline
