#pragma once
// Shared set-up of the wrapper tests: FR3 controller configurations, measured states and torque
// comparisons. The plugin files come from the build (COMPLY_TEST_* paths), so the tests do not
// depend on $COMPLY_PLUGIN_PATH.

#include <gtest/gtest.h>

#include <span>
#include <string>

#include "comply/core/state.hpp"
#include "comply/pipeline/config.hpp"
#include "comply/pipeline/controller.hpp"

namespace comply::pipeline::test {

inline constexpr int kFr3Dof = 7;
inline constexpr double kPeriod = 0.001;  // 1 kHz
/// A torque-rate limit [N m/s] that never binds, for tests about the law rather than shaping.
inline constexpr double kNoRateLimit = 1e9;

inline const std::string kJointImpedancePlugin = COMPLY_TEST_JOINT_IMPEDANCE;
inline const std::string kCartesianImpedancePlugin = COMPLY_TEST_CARTESIAN_IMPEDANCE;
inline const std::string kStepNanPlugin = COMPLY_TEST_FIXTURE_STEP_NAN;
inline const std::string kStepErrorPlugin = COMPLY_TEST_FIXTURE_STEP_ERROR;
/// Fails on a moving arm with a message that fills its buffer and has no NUL.
inline const std::string kUnterminatedErrorPlugin = COMPLY_TEST_FIXTURE_STEP_ERROR_UNTERMINATED;
inline const std::string kThrowingPlugin = COMPLY_TEST_FIXTURE_THROWING;
inline const std::string kThrowingActivatePlugin = COMPLY_TEST_FIXTURE_THROWING_ACTIVATE;

/// A controller file for `plugin` on `robot` (a name or a folder) with `parameter_lines` (YAML,
/// unindented) below them.
WrapperConfig controllerConfig(const std::string& plugin, const std::string& robot,
                               const std::string& parameter_lines);

/// Configuration of a controller for the FR3 with `plugin`; `parameter_lines` are YAML lines at
/// the level of `plugin:` (nested keys indented further, by two spaces per level).
WrapperConfig fr3Config(const std::string& plugin, const std::string& parameter_lines = {});

/// The FR3 home ("ready") pose from robots/fr3/robot.yaml.
JointVector fr3Home();

/// Gravity torque g(q) of the core's model.
JointVector gravityAt(const Controller& core, const JointVector& q);

/// The arm at rest at `q`, its joints carrying the gravity torque (what a holding arm measures, so
/// the torque-rate limit starts from there).
JointState restingAt(const Controller& core, const JointVector& q);

/// `q` with `delta` added to joint `joint`.
JointVector offset(const JointVector& q, int joint, double delta);

/// A smooth motion around `home` at `cycle` (kPeriod apart), different on every joint (joint i at
/// base_hz + 0.1 i Hz, `amplitude` [rad]), so every cycle computes new numbers; effort 0.
JointState movingState(const JointVector& home, int cycle, double amplitude, double base_hz);

/// A torque buffer for dof joints, filled with a value no controller would write.
struct TorqueBuffer {
  static constexpr double kUntouched = 123456.0;
  JointVector values = JointVector::Constant(kFr3Dof, kUntouched);
  std::span<double> span() { return {values.data(), static_cast<std::size_t>(values.size())}; }
};

/// Largest absolute difference, for messages and tolerances.
double maxDifference(const JointVector& a, const JointVector& b);

}  // namespace comply::pipeline::test

/// Expects two joint vectors to agree within `tolerance` in every entry.
#define COMPLY_EXPECT_JOINTS_NEAR(actual, expected, tolerance)                          \
  EXPECT_LE(::comply::pipeline::test::maxDifference((actual), (expected)), (tolerance)) \
      << "actual:   " << (actual).transpose() << "\nexpected: " << (expected).transpose()
