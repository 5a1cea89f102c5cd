#pragma once
// The controller file as flat, typed parameters: the shape ROS 2 gives it. ROS flattens the
// nested YAML of a controller file (`validation: {max_position_jump_m: 0.1}`) into dotted names
// (`validation.max_position_jump_m`); these functions declare comply's options in that shape
// (type, default, range, description, from the option table) and read such parameters back
// through the same parser, checks and messages as a controller file. Free of any middleware:
// the ROS 2 controllers convert to and from rclcpp's types, the rest is here and tested here.

#include <cstdint>
#include <string>
#include <variant>
#include <vector>

#include "comply/pipeline/config.hpp"

namespace comply::pipeline {

/// A parameter's value; std::monostate: not set.
using ParameterValue =
    std::variant<std::monostate, bool, std::int64_t, double, std::string, std::vector<bool>,
                 std::vector<std::int64_t>, std::vector<double>, std::vector<std::string>>;

struct FlatParameter {
  std::string name;  ///< dotted, under ros__parameters ("soft_limits.stiffness")
  ParameterValue value;
};

enum class ParameterType { kBool, kDouble, kString, kDoubleList };

/// One option as a typed parameter.
struct OptionDeclaration {
  std::string name;  ///< dotted ("validation.max_position_jump_m")
  ParameterType type = ParameterType::kDouble;
  /// Of `type`; a per-joint option's default is one number for every joint. std::monostate: no
  /// default (the description says what then).
  ParameterValue default_value;
  std::string description;  ///< the documented file's comment
  std::string constraint;   ///< "must be > 0", "must be hold or reanchor"
  /// kDouble and kDoubleList: every number lies in [min, max] (the bound is excluded where
  /// `constraint` says so); lowest() / max() where unbounded.
  double min = 0.0;
  double max = 0.0;
  std::vector<std::string> choices;  ///< kString: the allowed values
};

/// Every option of the controller file, in the documented file's order. Names, plugin parameters
/// and the initial block are not options (their keys are the user's): they are read as given.
std::vector<OptionDeclaration> optionDeclarations();

/// The value `config` holds for option `name`, typed as optionDeclarations() declares it.
/// Throws std::out_of_range for a name that is not an option.
ParameterValue optionValue(const WrapperConfig& config, const std::string& name);

/// Reads controller `controller_name` from its flat parameters, exactly as parseWrapperText()
/// reads the same options nested in a file: unknown names, wrong types and values out of range
/// are refused with an InputError naming `source` and the parameter. Parameters without a value
/// are skipped.
WrapperConfig parseWrapperParameters(const std::vector<FlatParameter>& parameters,
                                     const std::string& source, const std::string& controller_name);

}  // namespace comply::pipeline
