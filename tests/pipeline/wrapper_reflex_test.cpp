// The contact reflex through the wrapper on the FR3 at rest, the contact wrench read from its
// wrist sensor (observer off): each reaction in the cycle the debounce ends, the hold's latch
// (commands and chunks refused, one already queued taken without effect) until a reset, which
// resumes from the measured pose with the file's thresholds; a command's thresholds for its phase,
// within the ceiling, a refused one leaving the last in force; a joint law's hold; no estimate.

#include <gtest/gtest.h>

#include <string>

#include "comply/pipeline/wrapper.hpp"
#include "comply/schema/schema.hpp"
#include "resting_fr3.hpp"
#include "wrapper_support.hpp"

namespace comply::pipeline::test {
namespace {

std::string reflexLines(const std::string& reaction, const std::string& more = {}) {
  return "frozen_state_timeout_s: 0\n"
         "reflex:\n  enabled: true\n  reaction: " +
         reaction +
         "\n  force_n: 20.0\n  torque_nm: 5.0\n  max_force_n: 50.0\n  debounce_s: 0.005\n" + more;
}

Vector6d push(double x, double y, double z) {
  Vector6d wrench = Vector6d::Zero();
  wrench.head<3>() << x, y, z;
  return wrench;
}

class Reflex : public RestingFr3 {
 protected:
  explicit Reflex(const std::string& reaction = "hold", const std::string& more = {})
      : RestingFr3(reflexLines(reaction, more), 0.0) {}

  void SetUp() override {
    RestingFr3::SetUp();
    feel(Vector6d::Zero());
  }
  void feel(const Vector6d& wrench) {
    state.wrench = wrench;
    state.wrench_valid = true;
  }
  /// Cycles with `wrench` on the sensor until the reflex trips (at most `limit`); the cycle it
  /// tripped in, 1-based, or 0.
  int cyclesToTrip(const Vector6d& wrench, int limit = 50) {
    feel(wrench);
    for (int cycle = 1; cycle <= limit; ++cycle) {
      (void)wrapper.update(state, kPeriod, torque.span());
      ++cycle_count;
      if (wrapper.controller().reflex().tripped()) {
        return cycle;
      }
    }
    return 0;
  }
  /// A command moving the reference 2 cm along x at 0.1 m/s.
  CartesianCommand moving() {
    CartesianCommand command = CartesianCommand::zero(kFr3Dof);
    command.stamp_s = ++stamp;
    command.fields = CommandField::kPosition | CommandField::kVelocity;
    command.position = home_position + Eigen::Vector3d(0.02, 0.0, 0.0);
    command.orientation = home_orientation;
    command.twist[0] = 0.1;
    return command;
  }
  CartesianCommand thresholds(const Eigen::Vector3d& force, const Eigen::Vector3d& torque_nm) {
    CartesianCommand command = CartesianCommand::zero(kFr3Dof);
    command.stamp_s = ++stamp;
    command.fields = CommandField::kReflex;
    command.reflex_force = force;
    command.reflex_torque = torque_nm;
    return command;
  }
  [[nodiscard]] const comply_cartesian_command& inForce() {
    return std::get<comply_cartesian_command>(wrapper.controller().commandInForce());
  }
  /// The reference in force is the measured pose, at rest, pushing nothing.
  void expectHeldAtHome() {
    const comply_cartesian_command& held = inForce();
    EXPECT_LT((Eigen::Map<const Eigen::Vector3d>(held.position) - home_position).norm(), 1e-12);
    EXPECT_EQ(Eigen::Map<const Vector6d>(held.twist), Vector6d::Zero());
    EXPECT_EQ(Eigen::Map<const Vector6d>(held.wrench_feedforward), Vector6d::Zero());
  }

  double stamp = 0.0;
};

TEST_F(Reflex, AHoldTripsAfterTheDebounceAndRefusesCommandsUntilAReset) {
  ASSERT_TRUE(wrapper.submit(moving()).accepted);
  EXPECT_EQ(cyclesToTrip(push(0.0, 30.0, 0.0)), 6);  // above for 5 ms: the sixth sample
  EXPECT_EQ(wrapper.diagnostics().reflex_trips, 1U);
  EXPECT_TRUE(wrapper.diagnostics().reflex_latched);
  EXPECT_EQ(wrapper.controller().reflex().wrench(), push(0.0, 30.0, 0.0));
  EXPECT_EQ(wrapper.diagnostics().state, WrapperState::kActive);  // the law still holds the arm
  expectHeldAtHome();                                             // not the command that moved it

  // Nothing is taken while it holds, the push gone or not.
  feel(Vector6d::Zero());
  const Verdict refused = wrapper.submit(moving());
  EXPECT_FALSE(refused.accepted);
  EXPECT_EQ(refused.reason, RejectionReason::kReflexLatched);
  EXPECT_NE(refused.message.find("reset"), std::string::npos) << refused.message;
  CartesianChunk chunk;
  chunk.stamp_s = ++stamp;
  chunk.fields = CommandField::kPosition;
  chunk.waypoints.push_back({hostTime() + 0.05, moving()});
  EXPECT_EQ(wrapper.submitChunk(chunk, hostTime()).reason, RejectionReason::kReflexLatched);
  EXPECT_EQ(
      wrapper.diagnostics().rejections[static_cast<std::size_t>(RejectionReason::kReflexLatched)],
      2U);
  cycles(50);
  expectHeldAtHome();
  EXPECT_TRUE(wrapper.controller().reflex().latched());

  // A reset ends it: the measured pose held, commands taken again from the reset on.
  ASSERT_NE(wrapper.reset(), 0U);
  ASSERT_TRUE(wrapper.submit(moving()).accepted);  // queued behind the reset
  cycles(1);
  ResetResult result;
  ASSERT_TRUE(wrapper.controller().takeResetResult(result));
  EXPECT_EQ(result.end, ResetResult::End::kLeftReflex);
  EXPECT_FALSE(wrapper.controller().reflex().tripped());
  EXPECT_FALSE(wrapper.diagnostics().reflex_latched);
  EXPECT_EQ(Eigen::Map<const Eigen::Vector3d>(inForce().position),
            home_position + Eigen::Vector3d(0.02, 0.0, 0.0));
  // Armed again.
  EXPECT_EQ(cyclesToTrip(push(30.0, 0.0, 0.0)), 6);
  EXPECT_EQ(wrapper.diagnostics().reflex_trips, 2U);
}

TEST_F(Reflex, ACommandTheIntakeTookBeforeTheTripIsTakenWithoutEffect) {
  ASSERT_EQ(cyclesToTrip(push(0.0, 0.0, -30.0)), 6);
  // Queued by an intake that had not seen the trip yet (the same cycle): straight to the queue.
  IntakeMessage late;
  late.command = schema::toBus(moving(), kFr3Dof);
  std::get<comply_cartesian_command>(late.command).fields =
      static_cast<std::uint32_t>(CommandField::kPosition | CommandField::kVelocity);
  late.id = {.sequence = 77, .stamp_ns = 5};
  ASSERT_TRUE(wrapper.controller().enqueue(late));
  cycles(1);
  EXPECT_EQ(wrapper.controller().idInForce().sequence, 77U);  // its outcome is settled
  expectHeldAtHome();
}

TEST_F(Reflex, ThePhasesThresholdsLetAPushAlongTheRaisedAxisThroughAndAResetReturnsTheFiles) {
  ASSERT_TRUE(wrapper.submit(thresholds({0.0, 0.0, 40.0}, {0.0, 0.0, 0.0})).accepted);
  EXPECT_EQ(cyclesToTrip(push(0.0, 0.0, 30.0), 200), 0);  // along the raised task z
  EXPECT_EQ(wrapper.controller().reflex().inForce().force_n, Eigen::Vector3d(20.0, 20.0, 40.0));

  // Above the ceiling, negative, NaN: refused, naming the field; the 40 N stays in force.
  const Verdict above = wrapper.submit(thresholds({0.0, 0.0, 80.0}, {0.0, 0.0, 0.0}));
  EXPECT_FALSE(above.accepted);
  EXPECT_EQ(above.reason, RejectionReason::kOutOfRange);
  EXPECT_NE(above.message.find("reflex_force along z is 80 N, above the ceiling "
                               "reflex.max_force_n of 50 N"),
            std::string::npos)
      << above.message;
  const Verdict negative = wrapper.submit(thresholds({0.0, -1.0, 45.0}, {0.0, 0.0, 0.0}));
  EXPECT_EQ(negative.reason, RejectionReason::kOutOfRange);
  EXPECT_NE(negative.message.find("reflex_force entries must be >= 0"), std::string::npos)
      << negative.message;
  const Verdict nan = wrapper.submit(thresholds({0.0, 0.0, 45.0}, {std::nan(""), 0.0, 0.0}));
  EXPECT_EQ(nan.reason, RejectionReason::kNonFinite);
  EXPECT_EQ(cyclesToTrip(push(0.0, 0.0, 35.0), 200), 0);
  EXPECT_EQ(cyclesToTrip(push(0.0, 0.0, 45.0)), 6);  // 40 N is what is in force

  // The reset: the phase is over, the file's 20 N along every axis again.
  ASSERT_NE(wrapper.reset(), 0U);
  feel(Vector6d::Zero());
  cycles(1);
  EXPECT_EQ(Eigen::Map<const Eigen::Vector3d>(inForce().reflex_force), Eigen::Vector3d::Zero());
  EXPECT_EQ(cyclesToTrip(push(0.0, 0.0, 30.0)), 6);
}

TEST_F(Reflex, ATorqueAboveItsThresholdTripsToo) {
  Vector6d twist = Vector6d::Zero();
  twist[4] = 7.0;
  EXPECT_EQ(cyclesToTrip(twist), 6);
  EXPECT_EQ(wrapper.controller().reflex().wrench(), twist);
}

TEST_F(Reflex, ChunksCannotCarryThresholds) {
  CartesianChunk chunk;
  chunk.stamp_s = ++stamp;
  chunk.fields = CommandField::kPosition | CommandField::kReflex;
  CartesianCommand waypoint = moving();
  waypoint.reflex_force = Eigen::Vector3d(30.0, 30.0, 30.0);
  chunk.waypoints.push_back({hostTime() + 0.05, waypoint});
  const Verdict verdict = wrapper.submitChunk(chunk, hostTime());
  EXPECT_EQ(verdict.reason, RejectionReason::kInvalidChunk);
  EXPECT_NE(verdict.message.find("reflex"), std::string::npos) << verdict.message;
}

class RetreatingReflex : public Reflex {
 protected:
  RetreatingReflex()
      : Reflex("retreat",
               "  retreat_m: 0.01\n  retreat_speed_m_per_s: 0.05\n"
               "  hold_stiffness_fraction: 0.5\n") {}
};

TEST_F(RetreatingReflex, TheReferenceBacksOffAlongThePushAtItsSpeedThenHolds) {
  const double stiffness = inForce().stiffness_translational[0];
  const Vector6d along_y = push(0.0, 30.0, 0.0);
  ASSERT_EQ(cyclesToTrip(along_y), 6);
  expectHeldAtHome();  // the trip's cycle: where the arm is
  EXPECT_DOUBLE_EQ(inForce().stiffness_translational[0], 0.5 * stiffness);
  cycles(100);  // 0.1 s at 0.05 m/s
  Eigen::Vector3d offset = Eigen::Map<const Eigen::Vector3d>(inForce().position) - home_position;
  EXPECT_LT((offset - Eigen::Vector3d(0.0, 0.005, 0.0)).norm(), 1e-9) << offset.transpose();
  EXPECT_NEAR(inForce().twist[1], 0.05, 1e-12);
  cycles(200);  // past 0.2 s: 1 cm, at rest
  offset = Eigen::Map<const Eigen::Vector3d>(inForce().position) - home_position;
  EXPECT_LT((offset - Eigen::Vector3d(0.0, 0.01, 0.0)).norm(), 1e-9) << offset.transpose();
  EXPECT_EQ(Eigen::Map<const Vector6d>(inForce().twist), Vector6d::Zero());
  EXPECT_EQ(wrapper.submit(moving()).reason, RejectionReason::kReflexLatched);
  // The reset resumes where the arm is (here: home, the arm never moved), not the retreat's end.
  ASSERT_NE(wrapper.reset(), 0U);
  cycles(1);
  expectHeldAtHome();
}

class FaultingReflex : public Reflex {
 protected:
  FaultingReflex() : Reflex("fault") {}
};

TEST_F(FaultingReflex, FaultsNamingTheWrenchAndTheThresholds) {
  feel(push(0.0, 30.0, 0.0));
  for (int cycle = 1; cycle < 6; ++cycle) {
    ASSERT_EQ(wrapper.update(state, kPeriod, torque.span()), CycleStatus::kOk) << cycle;
  }
  EXPECT_EQ(wrapper.update(state, kPeriod, torque.span()), CycleStatus::kFault);
  const std::string fault = wrapper.diagnostics().last_fault;
  EXPECT_NE(fault.find("reflex: contact force (0, 30, 0) N in the task frame is 1.5 times its "
                       "thresholds (20, 20, 20) N"),
            std::string::npos)
      << fault;
  EXPECT_EQ(wrapper.diagnostics().reflex_trips, 1U);
  EXPECT_FALSE(wrapper.diagnostics().reflex_latched);  // FAULT's own rules: commands are taken
  EXPECT_TRUE(wrapper.submit(moving()).accepted);
  // A reset leaves FAULT holding the measured pose, the reflex armed again.
  feel(Vector6d::Zero());
  ASSERT_NE(wrapper.reset(), 0U);
  cycles(1);
  EXPECT_EQ(wrapper.diagnostics().state, WrapperState::kActive);
  EXPECT_FALSE(wrapper.controller().reflex().tripped());
  expectHeldAtHome();
}

TEST(WrapperReflex, WithoutAnyContactWrenchTheCycleFaultsAfterATenthOfASecond) {
  CartesianWrapper wrapper(fr3Config(kCartesianImpedancePlugin, reflexLines("hold")));
  JointState state = restingAt(wrapper.controller(), fr3Home());  // no wrist reading
  wrapper.activate(state);
  TorqueBuffer torque;
  int cycles = 0;
  while (wrapper.update(state, kPeriod, torque.span()) == CycleStatus::kOk && cycles < 1000) {
    ++cycles;
  }
  EXPECT_EQ(cycles, 99);  // the hundredth cycle without one faults
  EXPECT_NE(wrapper.diagnostics().last_fault.find("reflex: no contact wrench"), std::string::npos)
      << wrapper.diagnostics().last_fault;
}

TEST(WrapperReflex, AJointLawHoldsTheMeasuredJointsAndCannotRetreat) {
  JointWrapper wrapper(fr3Config(kJointImpedancePlugin, reflexLines("hold")));
  JointState state = restingAt(wrapper.controller(), fr3Home());
  state.wrench_valid = true;
  state.wrench = Vector6d::Zero();
  wrapper.activate(state);
  JointCommand command = JointCommand::zero(kFr3Dof);
  command.stamp_s = 1.0;
  command.fields = CommandField::kPosition | CommandField::kReflex;
  command.position = fr3Home() + JointVector::Constant(kFr3Dof, 0.1);
  command.reflex_force = Eigen::Vector3d(30.0, 0.0, 0.0);  // base x raised
  ASSERT_TRUE(wrapper.submit(command).accepted);
  TorqueBuffer torque;
  state.wrench = push(25.0, 0.0, 0.0);
  for (int cycle = 0; cycle < 100; ++cycle) {
    ASSERT_EQ(wrapper.update(state, kPeriod, torque.span()), CycleStatus::kOk);
  }
  EXPECT_FALSE(wrapper.controller().reflex().tripped());
  state.wrench = push(0.0, 25.0, 0.0);
  for (int cycle = 0; cycle < 6; ++cycle) {
    ASSERT_EQ(wrapper.update(state, kPeriod, torque.span()), CycleStatus::kOk);
  }
  EXPECT_TRUE(wrapper.controller().reflex().latched());
  const auto& held = std::get<comply_joint_command>(wrapper.controller().commandInForce());
  EXPECT_EQ(Eigen::Map<const JointVector>(held.position, kFr3Dof), fr3Home());

  try {
    (void)resolveController(fr3Config(kJointImpedancePlugin, reflexLines("retreat")));
    ADD_FAILURE() << "a joint law cannot retreat";
  } catch (const std::runtime_error& error) {
    EXPECT_NE(std::string(error.what()).find("reflex.reaction"), std::string::npos) << error.what();
    EXPECT_NE(std::string(error.what()).find("retreat needs a Cartesian law"), std::string::npos)
        << error.what();
  }
}

TEST(WrapperReflex, OffItNeverTrips) {
  CartesianWrapper wrapper(fr3Config(kCartesianImpedancePlugin, "frozen_state_timeout_s: 0\n"));
  JointState state = restingAt(wrapper.controller(), fr3Home());
  state.wrench_valid = true;
  state.wrench = push(0.0, 100.0, 0.0);
  wrapper.activate(state);
  TorqueBuffer torque;
  for (int cycle = 0; cycle < 100; ++cycle) {
    ASSERT_EQ(wrapper.update(state, kPeriod, torque.span()), CycleStatus::kOk);
  }
  EXPECT_FALSE(wrapper.controller().reflex().tripped());
  EXPECT_EQ(wrapper.diagnostics().reflex_trips, 0U);
}

}  // namespace
}  // namespace comply::pipeline::test
