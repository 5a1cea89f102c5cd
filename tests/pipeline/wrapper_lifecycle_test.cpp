// Lifecycle of both wrappers: nothing is written before activation or after deactivation, and
// every activation seeds the reference from the measured state, so the law starts at zero torque
// and the arm does not jump (docs/design.md, "Safety semantics").

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <type_traits>

#include "comply/pipeline/wrapper.hpp"
#include "wrapper_support.hpp"

namespace comply::pipeline::test {
namespace {

/// Seeding is exact (the reference is the measured pose itself), so the law's torque is zero up
/// to rounding in the model and the law.
constexpr double kSeededTolerance = 1e-9;

template <typename WrapperType>
struct Law;
template <>
struct Law<JointWrapper> {
  static std::string plugin() { return kJointImpedancePlugin; }
  /// Joint target of the command in force.
  static JointVector referenceJoints(const JointCommand& command) { return command.position; }
};
template <>
struct Law<CartesianWrapper> {
  static std::string plugin() { return kCartesianImpedancePlugin; }
  /// For a Cartesian command the joint-space reference is the nullspace target.
  static JointVector referenceJoints(const CartesianCommand& command) {
    return command.nullspace_position;
  }
};

template <typename WrapperType>
class WrapperLifecycle : public ::testing::Test {
 protected:
  WrapperType wrapper{fr3Config(Law<WrapperType>::plugin())};
  const JointVector home = fr3Home();
  TorqueBuffer torque;

  CycleStatus cycle(const JointState& state) {
    return wrapper.update(state, kPeriod, torque.span());
  }
  bool torqueUntouched() const { return (torque.values.array() == TorqueBuffer::kUntouched).all(); }
  JointVector referenceJoints() const {
    return Law<WrapperType>::referenceJoints(wrapper.lastAccepted());
  }
};

struct WrapperName {
  template <typename T>
  static std::string GetName(int) {
    return std::is_same_v<T, JointWrapper> ? "Joint" : "Cartesian";
  }
};
using Wrappers = ::testing::Types<JointWrapper, CartesianWrapper>;
TYPED_TEST_SUITE(WrapperLifecycle, Wrappers, WrapperName);

TYPED_TEST(WrapperLifecycle, UpdateBeforeActivationIsInactiveAndWritesNothing) {
  const JointState state = restingAt(this->wrapper.controller(), this->home);
  for (int i = 0; i < 5; ++i) {
    EXPECT_EQ(this->cycle(state), CycleStatus::kInactive);
  }
  // Not running means not judging the state either: an inactive controller does not fault.
  JointState broken = state;
  broken.position[2] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(this->cycle(broken), CycleStatus::kInactive);

  EXPECT_TRUE(this->torqueUntouched()) << this->torque.values.transpose();
  const DiagnosticsSnapshot diagnostics = this->wrapper.diagnostics();
  EXPECT_EQ(diagnostics.state, WrapperState::kInactive);
  EXPECT_EQ(diagnostics.faults, 0U);
}

TYPED_TEST(WrapperLifecycle, ActivationSeedsTheReferenceFromTheMeasuredState) {
  // Away from home and from zero, so neither the configured nor a default reference would pass.
  const JointVector q = offset(offset(this->home, 0, 0.3), 3, -0.2);
  const JointState state = restingAt(this->wrapper.controller(), q);
  this->wrapper.activate(state);
  EXPECT_EQ(this->wrapper.diagnostics().state, WrapperState::kActive);

  for (int i = 0; i < 3; ++i) {
    ASSERT_EQ(this->cycle(state), CycleStatus::kOk);
    // Gravity compensation alone: the law adds nothing at rest on its own reference.
    COMPLY_EXPECT_JOINTS_NEAR(this->torque.values, state.effort, kSeededTolerance);
  }
  COMPLY_EXPECT_JOINTS_NEAR(this->referenceJoints(), q, 0.0);
}

TYPED_TEST(WrapperLifecycle, DeactivationStopsTheOutput) {
  const JointState state = restingAt(this->wrapper.controller(), this->home);
  this->wrapper.activate(state);
  ASSERT_EQ(this->cycle(state), CycleStatus::kOk);

  this->wrapper.deactivate();
  EXPECT_EQ(this->wrapper.diagnostics().state, WrapperState::kInactive);
  this->torque = TorqueBuffer{};
  EXPECT_EQ(this->cycle(state), CycleStatus::kInactive);
  EXPECT_TRUE(this->torqueUntouched()) << this->torque.values.transpose();
}

TYPED_TEST(WrapperLifecycle, ReactivationSeedsAgainAtTheNewState) {
  const JointState first = restingAt(this->wrapper.controller(), this->home);
  this->wrapper.activate(first);
  ASSERT_EQ(this->cycle(first), CycleStatus::kOk);
  this->wrapper.deactivate();

  // The arm was moved by hand while the controller was inactive.
  const JointVector moved = offset(offset(this->home, 1, 0.2), 5, -0.15);
  const JointState second = restingAt(this->wrapper.controller(), moved);
  this->wrapper.activate(second);
  ASSERT_EQ(this->cycle(second), CycleStatus::kOk);
  // Pulled back towards the first pose, the law would add hundreds of N m here.
  COMPLY_EXPECT_JOINTS_NEAR(this->torque.values, second.effort, kSeededTolerance);
  COMPLY_EXPECT_JOINTS_NEAR(this->referenceJoints(), moved, 0.0);
}

TYPED_TEST(WrapperLifecycle, ActivationRefusesAnUnusableStateAndStaysInactive) {
  JointState nan_state = restingAt(this->wrapper.controller(), this->home);
  nan_state.velocity[4] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(this->wrapper.activate(nan_state), std::runtime_error);

  const JointState short_state = JointState::zero(kFr3Dof - 1);
  EXPECT_THROW(this->wrapper.activate(short_state), std::runtime_error);

  EXPECT_EQ(this->wrapper.diagnostics().state, WrapperState::kInactive);
  EXPECT_EQ(this->cycle(restingAt(this->wrapper.controller(), this->home)), CycleStatus::kInactive);
  EXPECT_TRUE(this->torqueUntouched());
}

}  // namespace
}  // namespace comply::pipeline::test
