// The option table as flat, typed parameters (the ROS 2 controllers' view of a controller file):
// every option declared with the default its struct member starts with, each read into its own
// member and no other, and the flat parameters read exactly as the same options in a file.

#include "comply/pipeline/config_parameters.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <vector>

#include "comply/core/input_error.hpp"

namespace comply::pipeline {
namespace {

const std::string kName = "arm";
const std::string kSource = "the parameters of controller 'arm'";

std::vector<FlatParameter> required() {
  return {{"plugin", std::string("cartesian_impedance")}, {"robot", std::string("fr3")}};
}

std::map<std::string, ParameterValue> valuesOf(const WrapperConfig& config) {
  std::map<std::string, ParameterValue> values;
  for (const OptionDeclaration& declaration : optionDeclarations()) {
    values[declaration.name] = optionValue(config, declaration.name);
  }
  return values;
}

/// A value of `declaration`'s type that differs from its default and lies in its range.
ParameterValue otherValue(const OptionDeclaration& declaration) {
  switch (declaration.type) {
    case ParameterType::kBool:
      return !std::get<bool>(declaration.default_value);
    case ParameterType::kString:
      for (const std::string& choice : declaration.choices) {
        if (choice != std::get<std::string>(declaration.default_value)) {
          return choice;
        }
      }
      break;
    case ParameterType::kDouble: {
      const double value = std::get<double>(declaration.default_value);
      return value != 0.0 ? 0.9 * value : std::min(0.5, declaration.max);
    }
    case ParameterType::kDoubleList: {
      if (const auto* list = std::get_if<std::vector<double>>(&declaration.default_value);
          list != nullptr && list->size() == 1 && list->front() != 0.0) {
        return std::vector<double>{0.9 * list->front()};
      }
      const std::size_t size =
          std::holds_alternative<std::monostate>(declaration.default_value) ? 1 : 3;
      return std::vector<double>(size, 0.5);
    }
  }
  return {};
}

TEST(OptionDeclarations, EveryOptionIsDeclaredOnceWithTheDefaultItsMemberStartsWith) {
  const std::vector<OptionDeclaration> declarations = optionDeclarations();
  ASSERT_GT(declarations.size(), 70u);
  std::set<std::string> names;
  const WrapperConfig defaults;
  for (const OptionDeclaration& declaration : declarations) {
    SCOPED_TRACE(declaration.name);
    EXPECT_TRUE(names.insert(declaration.name).second) << "declared twice";
    EXPECT_FALSE(declaration.description.empty());
    EXPECT_FALSE(declaration.constraint.empty());
    EXPECT_LT(declaration.min, declaration.max);
    if (!std::holds_alternative<std::monostate>(declaration.default_value)) {
      // The printed default (the row's text) and the member's initial value agree.
      EXPECT_EQ(declaration.default_value, optionValue(defaults, declaration.name));
    } else {
      EXPECT_EQ(declaration.type, ParameterType::kDoubleList);  // per joint: robot or URDF
    }
    if (declaration.type == ParameterType::kString) {
      EXPECT_GE(declaration.choices.size(), 2u);
    }
    if (declaration.type == ParameterType::kBool) {
      EXPECT_EQ(declaration.constraint, "must be true or false");
    } else if (declaration.type == ParameterType::kDouble) {
      EXPECT_TRUE(std::isfinite(declaration.min) && std::isfinite(declaration.max));
    }
  }
  const auto& timeout = *std::find_if(declarations.begin(), declarations.end(),
                                      [](const auto& d) { return d.name == "command_timeout_s"; });
  EXPECT_EQ(timeout.type, ParameterType::kDouble);
  EXPECT_EQ(std::get<double>(timeout.default_value), 0.5);
  EXPECT_EQ(timeout.min, 0.0);
  EXPECT_EQ(timeout.constraint, "must be >= 0");
  EXPECT_EQ(defaults.command_timeout_s, 0.5);
}

TEST(OptionDeclarations, EachOptionIsReadIntoItsOwnMemberAndNoOther) {
  const std::map<std::string, ParameterValue> defaults =
      valuesOf(parseWrapperParameters(required(), kSource, kName));
  for (const OptionDeclaration& declaration : optionDeclarations()) {
    SCOPED_TRACE(declaration.name);
    std::vector<FlatParameter> parameters = required();
    const ParameterValue value = otherValue(declaration);
    parameters.push_back({declaration.name, value});
    std::set<std::string> also_set;
    if (declaration.name == "passivity.enabled") {
      parameters.push_back({"gain_ramps.enabled", true});  // the tank needs the ramps
      also_set.insert("gain_ramps.enabled");
    }
    const WrapperConfig config = parseWrapperParameters(parameters, kSource, kName);
    const std::map<std::string, ParameterValue> values = valuesOf(config);
    EXPECT_EQ(values.at(declaration.name), value);
    for (const auto& [name, read] : values) {
      if (name != declaration.name && also_set.count(name) == 0) {
        EXPECT_EQ(read, defaults.at(name)) << name << " changed too";
      }
    }
  }
}

TEST(OptionDeclarations, FlatParametersReadAsTheSameOptionsInAFile) {
  const WrapperConfig from_file = parseWrapperText(
      "arm:\n"
      "  ros__parameters:\n"
      "    plugin: cartesian_impedance\n"
      "    robot: fr3\n"
      "    joints: [a, b]\n"
      "    command_timeout_s: 2\n"
      "    validation:\n"
      "      max_position_jump_m: 0.25\n"
      "    soft_limits:\n"
      "      stiffness: [10.0, 20.0]\n"
      "    torque_rate_limit_nm_per_s: 500\n"
      "    compensation:\n"
      "      friction:\n"
      "        model: viscous_coulomb\n"
      "    output:\n"
      "      admittance:\n"
      "        added_mass_kg: [1.0, 2.0, 3.0]\n"
      "    plugin_parameters:\n"
      "      gain: 3.5\n"
      "      mode: fast\n"
      "    initial:\n"
      "      stiffness_translational: 300\n",
      "file", kName);
  // As ROS 2 hands them over: integers stay integers, a single per-joint number is a scalar.
  std::vector<FlatParameter> parameters = required();
  parameters.push_back({"joints", std::vector<std::string>{"a", "b"}});
  parameters.push_back({"command_timeout_s", std::int64_t{2}});
  parameters.push_back({"validation.max_position_jump_m", 0.25});
  parameters.push_back({"soft_limits.stiffness", std::vector<double>{10.0, 20.0}});
  parameters.push_back({"torque_rate_limit_nm_per_s", std::int64_t{500}});
  parameters.push_back({"compensation.friction.model", std::string("viscous_coulomb")});
  parameters.push_back({"output.admittance.added_mass_kg", std::vector<double>{1.0, 2.0, 3.0}});
  parameters.push_back({"plugin_parameters.gain", 3.5});
  parameters.push_back({"plugin_parameters.mode", std::string("fast")});
  parameters.push_back({"initial.stiffness_translational", std::int64_t{300}});
  parameters.push_back({"base_frame", ParameterValue{}});  // declared, never set: skipped
  const WrapperConfig from_parameters = parseWrapperParameters(parameters, kSource, kName);

  EXPECT_EQ(valuesOf(from_parameters), valuesOf(from_file));
  EXPECT_EQ(from_parameters.command_timeout_s, 2.0);
  EXPECT_EQ(from_parameters.torque_rate_limit, std::vector<double>{500.0});
  EXPECT_EQ(from_parameters.joints, from_file.joints);
  EXPECT_EQ(from_parameters.plugin_parameters.at("gain").numbers, std::vector<double>{3.5});
  EXPECT_EQ(from_parameters.plugin_parameters.at("mode").text, "fast");
  EXPECT_EQ(*from_parameters.initial_block, *from_file.initial_block);
  EXPECT_EQ(from_parameters.name, kName);
}

// Walls and boxes, lists of maps no ROS 2 parameter holds, come as the YAML text of the list and
// read as the file's list: the same planes and boxes, and their errors named as in a file.
TEST(ConfigParameters, WallsAndBoxesComeAsTheYamlTextOfTheirList) {
  std::vector<FlatParameter> parameters = required();
  parameters.push_back(
      {"walls", std::string("[{point: [0.65, 0.0, 0.0], normal: [1.0, 0.0, 0.0]}, "
                            "{point: [0, 0, 0.05], normal: [0, 0, -1]}]")});
  parameters.push_back({"boxes", std::string("[{min: [0.2, -0.4, 0.05], max: [0.7, 0.4, 0.8]}]")});
  const WrapperConfig config = parseWrapperParameters(parameters, kSource, kName);
  ASSERT_EQ(config.walls.planes.size(), 2U);
  EXPECT_EQ(config.walls.planes[0].point, Eigen::Vector3d(0.65, 0.0, 0.0));
  EXPECT_EQ(config.walls.planes[1].normal, Eigen::Vector3d(0.0, 0.0, -1.0));
  ASSERT_EQ(config.walls.boxes.size(), 1U);
  EXPECT_EQ(config.walls.boxes[0].max, Eigen::Vector3d(0.7, 0.4, 0.8));

  parameters.back() = {"boxes", std::string("[{min: [0.2, -0.4, 0.05]")};
  EXPECT_THROW(parseWrapperParameters(parameters, kSource, kName), InputError);
  parameters.back() = {"boxes", std::string("[{min: [0.7, -0.4, 0.05], max: [0.2, 0.4, 0.8]}]")};
  try {
    parseWrapperParameters(parameters, kSource, kName);
    FAIL() << "a box with min above max was read";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("boxes[0].min: must be below max"), std::string::npos)
        << error.what();
  }
}

InputError refusal(const std::vector<FlatParameter>& extra) {
  std::vector<FlatParameter> parameters = required();
  parameters.insert(parameters.end(), extra.begin(), extra.end());
  try {
    parseWrapperParameters(parameters, kSource, kName);
  } catch (const InputError& error) {
    return error;
  }
  ADD_FAILURE() << "accepted";
  return InputError(InputErrc::kSyntax, "", "", "");
}

TEST(OptionDeclarations, BadParametersAreRefusedNamingTheParameter) {
  InputError error = refusal({{"validation.max_position_jumpp", 0.1}});
  EXPECT_EQ(error.code(), InputErrc::kUnknownKey);
  EXPECT_NE(std::string(error.what()).find(kSource), std::string::npos) << error.what();
  EXPECT_NE(std::string(error.what()).find("arm.ros__parameters.validation.max_position_jumpp"),
            std::string::npos)
      << error.what();

  error = refusal({{"command_timeout_s", -1.0}});
  EXPECT_EQ(error.code(), InputErrc::kOutOfRange);
  EXPECT_NE(std::string(error.what()).find("command_timeout_s: must be >= 0"), std::string::npos)
      << error.what();

  error = refusal({{"command_timeout_s", std::string("soon")}});
  EXPECT_EQ(error.code(), InputErrc::kWrongType);

  error = refusal({{"timeout_behavior", std::string("drift")}});
  EXPECT_EQ(error.code(), InputErrc::kInvalidValue);
  EXPECT_NE(std::string(error.what()).find("must be hold or reanchor"), std::string::npos)
      << error.what();

  error = refusal({{"output.admittance.added_mass_kg", std::vector<double>{1.0, 2.0}}});
  EXPECT_EQ(error.code(), InputErrc::kWrongSize);

  // A value and a section under the same name cannot both be, in either order.
  error = refusal({{"validation", 1.0}, {"validation.max_position_jump_m", 0.1}});
  EXPECT_EQ(error.code(), InputErrc::kInconsistent);
  error = refusal({{"validation.max_position_jump_m", 0.1}, {"validation", 1.0}});
  EXPECT_EQ(error.code(), InputErrc::kInconsistent);

  error = refusal({{"", 1.0}});
  EXPECT_EQ(error.code(), InputErrc::kInvalidValue);
  error = refusal({{"validation..max_position_jump_m", 0.1}});
  EXPECT_EQ(error.code(), InputErrc::kInvalidValue);

  // No number at all for a per-joint option would leave the joints without a limit.
  error = refusal({{"torque_rate_limit_nm_per_s", std::vector<double>{}}});
  EXPECT_EQ(error.code(), InputErrc::kWrongSize);
  EXPECT_NE(std::string(error.what()).find("torque_rate_limit_nm_per_s"), std::string::npos);
}

}  // namespace
}  // namespace comply::pipeline
