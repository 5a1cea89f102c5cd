// The chunk player on its own: the curve against closed forms (a cubic through given velocities, a
// constant-rate rotation), implied velocities, the blend from the reference in force (no jump in
// position or velocity; a chunk that continues the curve in force plays its own curve exactly),
// gains at their times and positive semi-definite between.

#include "comply/pipeline/chunk_player.hpp"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <random>

#include "comply/core/rotation.hpp"
#include "comply/schema/schema.hpp"

namespace comply::pipeline {
namespace {

constexpr int kDof = 7;
using Cartesian = comply_cartesian_command;
using Joint = comply_joint_command;

Eigen::Vector3d positionOf(const CommandBus& bus) {
  return Eigen::Map<const Eigen::Vector3d>(std::get<Cartesian>(bus).position);
}
Eigen::Vector3d linearOf(const double* six) {
  return Eigen::Map<const Eigen::Vector3d>(six);
}
Eigen::Vector3d angularOf(const double* six) {
  return Eigen::Map<const Eigen::Vector3d>(six + 3);
}
Eigen::Quaterniond orientationOf(const CommandBus& bus) {
  const double* q = std::get<Cartesian>(bus).orientation;
  return {q[3], q[0], q[1], q[2]};
}

CommandBus cartesianBus() {
  CartesianCommand command = CartesianCommand::zero(kDof);
  command.position = Eigen::Vector3d(0.4, 0.0, 0.5);
  return schema::toBus(command, kDof);
}

/// A cubic per axis: p(t) = c0 + c1 t + c2 t^2 + c3 t^3.
struct Cubic {
  Eigen::Vector3d c0{0.3, -0.1, 0.5}, c1{0.2, 0.1, -0.3}, c2{-0.4, 0.6, 0.2}, c3{0.5, -0.7, 0.3};
  [[nodiscard]] Eigen::Vector3d at(double t) const { return c0 + t * (c1 + t * (c2 + t * c3)); }
  [[nodiscard]] Eigen::Vector3d rate(double t) const { return c1 + t * (2 * c2 + 3 * t * c3); }
  [[nodiscard]] Eigen::Vector3d curvature(double t) const { return 2 * c2 + 6 * t * c3; }
};

TEST(ChunkPlayer, ReproducesACubicThroughGivenVelocitiesAndARotationAtConstantRate) {
  const Cubic cubic;
  const Eigen::Vector3d omega(0.4, -0.3, 0.9);  // rad/s, base frame
  const Eigen::Quaterniond q0(Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 2, 3).normalized()));
  const auto rotationAt = [&](double t) {
    return Eigen::Quaterniond(Eigen::AngleAxisd(omega.norm() * t, omega.normalized())) * q0;
  };
  CartesianChunk chunk;
  chunk.fields = CommandField::kPosition | CommandField::kVelocity;
  const double times[] = {0.0, 0.07, 0.15, 0.2, 0.33, 0.5};  // uneven on purpose
  for (double t : times) {
    ChunkWaypoint<CartesianCommand> waypoint{t, CartesianCommand::zero(kDof)};
    waypoint.command.position = cubic.at(t);
    waypoint.command.orientation = rotationAt(t);
    waypoint.command.twist << cubic.rate(t), omega;
    chunk.waypoints.push_back(waypoint);
  }
  ChunkPlayer player(COMPLY_COMMAND_CARTESIAN, kDof, 0.0);
  const double offset_s = 10.0;  // controller time = chunk time + 10 s
  const int slot = player.load(chunk, offset_s);
  ASSERT_GE(slot, 0);
  CommandBus active = cartesianBus();
  player.take(slot, active, offset_s);
  for (double t = 0.0; t < 0.5; t += 0.0037) {
    ASSERT_TRUE(player.play(offset_s + t, active));
    const Cartesian& bus = std::get<Cartesian>(active);
    EXPECT_LT((positionOf(active) - cubic.at(t)).norm(), 1e-12) << t;
    EXPECT_LT((linearOf(bus.twist) - cubic.rate(t)).norm(), 1e-11) << t;
    EXPECT_LT((linearOf(bus.acceleration) - cubic.curvature(t)).norm(), 1e-9) << t;
    EXPECT_LT(orientationOf(active).angularDistance(rotationAt(t)), 1e-12) << t;
    EXPECT_LT((angularOf(bus.twist) - omega).norm(), 1e-12) << t;
    EXPECT_LT(angularOf(bus.acceleration).norm(), 1e-10) << t;
  }
  // Past the last waypoint it holds it, at rest, and the chunk has ended.
  EXPECT_FALSE(player.play(offset_s + 0.6, active));
  EXPECT_FALSE(player.playing());
  EXPECT_LT((positionOf(active) - cubic.at(0.5)).norm(), 1e-12);
  EXPECT_EQ(linearOf(std::get<Cartesian>(active).twist).norm(), 0.0);
}

TEST(ChunkPlayer, ImpliesVelocitiesFromNeighboursComesInFromRestAndEndsAtRest) {
  // Evenly timed points on a line at 0.2 m/s: the velocity is the line's from the first waypoint
  // to the one before the last, zero at the last.
  JointChunk chunk;
  for (int k = 0; k < 5; ++k) {
    ChunkWaypoint<JointCommand> waypoint{0.1 * k, JointCommand::zero(kDof)};
    waypoint.command.position.setConstant(0.02 * k);
    chunk.waypoints.push_back(waypoint);
  }
  ChunkPlayer player(COMPLY_COMMAND_JOINT, kDof, 0.0);
  const int slot = player.load(chunk, 0.0);
  CommandBus active = schema::toBus(JointCommand::zero(kDof), kDof);
  player.take(slot, active, -1.0);
  const auto velocityAt = [&](double t) {
    player.play(t, active);
    return std::get<Joint>(active).velocity[3];
  };
  const auto positionNow = [&] { return std::get<Joint>(active).position[3]; };
  // The lead-in: at rest 1 cm behind until one segment (0.1 s) before, then evenly faster.
  EXPECT_NEAR(velocityAt(-0.5), 0.0, 1e-12);
  EXPECT_NEAR(positionNow(), -0.01, 1e-12);
  EXPECT_NEAR(velocityAt(-0.05), 0.1, 1e-12);
  EXPECT_NEAR(std::get<Joint>(active).acceleration[3], 2.0, 1e-9);
  EXPECT_NEAR(velocityAt(0.0), 0.2, 1e-12);
  EXPECT_NEAR(positionNow(), 0.0, 1e-12);
  EXPECT_NEAR(velocityAt(0.1), 0.2, 1e-12);
  EXPECT_NEAR(velocityAt(0.25), 0.2, 1e-12);  // between two interior waypoints: the line itself
  EXPECT_NEAR(positionNow(), 0.05, 1e-12);
  EXPECT_NEAR(std::get<Joint>(active).acceleration[3], 0.0, 1e-9);
  EXPECT_NEAR(velocityAt(0.4), 0.0, 1e-12);
}

TEST(ChunkPlayer, BlendsInFromTheReferenceInForceWithoutAJumpInPositionOrVelocity) {
  const Cubic cubic;
  CartesianChunk chunk;
  chunk.fields = CommandField::kPosition | CommandField::kVelocity;
  for (double t : {0.0, 0.1, 0.2, 0.3, 0.4}) {
    ChunkWaypoint<CartesianCommand> waypoint{t, CartesianCommand::zero(kDof)};
    waypoint.command.position = cubic.at(t);
    waypoint.command.twist << cubic.rate(t), Eigen::Vector3d(0.0, 0.0, 0.5);
    waypoint.command.orientation =
        Eigen::Quaterniond(Eigen::AngleAxisd(0.5 * t, Eigen::Vector3d::UnitZ()));
    chunk.waypoints.push_back(waypoint);
  }
  // The reference in force: elsewhere, moving, accelerating, turned.
  CommandBus from = cartesianBus();
  Cartesian& old = std::get<Cartesian>(from);
  Eigen::Map<Eigen::Vector3d>(old.position) = cubic.at(0.05) + Eigen::Vector3d(0.01, -0.02, 0.005);
  Eigen::Map<Vector6d>(old.twist) << 0.1, 0.05, -0.2, 0.1, 0.0, -0.2;
  Eigen::Map<Vector6d>(old.acceleration) << 1.0, -0.5, 0.3, 0.0, 0.4, 0.0;
  const Eigen::Quaterniond old_orientation(Eigen::AngleAxisd(0.05, Eigen::Vector3d::UnitX()));
  old.orientation[0] = old_orientation.x();
  old.orientation[1] = old_orientation.y();
  old.orientation[2] = old_orientation.z();
  old.orientation[3] = old_orientation.w();

  const double blend_s = 0.1;
  const double start_s = 0.05;
  ChunkPlayer player(COMPLY_COMMAND_CARTESIAN, kDof, blend_s);
  const int slot = player.load(chunk, 0.0);
  CommandBus active = from;
  player.take(slot, from, start_s);
  player.play(start_s, active);
  const Cartesian& now = std::get<Cartesian>(active);
  EXPECT_LT((positionOf(active) - positionOf(from)).norm(), 1e-12);
  EXPECT_LT((Eigen::Map<const Vector6d>(now.twist) - Eigen::Map<const Vector6d>(old.twist)).norm(),
            1e-12);
  // The acceleration steps, as at a waypoint: the blend adds none where it starts, so the
  // reference's is the chunk's own (the cubic's and, about z, the constant rate's zero).
  EXPECT_LT((linearOf(now.acceleration) - cubic.curvature(start_s)).norm(), 1e-9);
  EXPECT_LT(angularOf(now.acceleration).norm(), 1e-9);
  EXPECT_LT(orientationOf(active).angularDistance(old_orientation), 1e-12);

  // Along the blend the reference is smooth: the finite difference of the position matches the
  // velocity it reports, and the velocity moves by no more than its acceleration allows.
  const double dt = 1e-4;
  Eigen::Vector3d last_position = positionOf(active);
  Eigen::Vector3d last_velocity = linearOf(now.twist);
  for (double t = start_s + dt; t < 0.3; t += dt) {
    player.play(t, active);
    const Eigen::Vector3d velocity = linearOf(now.twist);
    const Eigen::Vector3d mean = 0.5 * (velocity + last_velocity);
    EXPECT_LT(((positionOf(active) - last_position) / dt - mean).norm(), 1e-4) << t;
    EXPECT_LT((velocity - last_velocity).norm(), 50.0 * dt) << t;
    last_position = positionOf(active);
    last_velocity = velocity;
  }
  // After the blend: the chunk itself.
  player.play(0.25, active);
  EXPECT_LT((positionOf(active) - cubic.at(0.25)).norm(), 1e-12);
  EXPECT_LT((linearOf(now.twist) - cubic.rate(0.25)).norm(), 1e-11);
}

TEST(ChunkPlayer, AChunkThatContinuesTheCurveInForcePlaysItsOwnCurveFromItsFirstCycle) {
  // The reference in force is on the cubic at 0.05 s, in position and velocity, but accelerates
  // differently (as the chunk before would at its waypoint): the blend has nothing to take away,
  // so the reference is the chunk's curve from the cycle it starts in, never rougher than it.
  const Cubic cubic;
  CartesianChunk chunk;
  chunk.fields = CommandField::kPosition | CommandField::kVelocity;
  for (double t : {0.0, 0.1, 0.2, 0.3}) {
    ChunkWaypoint<CartesianCommand> waypoint{t, CartesianCommand::zero(kDof)};
    waypoint.command.position = cubic.at(t);
    waypoint.command.twist << cubic.rate(t), Eigen::Vector3d::Zero();
    chunk.waypoints.push_back(waypoint);
  }
  const double start_s = 0.05;
  CommandBus from = cartesianBus();
  Cartesian& old = std::get<Cartesian>(from);
  Eigen::Map<Eigen::Vector3d>(old.position) = cubic.at(start_s);
  Eigen::Map<Vector6d>(old.twist) << cubic.rate(start_s), Eigen::Vector3d::Zero();
  Eigen::Map<Vector6d>(old.acceleration) << -3.0, 2.0, 1.0, 0.0, 0.0, 0.0;
  ChunkPlayer player(COMPLY_COMMAND_CARTESIAN, kDof, 0.1);
  const int slot = player.load(chunk, 0.0);
  CommandBus active = from;
  player.take(slot, from, start_s);
  const Cartesian& now = std::get<Cartesian>(active);
  for (double t = start_s; t < 0.2; t += 1e-3) {
    player.play(t, active);
    EXPECT_LT((positionOf(active) - cubic.at(t)).norm(), 1e-12) << t;
    EXPECT_LT((linearOf(now.twist) - cubic.rate(t)).norm(), 1e-11) << t;
    EXPECT_LT((linearOf(now.acceleration) - cubic.curvature(t)).norm(), 1e-9) << t;
  }
}

TEST(ChunkPlayer, AChunkWaitingForItsTakeoverWaypointTakesTheVelocityItJoinsThere) {
  // Joint points on a line at 0.2 rad/s taking over at waypoint 2 (0.2 s) from a reference moving
  // at -0.1 rad/s there: that waypoint's velocity is the reference's, the others stay implied;
  // the waypoint is where the chunk starts (the cycle after plays it from there), and a chunk
  // that gives its own velocities keeps them.
  JointChunk chunk;
  for (int k = 0; k < 5; ++k) {
    ChunkWaypoint<JointCommand> waypoint{0.1 * k, JointCommand::zero(kDof)};
    waypoint.command.position.setConstant(0.02 * k);
    chunk.waypoints.push_back(waypoint);
  }
  chunk.takeover_s = 0.2;
  JointCommand joined = JointCommand::zero(kDof);
  joined.position.setConstant(0.04);
  joined.velocity.setConstant(-0.1);
  const CommandBus joins = schema::toBus(joined, kDof);
  ChunkPlayer player(COMPLY_COMMAND_JOINT, kDof, 0.1);
  CommandBus active = joins;
  ASSERT_FALSE(player.take(player.load(chunk, 0.0, 7, 0.0, &joins), active, 0.1995));
  ASSERT_EQ(player.takeOverDue(0.2005, active), 7u);
  ASSERT_EQ(player.events().size(), 1u);
  EXPECT_EQ(player.events()[0].takeover_s, 0.2) << "at its waypoint, between the two cycles";
  EXPECT_EQ(player.events()[0].waypoints_past, 2);
  EXPECT_LT(player.events()[0].velocity_jump, 1e-12);
  player.play(0.2005, active);
  // On the Hermite segment from (0.04, -0.1 rad/s) at 0.2 s to (0.06, 0.2 rad/s) at 0.3 s.
  const double s = 0.005;
  const double h = 0.1;
  const double expected = (6 * s * s - 6 * s) * 0.04 + (3 * s * s - 4 * s + 1) * h * -0.1 +
                          (-6 * s * s + 6 * s) * 0.06 + (3 * s * s - 2 * s) * h * 0.2;
  EXPECT_NEAR(std::get<Joint>(active).velocity[3], expected / h, 1e-12);

  chunk.fields = CommandField::kPosition | CommandField::kVelocity;
  for (auto& waypoint : chunk.waypoints) {
    waypoint.command.velocity.setConstant(0.2);
  }
  ChunkPlayer given(COMPLY_COMMAND_JOINT, kDof, 0.1);
  active = joins;
  ASSERT_FALSE(given.take(given.load(chunk, 0.0, 8, 0.0, &joins), active, 0.1995));
  ASSERT_EQ(given.takeOverDue(0.2005, active), 8u);
  EXPECT_NEAR(given.events()[0].velocity_jump, 0.3, 1e-12) << "its own velocity stands";
}

/// A random symmetric positive semi-definite 3x3 block, rank deficient one time in three.
Eigen::Matrix3d randomPsd(std::mt19937& random, double scale) {
  std::uniform_real_distribution<double> entry(-1.0, 1.0);
  Eigen::Matrix3d a;
  for (int i = 0; i < 9; ++i) {
    a(i) = entry(random);
  }
  if (random() % 3 == 0) {
    a.col(2).setZero();
  }
  return scale * a * a.transpose();
}

TEST(ChunkPlayer, GainsReachTheirValuesAtTheirTimesAndStayPositiveSemiDefiniteBetween) {
  std::mt19937 random(7);
  for (int trial = 0; trial < 200; ++trial) {
    CartesianChunk chunk;
    chunk.fields = CommandField::kPosition | CommandField::kStiffness | CommandField::kDamping |
                   CommandField::kTaskFrame;
    for (int k = 0; k < 3; ++k) {
      ChunkWaypoint<CartesianCommand> waypoint{0.1 * k, CartesianCommand::zero(kDof)};
      waypoint.command.position = Eigen::Vector3d(0.4, 0.0, 0.5);
      waypoint.command.stiffness_translational = randomPsd(random, 2000.0);
      waypoint.command.stiffness_rotational = randomPsd(random, 50.0);
      waypoint.command.damping_translational = randomPsd(random, 80.0);
      waypoint.command.damping_rotational = randomPsd(random, 5.0);
      waypoint.command.task_frame = Eigen::Quaterniond::UnitRandom();
      chunk.waypoints.push_back(waypoint);
    }
    ChunkPlayer player(COMPLY_COMMAND_CARTESIAN, kDof, 0.0);
    const int slot = player.load(chunk, 0.0);
    CommandBus active = cartesianBus();
    player.take(slot, active, 0.0);
    for (int step = 0; step <= 20; ++step) {
      const double t = 0.01 * step;
      player.play(t, active);
      const Cartesian& bus = std::get<Cartesian>(active);
      for (const double* block : {bus.stiffness_translational, bus.stiffness_rotational,
                                  bus.damping_translational, bus.damping_rotational}) {
        const Eigen::Matrix3d m =
            Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(block);
        EXPECT_LT((m - m.transpose()).norm(), 1e-12 * (1.0 + m.norm()));
        EXPECT_GE(Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(m).eigenvalues().minCoeff(),
                  -1e-9 * (1.0 + m.norm()));
      }
      if (step % 10 == 0) {  // at a waypoint's time: its gains exactly
        const CartesianCommand& waypoint = chunk.waypoints[step / 10].command;
        const Eigen::Matrix3d k = Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(
            bus.stiffness_translational);
        EXPECT_LT((k - waypoint.stiffness_translational).norm(), 1e-9);
        const double* q = bus.task_frame;
        EXPECT_LT(Eigen::Quaterniond(q[3], q[0], q[1], q[2]).angularDistance(waypoint.task_frame),
                  1e-9);
      }
    }
  }
}

TEST(ChunkPlayer, SlotsRunOutWhenTheSenderOutpacesTheCycleAndAreFreedWhenTheCycleIsDone) {
  JointChunk chunk;
  chunk.waypoints.push_back({1.0, JointCommand::zero(kDof)});
  ChunkPlayer player(COMPLY_COMMAND_JOINT, kDof, 0.0);
  int slots[ChunkPlayer::kSlots];
  for (int& slot : slots) {
    slot = player.load(chunk, 0.0);
    ASSERT_GE(slot, 0);
  }
  EXPECT_EQ(player.load(chunk, 0.0), -1);
  CommandBus active = schema::toBus(JointCommand::zero(kDof), kDof);
  player.take(slots[0], active, 0.0);
  player.take(slots[1], active, 0.0);  // the first is done: its slot is free again
  EXPECT_EQ(player.load(chunk, 0.0), slots[0]);
  EXPECT_EQ(player.load(CartesianChunk{}, 0.0), -1) << "a joint player takes no Cartesian chunk";
}

}  // namespace
}  // namespace comply::pipeline
