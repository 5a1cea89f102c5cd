// The controller file's reflex.* options: off by default with the documented values, read as
// written, and each bad value refused with its key in the error: a threshold above its own
// ceiling, a reaction that is not one, a value out of range, the thresholds in the initial block.

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "comply/pipeline/config.hpp"
#include "config_errors.hpp"

namespace comply::pipeline {
namespace {

const std::string kPrefix = "arm_controller.ros__parameters.";

std::string controllerYaml(const std::string& lines) {
  return "arm_controller:\n  ros__parameters:\n    plugin: cartesian_impedance\n    robot: fr3\n" +
         lines;
}

WrapperConfig parse(const std::string& lines) {
  return parseWrapperText(controllerYaml(lines), "arm.yaml");
}

void expectError(const std::string& lines, const std::vector<std::string>& fragments) {
  // The initial block too.
  test::expectReadError(
      [](const std::string& text) { return parseWrapperConfig(controllerYaml(text), "arm.yaml"); },
      lines, fragments);
}

TEST(ReflexConfig, OffByDefaultWithTheDocumentedValues) {
  const ReflexConfig reflex = parse("").reflex;
  EXPECT_FALSE(reflex.enabled);
  EXPECT_EQ(reflex.reaction, ReflexReaction::kHold);
  EXPECT_DOUBLE_EQ(reflex.force_n, 20.0);
  EXPECT_DOUBLE_EQ(reflex.torque_nm, 5.0);
  EXPECT_DOUBLE_EQ(reflex.max_force_n, 60.0);
  EXPECT_DOUBLE_EQ(reflex.max_torque_nm, 15.0);
  EXPECT_DOUBLE_EQ(reflex.debounce_s, 0.005);
  EXPECT_DOUBLE_EQ(reflex.retreat_m, 0.05);
  EXPECT_DOUBLE_EQ(reflex.retreat_speed_m_per_s, 0.1);
  EXPECT_DOUBLE_EQ(reflex.hold_stiffness_fraction, 1.0);
}

TEST(ReflexConfig, OptionsAreReadAsWritten) {
  const ReflexConfig reflex = parse(
                                  "    reflex:\n      enabled: true\n      reaction: retreat\n"
                                  "      force_n: 12.5\n      torque_nm: 2.0\n"
                                  "      max_force_n: 40.0\n      max_torque_nm: 4.0\n"
                                  "      debounce_s: 0.01\n      retreat_m: 0.02\n"
                                  "      retreat_speed_m_per_s: 0.05\n"
                                  "      hold_stiffness_fraction: 0.25\n")
                                  .reflex;
  EXPECT_TRUE(reflex.enabled);
  EXPECT_EQ(reflex.reaction, ReflexReaction::kRetreat);
  EXPECT_DOUBLE_EQ(reflex.force_n, 12.5);
  EXPECT_DOUBLE_EQ(reflex.torque_nm, 2.0);
  EXPECT_DOUBLE_EQ(reflex.max_force_n, 40.0);
  EXPECT_DOUBLE_EQ(reflex.max_torque_nm, 4.0);
  EXPECT_DOUBLE_EQ(reflex.debounce_s, 0.01);
  EXPECT_DOUBLE_EQ(reflex.retreat_m, 0.02);
  EXPECT_DOUBLE_EQ(reflex.retreat_speed_m_per_s, 0.05);
  EXPECT_DOUBLE_EQ(reflex.hold_stiffness_fraction, 0.25);
  EXPECT_EQ(parse("    reflex:\n      reaction: fault\n").reflex.reaction, ReflexReaction::kFault);
}

TEST(ReflexConfig, EachBadValueIsNamed) {
  expectError("    reflex:\n      force_n: 80.0\n",
              {kPrefix + "reflex.force_n", "must not exceed reflex.max_force_n"});
  expectError("    reflex:\n      torque_nm: 6.0\n      max_torque_nm: 5.0\n",
              {kPrefix + "reflex.torque_nm", "must not exceed reflex.max_torque_nm"});
  expectError("    reflex:\n      reaction: stop\n",
              {kPrefix + "reflex.reaction", "hold", "retreat", "fault"});
  expectError("    reflex:\n      force_n: 0.0\n", {kPrefix + "reflex.force_n"});
  expectError("    reflex:\n      debounce_s: -0.001\n", {kPrefix + "reflex.debounce_s"});
  expectError("    reflex:\n      retreat_m: 0.5\n", {kPrefix + "reflex.retreat_m"});
  expectError("    reflex:\n      retreat_speed_m_per_s: 0.0\n",
              {kPrefix + "reflex.retreat_speed_m_per_s"});
  expectError("    reflex:\n      hold_stiffness_fraction: 1.5\n",
              {kPrefix + "reflex.hold_stiffness_fraction"});
  expectError("    reflex:\n      enabled: maybe\n", {kPrefix + "reflex.enabled"});
  // One place for the file's thresholds: not the initial command.
  expectError("    initial:\n      reflex_force: [30.0, 30.0, 30.0]\n",
              {kPrefix + "initial.reflex_force", "reflex.force_n"});
}

}  // namespace
}  // namespace comply::pipeline
