// The energy tank pays for a move of the nullspace target (issue 46, finding 7): on the FR3 held
// at home, a target 0.4 rad away on joint 1 with a nullspace stiffness of 10 N m/rad would put
// 1/2 10 0.4^2 = 0.8 J into the spring, more than the nullspace account's 0.5 J (floor 0.01 J).
// The law's target goes only as far as the account pays, sqrt(2 0.49 / 10) = 0.313 rad, and stays
// there; a move back toward the arm gives back what was paid; with the tank off the target passes
// at once.

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "comply/pipeline/wrapper.hpp"
#include "wrapper_support.hpp"

namespace comply::pipeline::test {
namespace {

constexpr double kStiffness = 10.0;  // N m/rad, nullspace, every joint

const comply_cartesian_command& lawCommand(const CartesianWrapper& wrapper) {
  return std::get<comply_cartesian_command>(wrapper.controller().lawBus());
}

/// The nullspace group: the target `offset_rad` from home on joint 1.
CartesianCommand nullspaceTarget(double offset_rad, double stamp_s) {
  CartesianCommand command = CartesianCommand::zero(kFr3Dof);
  command.stamp_s = stamp_s;
  command.fields = CommandField::kNullspace;
  command.nullspace_position = offset(fr3Home(), 0, offset_rad);
  command.nullspace_stiffness.setConstant(kFr3Dof, kStiffness);
  command.nullspace_damping.setConstant(kFr3Dof, 1.0);
  return command;
}

/// The arm held at home (its joints do not move; they carry the torque), `cycles` cycles.
void hold(CartesianWrapper& wrapper, JointState& state, int cycles) {
  TorqueBuffer torque;
  for (int cycle = 0; cycle < cycles; ++cycle) {
    ASSERT_EQ(wrapper.update(state, kPeriod, torque.span()), CycleStatus::kOk)
        << wrapper.diagnostics().last_fault;
    state.effort = torque.values;
  }
}

std::string tankLines(bool enabled) {
  // Ramps so fast that the stiffness arrives in one cycle (at a target on the arm it injects
  // nothing); the tank needs the ramps on.
  return std::string(
             "gain_ramps:\n  enabled: true\n  joint_stiffness_per_s: 1.0e12\n"
             "  joint_damping_per_s: 1.0e12\npassivity:\n  enabled: ") +
         (enabled ? "true" : "false") +
         "\n  nullspace_tank_initial_j: 0.5\n  nullspace_tank_max_j: 1.0\n  tank_min_j: 0.01\n";
}

TEST(NullspaceTank, AMoveOfTheTargetGoesOnlyAsFarAsTheTankPays) {
  CartesianWrapper wrapper(fr3Config(kCartesianImpedancePlugin, tankLines(true)));
  JointState state = restingAt(wrapper.controller(), fr3Home());
  wrapper.activate(state);
  hold(wrapper, state, 10);
  ASSERT_TRUE(wrapper.submit(nullspaceTarget(0.4, 1.0)).accepted);
  hold(wrapper, state, 200);
  const double reached = lawCommand(wrapper).nullspace_position[0] - fr3Home()[0];
  const double payable = std::sqrt(2.0 * 0.49 / kStiffness);  // 0.313 rad
  EXPECT_LE(reached, payable + 1e-9);
  EXPECT_GT(reached, 0.95 * payable) << "the target moves as far as the tank pays";
  // The stiffness arrived (it injects nothing at a target on the arm), the other joints' targets
  // are home's.
  EXPECT_EQ(lawCommand(wrapper).nullspace_stiffness[0], kStiffness);
  for (int joint = 1; joint < kFr3Dof; ++joint) {
    EXPECT_EQ(lawCommand(wrapper).nullspace_position[joint], fr3Home()[joint]) << joint;
  }
  const PassivitySnapshot tank = wrapper.diagnostics().passivity;
  EXPECT_NEAR(tank.nullspace_tank_energy_j, 0.5 - 0.5 * kStiffness * reached * reached, 1e-9);
  EXPECT_GT(tank.refused_j, 0.0) << "the rest is refused every cycle";
  // Back onto the arm: arrives, and what the spring held comes back to the account.
  ASSERT_TRUE(wrapper.submit(nullspaceTarget(0.0, 2.0)).accepted);
  hold(wrapper, state, 2);
  EXPECT_EQ(lawCommand(wrapper).nullspace_position[0], fr3Home()[0]);
  EXPECT_NEAR(wrapper.diagnostics().passivity.nullspace_tank_energy_j, 0.5, 1e-9);
}

TEST(NullspaceTank, WithTheTankOffTheTargetPassesAtOnce) {
  CartesianWrapper wrapper(fr3Config(kCartesianImpedancePlugin, tankLines(false)));
  JointState state = restingAt(wrapper.controller(), fr3Home());
  wrapper.activate(state);
  hold(wrapper, state, 10);
  ASSERT_TRUE(wrapper.submit(nullspaceTarget(0.4, 1.0)).accepted);
  hold(wrapper, state, 1);
  const auto& active = std::get<comply_cartesian_command>(wrapper.controller().activeCommand());
  EXPECT_EQ(active.nullspace_position[0], fr3Home()[0] + 0.4);
  EXPECT_EQ(lawCommand(wrapper).nullspace_position[0], fr3Home()[0] + 0.4);
}

}  // namespace
}  // namespace comply::pipeline::test
