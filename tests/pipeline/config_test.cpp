// Wrapper configuration from ros2_control-shaped YAML. Defaults must be the documented safe ones,
// and every error must name the file and the full key, since that is all a user sees when a
// controller refuses to start.

#include "comply/pipeline/config.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "comply/core/input_error.hpp"
#include "comply/pipeline/config_parameters.hpp"

namespace comply::pipeline {
namespace {

const std::string kSource = "arm.yaml";
const std::string kPrefix = "arm.yaml: arm_controller.ros__parameters.";

/// A controller file for fr3 with `lines` (indented as direct parameters) appended.
std::string controllerYaml(const std::string& lines = {}) {
  std::string yaml =
      "arm_controller:\n"
      "  ros__parameters:\n"
      "    plugin: cartesian_impedance\n"
      "    robot: fr3\n";
  std::istringstream stream(lines);
  for (std::string line; std::getline(stream, line);) {
    yaml += "    " + line + "\n";
  }
  return yaml;
}

WrapperConfig parse(const std::string& lines) {
  return parseWrapperConfig(controllerYaml(lines), kSource);
}

/// Expects parsing `yaml` to throw std::runtime_error whose message holds every fragment.
void expectError(const std::string& yaml, const std::vector<std::string>& fragments,
                 const std::string& controller_name = {}) {
  try {
    parseWrapperConfig(yaml, kSource, controller_name);
    ADD_FAILURE() << "expected an error for:\n" << yaml;
  } catch (const std::runtime_error& error) {
    const std::string message = error.what();
    for (const auto& fragment : fragments) {
      EXPECT_NE(message.find(fragment), std::string::npos)
          << "'" << fragment << "' not in: " << message;
    }
  }
}

std::vector<double> repeated(double value, int count = 7) {
  return std::vector<double>(static_cast<std::size_t>(count), value);
}

TEST(WrapperConfig, DefaultsAreTheDocumentedOnes) {
  const WrapperConfig config = parseWrapperConfig(controllerYaml(), kSource);
  EXPECT_EQ(config.name, "arm_controller");
  EXPECT_EQ(config.plugin, "cartesian_impedance");
  EXPECT_TRUE(config.plugin_parameters.empty());
  EXPECT_EQ(config.robot, "fr3");
  EXPECT_EQ(config.joints,
            (std::vector<std::string>{"fr3_joint1", "fr3_joint2", "fr3_joint3", "fr3_joint4",
                                      "fr3_joint5", "fr3_joint6", "fr3_joint7"}));
  EXPECT_EQ(config.dof, 7);
  EXPECT_EQ(config.base_frame, "fr3_link0");
  EXPECT_EQ(config.tip_frame, "fr3_tcp");

  EXPECT_EQ(config.command_timeout_s, 0.5);
  EXPECT_EQ(config.timeout_behavior, TimeoutBehavior::kHold);
  EXPECT_EQ(config.validation.quaternion_tolerance, 1e-3);
  EXPECT_EQ(config.validation.max_position_jump_m, 0.10);
  EXPECT_EQ(config.validation.max_orientation_jump_rad, 0.60);
  EXPECT_EQ(config.validation.max_joint_jump_rad, 0.50);
  EXPECT_EQ(config.validation.gain_tolerance, 1e-9);

  EXPECT_TRUE(config.gravity_compensation);
  EXPECT_FALSE(config.payload_compensation);
  EXPECT_EQ(config.payload.mass_kg, 0.0);
  EXPECT_EQ(config.payload.com_in_tip, Eigen::Vector3d::Zero());
  EXPECT_EQ(config.friction.model, FrictionModel::kNone);

  EXPECT_TRUE(config.soft_limits.enabled);
  EXPECT_EQ(config.soft_limits.margin, repeated(0.1));
  EXPECT_EQ(config.soft_limits.stiffness, repeated(100.0));
  EXPECT_EQ(config.soft_limits.damping, repeated(5.0));

  EXPECT_EQ(config.filter_alpha, 1.0);
  EXPECT_EQ(config.torque_rate_limit, repeated(1000.0));
  EXPECT_TRUE(config.effort_limit.empty());  // empty: the URDF effort limits apply
  EXPECT_EQ(config.fault_damping, repeated(5.0));
}

TEST(WrapperConfig, DefaultInitialCommands) {
  const WrapperConfig config = parseWrapperConfig(controllerYaml(), kSource);
  const JointCommand& joint = config.initial_joint;
  EXPECT_EQ(joint.position, JointVector::Zero(7));
  EXPECT_EQ(joint.stiffness, JointVector::Constant(7, 100.0));
  EXPECT_EQ(joint.damping, JointVector::Constant(7, 10.0));

  const CartesianCommand& cartesian = config.initial_cartesian;
  EXPECT_EQ(cartesian.stiffness_translational, 500.0 * Eigen::Matrix3d::Identity());
  EXPECT_EQ(cartesian.stiffness_rotational, 30.0 * Eigen::Matrix3d::Identity());
  EXPECT_EQ(cartesian.damping_translational, 45.0 * Eigen::Matrix3d::Identity());
  EXPECT_EQ(cartesian.damping_rotational, 3.0 * Eigen::Matrix3d::Identity());
  EXPECT_EQ(cartesian.damping_mode, DampingMode::kRatio);
  EXPECT_EQ(cartesian.damping_ratio, Vector6d::Ones());
  EXPECT_EQ(cartesian.task_frame.coeffs(), Eigen::Quaterniond::Identity().coeffs());
  EXPECT_EQ(cartesian.nullspace_position, JointVector::Zero(7));
  EXPECT_EQ(cartesian.nullspace_stiffness, JointVector::Constant(7, 2.0));
  EXPECT_EQ(cartesian.nullspace_damping, JointVector::Constant(7, 0.5));
  EXPECT_EQ(cartesian.torque_feedforward.size(), 7);
}

TEST(WrapperConfig, ReadsScalarOptions) {
  const WrapperConfig config = parse(
      "command_timeout_s: 0.2\n"
      "timeout_behavior: reanchor\n"
      "filter_alpha: 0.3\n"
      "base_frame: fr3_link1\n"
      "tip_frame: fr3_link8\n"
      "validation:\n"
      "  quaternion_tolerance: 0.01\n"
      "  max_position_jump_m: 0.05\n"
      "  max_orientation_jump_rad: 0.25\n"
      "  max_joint_jump_rad: 0.125\n");
  EXPECT_EQ(config.command_timeout_s, 0.2);
  EXPECT_EQ(config.timeout_behavior, TimeoutBehavior::kReanchor);
  EXPECT_EQ(config.filter_alpha, 0.3);
  EXPECT_EQ(config.base_frame, "fr3_link1");
  EXPECT_EQ(config.tip_frame, "fr3_link8");
  EXPECT_EQ(config.validation.quaternion_tolerance, 0.01);
  EXPECT_EQ(config.validation.max_position_jump_m, 0.05);
  EXPECT_EQ(config.validation.max_orientation_jump_rad, 0.25);
  EXPECT_EQ(config.validation.max_joint_jump_rad, 0.125);
}

TEST(WrapperConfig, ReadsPluginParametersAsNumbersListsOrText) {
  const WrapperConfig config = parse(
      "plugin_parameters:\n"
      "  gain: 2.5\n"
      "  weights: [1, 2, 3]\n"
      "  mode: fast\n");
  ASSERT_EQ(config.plugin_parameters.size(), 3U);
  const auto& gain = config.plugin_parameters.at("gain");
  EXPECT_FALSE(gain.is_text);
  EXPECT_EQ(gain.numbers, std::vector<double>{2.5});
  EXPECT_EQ(config.plugin_parameters.at("weights").numbers, (std::vector<double>{1, 2, 3}));
  const auto& mode = config.plugin_parameters.at("mode");
  EXPECT_TRUE(mode.is_text);
  EXPECT_EQ(mode.text, "fast");
  EXPECT_TRUE(mode.numbers.empty());
}

TEST(WrapperConfig, PerJointListsTakeOneValueOrOnePerJoint) {
  const WrapperConfig config = parse(
      "torque_rate_limit_nm_per_s: 250\n"
      "effort_limit_nm: [87, 87, 87, 87, 12, 12, 12]\n"
      "fault_damping: [1, 2, 3, 4, 5, 6, 7]\n"
      "soft_limits:\n"
      "  enabled: false\n"
      "  margin_rad: 0.05\n"
      "  stiffness: [10, 20, 30, 40, 50, 60, 70]\n"
      "  damping: 1.5\n");
  EXPECT_EQ(config.torque_rate_limit, repeated(250.0));
  EXPECT_EQ(config.effort_limit, (std::vector<double>{87, 87, 87, 87, 12, 12, 12}));
  EXPECT_EQ(config.fault_damping, (std::vector<double>{1, 2, 3, 4, 5, 6, 7}));
  EXPECT_FALSE(config.soft_limits.enabled);
  EXPECT_EQ(config.soft_limits.margin, repeated(0.05));
  EXPECT_EQ(config.soft_limits.stiffness, (std::vector<double>{10, 20, 30, 40, 50, 60, 70}));
  EXPECT_EQ(config.soft_limits.damping, repeated(1.5));
}

TEST(WrapperConfig, PerJointListsFollowAShorterJointList) {
  const WrapperConfig config = parse(
      "joints: [fr3_joint1, fr3_joint2]\n"
      "fault_damping: [3, 4]\n");
  EXPECT_EQ(config.dof, 2);
  EXPECT_EQ(config.fault_damping, (std::vector<double>{3, 4}));
  EXPECT_EQ(config.torque_rate_limit, repeated(1000.0, 2));
  EXPECT_EQ(config.initial_joint.stiffness.size(), 2);
}

TEST(WrapperConfig, PerJointListOfTheWrongLengthNamesTheKey) {
  expectError(controllerYaml("torque_rate_limit_nm_per_s: [1, 2, 3]"),
              {kPrefix + "torque_rate_limit_nm_per_s: has 3 values, expected 1 or 7"});
  expectError(controllerYaml("soft_limits:\n  stiffness: [1, 2]"),
              {kPrefix + "soft_limits.stiffness: has 2 values, expected 1 or 7"});
  expectError(controllerYaml("initial:\n  damping_ratio: [1, 1, 1, 1, 1, 1, 1]"),
              {kPrefix + "initial.damping_ratio: 'damping_ratio' has 7 numbers, expected 1 or 6"});
}

TEST(WrapperConfig, PerJointListOfTheWrongTypeNamesTheKey) {
  expectError(controllerYaml("fault_damping: soft"),
              {kPrefix + "fault_damping: must be a number or a list of numbers"});
}

TEST(WrapperConfig, NegativePerJointLimitNamesTheKey) {
  expectError(controllerYaml("soft_limits:\n  stiffness: -1"),
              {kPrefix + "soft_limits.stiffness: must be >= 0"});
  expectError(controllerYaml("torque_rate_limit_nm_per_s: [1, 1, 1, -1, 1, 1, 1]"),
              {kPrefix + "torque_rate_limit_nm_per_s: must be > 0"});
}

// A torque-rate limit of 0 holds every joint's torque where it starts: the controller cannot act.
// Refused at configure time, like an effort limit of 0.
TEST(WrapperConfig, LimitsThatLeaveTheControllerNoTorqueAreRefused) {
  expectError(controllerYaml("torque_rate_limit_nm_per_s: 0"),
              {kPrefix + "torque_rate_limit_nm_per_s: must be > 0"});
  expectError(controllerYaml("torque_rate_limit_nm_per_s: [1, 1, 1, 0, 1, 1, 1]"),
              {kPrefix + "torque_rate_limit_nm_per_s: must be > 0"});
  expectError(controllerYaml("effort_limit_nm: 0"), {kPrefix + "effort_limit_nm: must be > 0"});
  expectError(controllerYaml("filter_alpha: 0"), {kPrefix + "filter_alpha: must be in (0, 1]"});
  EXPECT_EQ(parse("torque_rate_limit_nm_per_s: 0.001").torque_rate_limit, repeated(0.001));
}

TEST(WrapperConfig, JointListBeyondTheCapacityIsRefused) {
  std::string joints = "joints: [j1";
  for (int i = 2; i <= kMaxDof + 1; ++i) {
    joints += ", j" + std::to_string(i);
  }
  expectError(controllerYaml(joints + "]"), {kPrefix + "joints: has 13 entries, expected 1 to 12"});
  expectError(controllerYaml("joints: []"), {kPrefix + "joints: has 0 entries"});
}

TEST(WrapperConfig, GainBlocksTakeOneThreeOrNineValues) {
  const WrapperConfig config = parse(
      "initial:\n"
      "  stiffness_translational: 800\n"
      "  stiffness_rotational: [10, 20, 30]\n"
      "  damping_translational: [4, 1, 0, 1, 5, 2, 0, 2, 6]\n");
  const CartesianCommand& c = config.initial_cartesian;
  EXPECT_EQ(c.stiffness_translational, 800.0 * Eigen::Matrix3d::Identity());
  EXPECT_EQ(c.stiffness_rotational, Eigen::Vector3d(10, 20, 30).asDiagonal().toDenseMatrix());
  Eigen::Matrix3d full;
  full << 4, 1, 0, 1, 5, 2, 0, 2, 6;  // symmetric positive definite, as every gain block must be
  EXPECT_EQ(c.damping_translational, full);
  EXPECT_EQ(c.damping_rotational, 3.0 * Eigen::Matrix3d::Identity());  // default kept
}

TEST(WrapperConfig, InitialGainsAreCheckedLikeACommand) {
  // An asymmetric, an indefinite and a negative gain run away on a robot: refused at load, as the
  // same values in a command are.
  expectError(controllerYaml("initial:\n  damping_translational: [1, 2, 3, 4, 5, 6, 7, 8, 9]"),
              {kPrefix + "initial.damping_translational: ", "symmetric positive semi-definite"});
  expectError(controllerYaml("initial:\n  stiffness_translational: [100, -5, 100]"),
              {kPrefix + "initial.stiffness_translational: "});
  expectError(controllerYaml("initial:\n  nullspace_damping: -1"),
              {kPrefix + "initial.nullspace_damping: "});
  // A feedforward beyond any arm would pin every joint at its effort limit from the first cycle.
  expectError(controllerYaml("initial:\n  wrench_feedforward: [1.0e9, 0, 0, 0, 0, 0]"),
              {kPrefix + "initial.wrench_feedforward: ", "above the limit of 10000"});
}

TEST(WrapperConfig, GainBlockOfTheWrongLengthNamesTheKey) {
  expectError(
      controllerYaml("initial:\n  damping_rotational: [1, 2]"),
      {kPrefix +
       "initial.damping_rotational: 'damping_rotational' has 2 numbers, expected 1, 3 or 9"});
}

TEST(WrapperConfig, ReadsInitialJointAndNullspaceGains) {
  const WrapperConfig config = parse(
      "initial:\n"
      "  stiffness: [1, 2, 3, 4, 5, 6, 7]\n"
      "  damping: 0.5\n"
      "  damping_mode: absolute\n"
      "  damping_ratio: [0.5, 0.6, 0.7, 0.8, 0.9, 1.0]\n"
      "  nullspace_stiffness: 7\n"
      "  nullspace_damping: [0, 1, 0, 1, 0, 1, 0]\n");
  JointVector expected_stiffness(7);
  expected_stiffness << 1, 2, 3, 4, 5, 6, 7;
  EXPECT_EQ(config.initial_joint.stiffness, expected_stiffness);
  EXPECT_EQ(config.initial_joint.damping, JointVector::Constant(7, 0.5));
  const CartesianCommand& c = config.initial_cartesian;
  EXPECT_EQ(c.damping_mode, DampingMode::kAbsolute);
  Vector6d ratio;
  ratio << 0.5, 0.6, 0.7, 0.8, 0.9, 1.0;
  EXPECT_EQ(c.damping_ratio, ratio);
  EXPECT_EQ(c.nullspace_stiffness, JointVector::Constant(7, 7.0));
  JointVector expected_damping(7);
  expected_damping << 0, 1, 0, 1, 0, 1, 0;
  EXPECT_EQ(c.nullspace_damping, expected_damping);
}

TEST(WrapperConfig, BadDampingModeNamesTheKey) {
  expectError(controllerYaml("initial:\n  damping_mode: critical"),
              {kPrefix + "initial.damping_mode: 'damping_mode' must be \"absolute\" or \"ratio\""});
}

TEST(WrapperConfig, TaskFrameIsXyzw) {
  const WrapperConfig config = parse("initial:\n  task_frame: [1, 0, 0, 0]");
  const Eigen::Quaterniond& q = config.initial_cartesian.task_frame;
  EXPECT_EQ(q.x(), 1.0);
  EXPECT_EQ(q.w(), 0.0);
  EXPECT_EQ(q.y(), 0.0);
  EXPECT_EQ(q.z(), 0.0);
}

TEST(WrapperConfig, NonUnitTaskFrameNamesTheKey) {
  expectError(controllerYaml("initial:\n  task_frame: [0, 0, 0, 2]"),
              {kPrefix + "initial.task_frame: task_frame is not a unit quaternion"});
  expectError(controllerYaml("initial:\n  task_frame: [0, 0, 1]"),
              {kPrefix + "initial.task_frame: 'task_frame' has 3 numbers, expected 4"});
}

TEST(WrapperConfig, FilterAlphaMustBeInTheHalfOpenUnitInterval) {
  EXPECT_EQ(parse("filter_alpha: 1").filter_alpha, 1.0);
  for (const char* bad : {"0", "1.5", "-0.2", ".nan"}) {
    SCOPED_TRACE(bad);
    expectError(controllerYaml(std::string("filter_alpha: ") + bad),
                {kPrefix + "filter_alpha: must be in (0, 1]"});
  }
  expectError(controllerYaml("filter_alpha: strong"),
              {kPrefix + "filter_alpha: has the wrong type"});
}

TEST(WrapperConfig, BadTimeoutBehaviorNamesTheKey) {
  expectError(controllerYaml("timeout_behavior: drop"),
              {kPrefix + "timeout_behavior: must be hold or reanchor"});
}

TEST(WrapperConfig, UnknownKeysAreNamedAtEveryLevel) {
  expectError(controllerYaml("filter_alpah: 0.5"),
              {kPrefix + "filter_alpah: is not a known option"});
  expectError(controllerYaml("validation:\n  max_jump: 1"),
              {kPrefix + "validation.max_jump: is not a known option"});
  expectError(controllerYaml("compensation:\n  friction:\n    model: none\n    phi: 1"),
              {kPrefix + "compensation.friction.phi: is not a known option"});
  expectError(controllerYaml("initial:\n  stiffnes: 1"),
              {kPrefix + "initial.stiffnes: is not a known option"});
}

TEST(WrapperConfig, MissingPluginOrRobotNamesTheKey) {
  expectError("c:\n  ros__parameters:\n    robot: fr3\n",
              {"arm.yaml: c.ros__parameters.plugin: is required"});
  expectError("c:\n  ros__parameters:\n    plugin: joint_impedance\n",
              {"arm.yaml: c.ros__parameters.robot: is required"});
}

TEST(WrapperConfig, InvalidYamlIsReportedWithTheSource) {
  expectError("arm_controller: [unclosed\n", {"arm.yaml: not valid YAML"});
  expectError("", {"arm.yaml: expected '<controller_name>: ros__parameters: ...'"});
  expectError("arm_controller:\n  plugin: x\n", {"arm_controller: has no 'ros__parameters'"});
}

TEST(WrapperConfig, SeveralControllersNeedAName) {
  const std::string yaml = controllerYaml() +
                           "other_controller:\n"
                           "  ros__parameters:\n"
                           "    plugin: joint_impedance\n"
                           "    robot: fr3\n";
  expectError(yaml, {"arm.yaml: holds several controllers; name the one to use"});
  const WrapperConfig other = parseWrapperConfig(yaml, kSource, "other_controller");
  EXPECT_EQ(other.name, "other_controller");
  EXPECT_EQ(other.plugin, "joint_impedance");
  expectError(yaml, {"arm.yaml: no controller named 'third'"}, "third");
}

TEST(WrapperConfig, SigmoidFrictionDefaultsToTheRobotFile) {
  const WrapperConfig config = parse("compensation:\n  friction:\n    model: sigmoid");
  EXPECT_EQ(config.friction.model, FrictionModel::kSigmoid);
  // robots/fr3/robot.yaml
  EXPECT_EQ(config.friction.phi1,
            (std::vector<double>{0.54615, 0.87224, 0.64068, 1.2794, 0.83904, 0.30301, 0.56489}));
  EXPECT_EQ(config.friction.phi2,
            (std::vector<double>{5.1181, 9.0657, 10.136, 5.5903, 8.3469, 17.133, 10.336}));
  EXPECT_EQ(config.friction.phi3, (std::vector<double>{0.039533, 0.025882, -0.04607, 0.036194,
                                                       0.026226, -0.021047, 0.0035526}));
}

TEST(WrapperConfig, SigmoidFrictionForOtherJointsNeedsItsOwnParameters) {
  expectError(controllerYaml("joints: [fr3_joint1, fr3_joint2]\n"
                             "compensation:\n  friction:\n    model: sigmoid"),
              {kPrefix + "compensation.friction: model sigmoid needs phi1, phi2, phi3"});
  const WrapperConfig config = parse(
      "joints: [fr3_joint1, fr3_joint2]\n"
      "compensation:\n  friction:\n    model: sigmoid\n    phi1: 1\n    phi2: [2, 3]\n"
      "    phi3: 0");
  EXPECT_EQ(config.friction.phi1, (std::vector<double>{1, 1}));
  EXPECT_EQ(config.friction.phi2, (std::vector<double>{2, 3}));
  EXPECT_EQ(config.friction.phi3, (std::vector<double>{0, 0}));
}

TEST(WrapperConfig, ViscousCoulombFriction) {
  const WrapperConfig config = parse(
      "compensation:\n"
      "  friction:\n"
      "    model: viscous_coulomb\n"
      "    viscous: 0.2\n"
      "    coulomb: [1, 1, 1, 1, 0.5, 0.5, 0.5]\n"
      "    smoothing_velocity: 0.05");
  EXPECT_EQ(config.friction.model, FrictionModel::kViscousCoulomb);
  EXPECT_EQ(config.friction.viscous, repeated(0.2));
  EXPECT_EQ(config.friction.coulomb, (std::vector<double>{1, 1, 1, 1, 0.5, 0.5, 0.5}));
  EXPECT_EQ(config.friction.smoothing_velocity, 0.05);
  expectError(controllerYaml("compensation:\n  friction:\n    model: viscous_coulomb\n"
                             "    smoothing_velocity: 0"),
              {kPrefix + "compensation.friction.smoothing_velocity: must be > 0"});
  expectError(controllerYaml("compensation:\n  friction:\n    model: lugre"),
              {kPrefix + "compensation.friction.model: must be none, sigmoid or viscous_coulomb"});
}

TEST(WrapperConfig, ReadsTheGainStageAndRefusesATankWithoutRampsOrOutOfOrder) {
  const WrapperConfig config = parse(
      "gain_ramps:\n  enabled: true\n  translational_stiffness_per_s: 500.0\n"
      "passivity:\n  enabled: true\n  tank_initial_j: 0.5\n  tank_max_j: 3.0\n");
  EXPECT_TRUE(config.gain_ramps.enabled);
  EXPECT_EQ(config.gain_ramps.translational_stiffness_per_s, 500.0);
  EXPECT_EQ(config.gain_ramps.task_frame_rad_per_s, 1.0);
  EXPECT_TRUE(config.passivity.enabled);
  EXPECT_EQ(config.passivity.tank_initial_j, 0.5);
  EXPECT_EQ(config.passivity.tank_max_j, 3.0);
  EXPECT_FALSE(parse("").passivity.enabled);
  EXPECT_FALSE(parse("").gain_ramps.enabled);
  expectError(controllerYaml("passivity:\n  enabled: true"),
              {kPrefix + "passivity.enabled: needs gain_ramps.enabled: true"});
  expectError(controllerYaml("passivity:\n  tank_initial_j: 3.0"),
              {kPrefix + "passivity.tank_initial_j: must lie between passivity.tank_min_j and "
                         "passivity.tank_max_j"});
  expectError(controllerYaml("passivity:\n  tank_min_j: 2.0"),
              {kPrefix + "passivity.tank_min_j: must be below passivity.tank_max_j"});
  expectError(controllerYaml("gain_ramps:\n  joint_stiffness_per_s: 0"),
              {kPrefix + "gain_ramps.joint_stiffness_per_s: must be"});
}

TEST(WrapperConfig, ReadsPayload) {
  const WrapperConfig config = parse(
      "compensation:\n"
      "  gravity: false\n"
      "  payload:\n"
      "    enabled: true\n"
      "    mass_kg: 1.25\n"
      "    com_m: [0.0, 0.01, 0.1]");
  EXPECT_FALSE(config.gravity_compensation);
  EXPECT_TRUE(config.payload_compensation);
  EXPECT_EQ(config.payload.mass_kg, 1.25);
  EXPECT_EQ(config.payload.com_in_tip, Eigen::Vector3d(0.0, 0.01, 0.1));
  expectError(controllerYaml("compensation:\n  payload:\n    com_m: [0, 0]"),
              {kPrefix + "compensation.payload.com_m: must be [x, y, z]"});
  expectError(controllerYaml("compensation:\n  payload:\n    mass_kg: -1"),
              {kPrefix + "compensation.payload.mass_kg: must be in [0, 1000]"});
}

TEST(WrapperConfig, LoadsFromAFileAndNamesItInErrors) {
  const std::filesystem::path file =
      std::filesystem::path(::testing::TempDir()) / "pipeline_config_test.yaml";
  {
    std::ofstream out(file);
    out << controllerYaml("filter_alpha: 0.75");
  }
  EXPECT_EQ(loadWrapperConfig(file).filter_alpha, 0.75);
  {
    std::ofstream out(file);
    out << controllerYaml("filter_alpha: 2");
  }
  try {
    loadWrapperConfig(file);
    ADD_FAILURE() << "expected an error";
  } catch (const std::runtime_error& error) {
    EXPECT_NE(std::string(error.what()).find(file.string() + ": arm_controller"), std::string::npos)
        << error.what();
  }
  std::filesystem::remove(file);
  EXPECT_THROW(loadWrapperConfig(file), std::runtime_error);
}

}  // namespace
}  // namespace comply::pipeline

namespace comply::pipeline {
namespace {

TEST(DocumentedDefaults, TheDocumentedFileIsWhatTheOptionTablePrints) {
  // config/cartesian_impedance.yaml is `comply config --defaults` for the FR3: regenerate it with
  // that command when an option changes.
  const std::filesystem::path file =
      std::filesystem::path(COMPLY_SOURCE_DIR) / "config" / "cartesian_impedance.yaml";
  std::ifstream stream(file);
  ASSERT_TRUE(stream) << file;
  std::stringstream committed;
  committed << stream.rdbuf();
  EXPECT_EQ(committed.str(), documentedDefaults("cartesian_impedance", "cartesian_impedance", "fr3",
                                                "fr3_tcp", /*cartesian=*/true));
}

TEST(DocumentedDefaults, PrintedDefaultsReadBackAsTheDefaults) {
  for (const bool cartesian : {true, false}) {
    const WrapperConfig printed = parseWrapperConfig(
        documentedDefaults("arm", cartesian ? "cartesian_impedance" : "joint_impedance", "fr3",
                           "fr3_tcp", cartesian),
        "printed");
    const WrapperConfig bare = parseWrapperConfig(
        "arm:\n  ros__parameters:\n    plugin: x\n    robot: fr3\n    tip_frame: fr3_tcp\n",
        "bare");
    for (const OptionDeclaration& option : optionDeclarations()) {
      EXPECT_EQ(optionValue(printed, option.name), optionValue(bare, option.name)) << option.name;
    }
    EXPECT_EQ(printed.initial_cartesian.stiffness_translational,
              bare.initial_cartesian.stiffness_translational);
    EXPECT_EQ(printed.initial_cartesian.damping_mode, bare.initial_cartesian.damping_mode);
    EXPECT_EQ(printed.initial_cartesian.nullspace_damping,
              bare.initial_cartesian.nullspace_damping);
    EXPECT_EQ(printed.initial_joint.stiffness, bare.initial_joint.stiffness);
    EXPECT_EQ(printed.initial_joint.damping, bare.initial_joint.damping);
  }
}

TEST(WrapperConfig, NonFiniteOrNegativeValidationLimitsAreRefused) {
  // A NaN jump limit would switch the check off; a NaN tolerance would reject every command; an
  // infinite one is refused even where no upper bound is (0 is how options say "off").
  for (const char* line :
       {"validation:\n  max_position_jump_m: .nan", "validation:\n  quaternion_tolerance: -1.0e-3",
        "validation:\n  max_orientation_jump_rad: .inf", "validation:\n  max_position_jump_m: .inf",
        "command_timeout_s: .inf", "torque_rate_limit_nm_per_s: [.inf]", "command_timeout_s: .nan",
        "effort_limit_nm: .nan", "compensation:\n  payload:\n    mass_kg: .nan"}) {
    SCOPED_TRACE(line);
    EXPECT_THROW(parse(line), InputError);
  }
}

TEST(WrapperConfig, EachRefusedLimitIsNamedWithItsKey) {
  // The message must name the key a user wrote (an effort limit used to be reported as missing
  // from the URDF), so each bad value is checked against its own key.
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"validation:\n  quaternion_tolerance: .nan", "validation.quaternion_tolerance"},
      {"validation:\n  quaternion_tolerance: -1.0e-3", "validation.quaternion_tolerance"},
      {"validation:\n  max_position_jump_m: .nan", "validation.max_position_jump_m"},
      {"effort_limit_nm: -5.0", "effort_limit_nm"},
      {"effort_limit_nm: [87, 87, 87, 87, 12, .nan, 12]", "effort_limit_nm"},
      {"compensation:\n  payload:\n    mass_kg: .nan", "compensation.payload.mass_kg"},
      {"compensation:\n  friction:\n    model: viscous_coulomb\n    viscous: .nan\n"
       "    coulomb: 0.1",
       "compensation.friction.viscous"},
      {"compensation:\n  friction:\n    model: sigmoid\n    phi1: [.nan, 0, 0, 0, 0, 0, 0]",
       "compensation.friction.phi1: must be a finite number"},
  };
  for (const auto& [line, key] : cases) {
    SCOPED_TRACE(line);
    expectError(controllerYaml(line), {kPrefix + key});
    try {
      parse(line);
    } catch (const std::runtime_error& error) {
      EXPECT_EQ(std::string(error.what()).find("URDF"), std::string::npos) << error.what();
    }
  }
}

}  // namespace
}  // namespace comply::pipeline
