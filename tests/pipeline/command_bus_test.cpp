// Conversion of commands to the plugin buses. The bus layout is the contract with every plugin
// (C, generated code): 3x3 blocks row-major, quaternions x y z w, joint arrays zero past `dof`.
// Asymmetric matrices and non-unit quaternions make a transposed or reordered copy visible.

#include "comply/pipeline/command_bus.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <utility>

namespace comply::pipeline {
namespace {

constexpr int kDof = 3;

/// 1..9 in reading order: bus[k] must equal k + 1 + offset when copied row-major.
Eigen::Matrix3d readingOrder(double offset) {
  Eigen::Matrix3d m;
  m << 1, 2, 3, 4, 5, 6, 7, 8, 9;
  return m.array() + offset;
}

JointVector ramp(int size, double start) {
  JointVector v(size);
  for (int i = 0; i < size; ++i) {
    v[i] = start + i;
  }
  return v;
}

void expectRowMajor(const double* bus, double offset, const char* name) {
  for (int k = 0; k < 9; ++k) {
    EXPECT_EQ(bus[k], k + 1 + offset) << name << "[" << k << "]";
  }
}

void expectJointArray(const double* bus, double start, int dof, const char* name) {
  for (int i = 0; i < COMPLY_MAX_DOF; ++i) {
    EXPECT_EQ(bus[i], i < dof ? start + i : 0.0) << name << "[" << i << "]";
  }
}

CartesianCommand distinctCartesian() {
  CartesianCommand c = CartesianCommand::zero(kDof);
  c.stamp_s = 12.5;
  c.fields = CommandField::kStiffness | CommandField::kNullspace;
  c.position = {0.1, 0.2, 0.3};
  c.orientation = Eigen::Quaterniond(0.4, 0.1, 0.2, 0.3);  // w first in Eigen's constructor
  c.twist << 1, 2, 3, 4, 5, 6;
  c.acceleration << 7, 8, 9, 10, 11, 12;
  c.stiffness_translational = readingOrder(0);
  c.stiffness_rotational = readingOrder(10);
  c.damping_translational = readingOrder(20);
  c.damping_rotational = readingOrder(30);
  c.damping_mode = DampingMode::kRatio;
  c.damping_ratio << 0.5, 0.6, 0.7, 0.8, 0.9, 1.0;
  c.task_frame = Eigen::Quaterniond(-0.8, 0.5, 0.6, 0.7);
  c.wrench_feedforward << -1, -2, -3, -4, -5, -6;
  c.torque_feedforward = ramp(kDof, 100);
  c.nullspace_position = ramp(kDof, 200);
  c.nullspace_stiffness = ramp(kDof, 300);
  c.nullspace_damping = ramp(kDof, 400);
  return c;
}

TEST(CommandBus, CartesianHeaderAndVectors) {
  const comply_cartesian_command bus = toBus(distinctCartesian(), kDof);
  EXPECT_EQ(bus.stamp_s, 12.5);
  EXPECT_EQ(bus.fields,
            static_cast<std::uint32_t>(COMPLY_FIELD_STIFFNESS | COMPLY_FIELD_NULLSPACE));
  EXPECT_EQ(bus.dof, kDof);
  EXPECT_EQ(bus.position[0], 0.1);
  EXPECT_EQ(bus.position[1], 0.2);
  EXPECT_EQ(bus.position[2], 0.3);
  for (int i = 0; i < 6; ++i) {
    EXPECT_EQ(bus.twist[i], 1.0 + i) << i;  // linear first
    EXPECT_EQ(bus.acceleration[i], 7.0 + i) << i;
    EXPECT_EQ(bus.wrench_feedforward[i], -1.0 - i) << i;
    EXPECT_EQ(bus.damping_ratio[i], 0.5 + 0.1 * i) << i;
  }
  EXPECT_EQ(bus.damping_mode, COMPLY_DAMPING_RATIO);
}

TEST(CommandBus, CartesianQuaternionsAreXyzw) {
  // Copied as they are (validation normalises earlier), so the sender's numbers are visible.
  const comply_cartesian_command bus = toBus(distinctCartesian(), kDof);
  EXPECT_EQ(bus.orientation[0], 0.1);
  EXPECT_EQ(bus.orientation[1], 0.2);
  EXPECT_EQ(bus.orientation[2], 0.3);
  EXPECT_EQ(bus.orientation[3], 0.4);
  EXPECT_EQ(bus.task_frame[0], 0.5);
  EXPECT_EQ(bus.task_frame[1], 0.6);
  EXPECT_EQ(bus.task_frame[2], 0.7);
  EXPECT_EQ(bus.task_frame[3], -0.8);
}

TEST(CommandBus, CartesianGainBlocksAreRowMajor) {
  const comply_cartesian_command bus = toBus(distinctCartesian(), kDof);
  expectRowMajor(bus.stiffness_translational, 0, "stiffness_translational");
  expectRowMajor(bus.stiffness_rotational, 10, "stiffness_rotational");
  expectRowMajor(bus.damping_translational, 20, "damping_translational");
  expectRowMajor(bus.damping_rotational, 30, "damping_rotational");
  EXPECT_EQ(bus.stiffness_translational[1], 2.0);  // row 0, column 1; column-major would give 4
}

TEST(CommandBus, CartesianJointArraysAreZeroPastDof) {
  const comply_cartesian_command bus = toBus(distinctCartesian(), kDof);
  expectJointArray(bus.torque_feedforward, 100, kDof, "torque_feedforward");
  expectJointArray(bus.nullspace_position, 200, kDof, "nullspace_position");
  expectJointArray(bus.nullspace_stiffness, 300, kDof, "nullspace_stiffness");
  expectJointArray(bus.nullspace_damping, 400, kDof, "nullspace_damping");
}

TEST(CommandBus, ShortJointVectorsArePaddedWithZeros) {
  // A Cartesian command whose joint-space groups were never set has empty vectors.
  CartesianCommand c;
  c.torque_feedforward = ramp(2, 1);
  const comply_cartesian_command bus = toBus(c, kDof);
  expectJointArray(bus.torque_feedforward, 1, 2, "torque_feedforward");
  expectJointArray(bus.nullspace_position, 0, 0, "nullspace_position");
  EXPECT_EQ(bus.orientation[3], 1.0);  // identity: w = 1 is last
  EXPECT_EQ(bus.task_frame[3], 1.0);
  EXPECT_EQ(bus.damping_mode, COMPLY_DAMPING_ABSOLUTE);
}

TEST(CommandBus, JointCommandCopiesEveryGroup) {
  JointCommand c = JointCommand::zero(kDof);
  c.stamp_s = 3.25;
  c.fields = CommandField::kPosition | CommandField::kTorqueFeedforward;
  c.position = ramp(kDof, 10);
  c.velocity = ramp(kDof, 20);
  c.acceleration = ramp(kDof, 30);
  c.stiffness = ramp(kDof, 40);
  c.damping = ramp(kDof, 50);
  c.torque_feedforward = ramp(kDof, 60);
  const comply_joint_command bus = toBus(c, kDof);
  EXPECT_EQ(bus.stamp_s, 3.25);
  EXPECT_EQ(bus.fields,
            static_cast<std::uint32_t>(COMPLY_FIELD_POSITION | COMPLY_FIELD_TORQUE_FEEDFORWARD));
  EXPECT_EQ(bus.dof, kDof);
  expectJointArray(bus.position, 10, kDof, "position");
  expectJointArray(bus.velocity, 20, kDof, "velocity");
  expectJointArray(bus.acceleration, 30, kDof, "acceleration");
  expectJointArray(bus.stiffness, 40, kDof, "stiffness");
  expectJointArray(bus.damping, 50, kDof, "damping");
  expectJointArray(bus.torque_feedforward, 60, kDof, "torque_feedforward");
}

TEST(CommandBus, FieldMaskBitsMatchTheAbi) {
  const std::pair<CommandField, std::uint32_t> bits[] = {
      {CommandField::kPosition, COMPLY_FIELD_POSITION},
      {CommandField::kVelocity, COMPLY_FIELD_VELOCITY},
      {CommandField::kAcceleration, COMPLY_FIELD_ACCELERATION},
      {CommandField::kStiffness, COMPLY_FIELD_STIFFNESS},
      {CommandField::kDamping, COMPLY_FIELD_DAMPING},
      {CommandField::kTaskFrame, COMPLY_FIELD_TASK_FRAME},
      {CommandField::kWrenchFeedforward, COMPLY_FIELD_WRENCH_FEEDFORWARD},
      {CommandField::kTorqueFeedforward, COMPLY_FIELD_TORQUE_FEEDFORWARD},
      {CommandField::kNullspace, COMPLY_FIELD_NULLSPACE},
      {CommandField::kForce, COMPLY_FIELD_FORCE},
      {CommandField::kReflex, COMPLY_FIELD_REFLEX},
      {CommandField::kWorkspace, COMPLY_FIELD_WORKSPACE}};
  std::uint32_t all = 0;
  for (const auto& [field, abi_bit] : bits) {
    EXPECT_EQ(static_cast<std::uint32_t>(field), abi_bit);
    all |= abi_bit;
  }
  EXPECT_EQ(all, static_cast<std::uint32_t>(CommandField::kAll)) << "a group without its ABI bit";
  EXPECT_EQ(toBus(JointCommand::zero(1), 1).fields, static_cast<std::uint32_t>(CommandField::kAll));
}

}  // namespace
}  // namespace comply::pipeline
