// The simulated hardware on its own: determinism, effort clamping, refusal of bad torques, the
// tool contact wrench against stiffness x penetration, and scene-file errors. Then the run's log:
// the energy tank's columns in log.csv only when the tank is on.

#include "comply/sim/simulated_robot.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>

#include "comply/host/sim_session.hpp"
#include "comply/model/robot_description.hpp"
#include "comply/model/update.hpp"
#include "comply/sim/sim_error.hpp"
#include "plant_commands.hpp"
#include "sim_support.hpp"

namespace comply::testing {
namespace {

/// Positions read over 200 cycles of a fixed torque pattern, with measurement noise.
std::vector<double> noisyTrajectory(std::uint64_t seed) {
  sim::PlantOptions options;
  options.seed = seed;
  options.position_noise_rad = 1e-4;
  options.substeps = 2;
  sim::SimulatedRobot robot(model::loadRobotDescription("fr3"), options);
  JointState state = JointState::zero(robot.dof());
  std::vector<double> torque(static_cast<std::size_t>(robot.dof()), 0.0);
  std::vector<double> positions;
  for (int cycle = 0; cycle < 200; ++cycle) {
    robot.read(state);
    for (int j = 0; j < robot.dof(); ++j) {
      torque[j] = 2.0 * std::sin(0.05 * cycle + j);
      positions.push_back(state.position[j]);
    }
    robot.write(torque);
    robot.step();
  }
  return positions;
}

TEST(SimulatedRobot, SameSeedSameTrajectoryBitForBit) {
  const std::vector<double> first = noisyTrajectory(7);
  EXPECT_EQ(first, noisyTrajectory(7));
  EXPECT_NE(first, noisyTrajectory(8));
}

TEST(SimulatedRobot, ClampsToTheUrdfEffortLimitAndRefusesBadTorques) {
  sim::SimulatedRobot robot(model::loadRobotDescription("fr3"), sim::PlantOptions{});
  const int dof = robot.dof();
  ASSERT_EQ(dof, 7);
  std::vector<double> torque(static_cast<std::size_t>(dof), 1e4);
  ASSERT_TRUE(robot.write(torque));
  for (int j = 0; j < dof; ++j) {
    EXPECT_GT(robot.effortLimit()[j], 0.0);
    EXPECT_DOUBLE_EQ(robot.appliedEffort()[j], robot.effortLimit()[j]);
  }
  // FR3 datasheet: 87 N m on joints 1-4, 12 N m on 5-7.
  EXPECT_DOUBLE_EQ(robot.effortLimit()[0], 87.0);
  EXPECT_DOUBLE_EQ(robot.effortLimit()[6], 12.0);

  std::vector<double> bad(torque.size(), 1.0);
  bad[3] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(robot.write(bad));
  EXPECT_FALSE(robot.write(std::vector<double>(3, 0.0)));
  EXPECT_DOUBLE_EQ(robot.appliedEffort()[3], robot.effortLimit()[3]);  // previous torque kept
}

/// How far FR3 joint 4 turns in 0.5 s under its gravity-holding torque plus `extra_nm`, with the
/// plant's Coulomb friction scaled by `friction_scale`.
double jointFourTravel(double friction_scale, double extra_nm) {
  sim::PlantOptions options;
  options.friction_scale = friction_scale;
  sim::SimulatedRobot robot(model::loadRobotDescription("fr3"), options);
  std::vector<double> torque(robot.appliedEffort().begin(), robot.appliedEffort().end());
  constexpr int kJoint = 3;
  torque[kJoint] += extra_nm;
  JointState state = JointState::zero(robot.dof());
  robot.read(state);
  const double start = state.position[kJoint];
  for (int cycle = 0; cycle < 500; ++cycle) {
    robot.write(torque);
    robot.step();
  }
  robot.read(state);
  return std::abs(state.position[kJoint] - start);
}

// Deactivating a controller used to leave its last torque on the simulated motors (the arm fell
// from a 0.59 m TCP height to 0.03 m); hold() is the brake a real driver engages instead.
TEST(SimulatedRobot, HoldIsABrakeUntilTheNextTorque) {
  const model::RobotDescription fr3 = model::loadRobotDescription("fr3");
  const auto settle = [](sim::SimulatedRobot& robot, bool hold) {
    const std::vector<double> zero(7, 0.0);
    for (int cycle = 0; cycle < 500; ++cycle) {
      if (hold) {
        EXPECT_TRUE(robot.hold());
      } else {
        ASSERT_TRUE(robot.write(zero));
      }
      robot.step();
    }
  };
  sim::SimulatedRobot falling(fr3, sim::PlantOptions{});
  const double start_z = falling.tcpPose().translation().z();
  settle(falling, false);
  EXPECT_LT(falling.tcpPose().translation().z(), start_z - 0.05) << "unheld, the arm falls";

  sim::SimulatedRobot held(fr3, sim::PlantOptions{});
  JointState before = JointState::zero(7);
  ASSERT_TRUE(held.read(before));
  settle(held, true);
  JointState after = JointState::zero(7);
  ASSERT_TRUE(held.read(after));
  EXPECT_LT((after.position - before.position).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_EQ(after.velocity.cwiseAbs().maxCoeff(), 0.0);
  EXPECT_GT(after.effort.cwiseAbs().maxCoeff(), 1.0) << "the drives carry gravity while braked";
  EXPECT_NEAR(held.tcpPose().translation().z(), start_z, 1e-9);

  // A torque releases the brake.
  const std::vector<double> zero(7, 0.0);
  for (int cycle = 0; cycle < 200; ++cycle) {
    ASSERT_TRUE(held.write(zero));
    held.step();
  }
  EXPECT_LT(held.tcpPose().translation().z(), start_z - 0.01);
}

TEST(SimulatedRobot, FrictionScaleMultipliesTheCoulombFrictionOnly) {
  const model::RobotDescription fr3 = model::loadRobotDescription("fr3");
  ASSERT_TRUE(fr3.joint_dynamics.has_value());
  sim::PlantOptions options;
  options.friction_scale = 0.5;
  const sim::SimulatedRobot robot(fr3, options);
  const mjModel& mujoco = robot.mujocoModel();
  for (int j = 0; j < robot.dof(); ++j) {
    const int dof_address =
        mujoco.jnt_dofadr[mj_name2id(&mujoco, mjOBJ_JOINT, fr3.joints[j].c_str())];
    EXPECT_DOUBLE_EQ(mujoco.dof_frictionloss[dof_address],
                     0.5 * fr3.joint_dynamics->frictionloss[j]);
    EXPECT_DOUBLE_EQ(mujoco.dof_damping[dof_address], fr3.joint_dynamics->damping[j]);
    EXPECT_DOUBLE_EQ(mujoco.dof_armature[dof_address], fr3.joint_dynamics->armature[j]);
  }
  // 0.15 N m on joint 4 is below its 1.137 N m of Coulomb friction. MuJoCo's friction loss is a
  // soft constraint, so the joint creeps rather than sticks; without it the joint turns freely.
  const double with_friction = jointFourTravel(1.0, 0.15);
  const double without_friction = jointFourTravel(0.0, 0.15);
  EXPECT_GT(without_friction, 0.01);
  EXPECT_LT(with_friction, 0.1 * without_friction);

  for (const double bad : {-1.0, std::numeric_limits<double>::quiet_NaN()}) {
    options.friction_scale = bad;
    EXPECT_THROW(sim::SimulatedRobot(fr3, options), sim::SimError);
  }
}

// The joint-torque sensors (link_side_torque): what reaches the link, the drive's torque less the
// joint's friction, damping and rotor inertia. Checked against comply's own dynamics of the links
// alone (M(q) ddq + C(q, dq) dq + g(q), no armature) at MuJoCo's acceleration of each step, while
// the arm moves under a torque pattern with its friction on; at rest, a torque below the static
// friction reaches the drive's reading but not the link's.
TEST(SimulatedRobot, TheLinkSideTorqueSensorsReadWhatReachesTheLinks) {
  const model::RobotDescription fr3 = model::loadRobotDescription("fr3");
  const model::Model chain = fr3.loadModel();
  model::Data data(chain);
  sim::PlantOptions options;
  options.link_side_torque = true;
  sim::SimulatedRobot robot(fr3, options);
  const int dof = robot.dof();
  const std::vector<double> gravity(robot.appliedEffort().begin(), robot.appliedEffort().end());
  JointState before = JointState::zero(dof);
  JointState after = JointState::zero(dof);
  std::vector<double> torque(static_cast<std::size_t>(dof), 0.0);
  double largest_error = 0.0;
  double largest_friction = 0.0;
  for (int cycle = 0; cycle < 300; ++cycle) {
    robot.read(before);
    for (int j = 0; j < dof; ++j) {
      torque[j] = gravity[j] + 4.0 * std::sin(0.02 * cycle + j);
    }
    robot.write(torque);
    robot.step();
    robot.read(after);
    const std::span<const double> q(before.position.data(), std::size_t(dof));
    const std::span<const double> dq(before.velocity.data(), std::size_t(dof));
    ASSERT_EQ(model::update(chain, data, q, dq,
                            model::Quantity::kMassMatrix | model::Quantity::kCoriolis |
                                model::Quantity::kGravity),
              model::UpdateStatus::kOk);
    const mjData& mujoco = robot.mujocoData();
    const mjModel& plant = robot.mujocoModel();
    JointVector acceleration(dof);
    for (int j = 0; j < dof; ++j) {
      acceleration[j] =
          mujoco.qacc[plant.jnt_dofadr[mj_name2id(&plant, mjOBJ_JOINT, fr3.joints[j].c_str())]];
    }
    const JointVector links = data.mass_matrix.topLeftCorner(dof, dof) * acceleration +
                              data.coriolis.head(dof) + data.gravity.head(dof);
    for (int j = 0; j < dof; ++j) {
      largest_error = std::max(largest_error, std::abs(after.effort[j] - links[j]));
      largest_friction = std::max(largest_friction, std::abs(torque[j] - after.effort[j]));
    }
  }
  EXPECT_LT(largest_error, 1e-4);  // measured 1.2e-5 N m: two dynamics implementations
  EXPECT_GT(largest_friction, 0.5) << "the drive's torque and the link's must differ";

  // At rest: 0.5 N m on joint 4, below its 1.137 N m of friction, is the drive's and not the
  // link's.
  sim::SimulatedRobot resting(fr3, options);
  std::vector<double> hold(resting.appliedEffort().begin(), resting.appliedEffort().end());
  hold[3] += 0.5;
  JointState state = JointState::zero(dof);
  for (int cycle = 0; cycle < 200; ++cycle) {
    resting.write(hold);
    resting.step();
  }
  resting.read(state);
  EXPECT_NEAR(state.effort[3], hold[3] - 0.5, 0.05);
  EXPECT_DOUBLE_EQ(resting.appliedEffort()[3], hold[3]);
}

TEST(SimulatedRobot, HomePoseMatchesTheControllerModel) {
  const model::RobotDescription description = model::loadRobotDescription("iiwa14");
  sim::SimulatedRobot robot(description, sim::PlantOptions{});
  const model::Model chain = description.loadModel();
  model::Data data(chain);
  const std::vector<double> zero(description.home.size(), 0.0);
  ASSERT_EQ(model::update(chain, data, description.home, zero, model::Quantity::kPose),
            model::UpdateStatus::kOk);
  EXPECT_LT((robot.tcpPose().translation() - data.tip_position).norm(), 1e-9);
  EXPECT_LT(Eigen::Quaterniond(robot.tcpPose().linear()).angularDistance(data.tip_orientation),
            1e-9);
}

TEST(SimulatedRobot, ProbeForceEqualsStiffnessTimesPenetration) {
  host::SimRunOptions run = fr3ExampleRun("press_on_table.yaml");
  const host::SimResult result = host::runSimulation(run);
  ASSERT_EQ(result.summary.faults, 0U);
  // The task's z stiffness is 500 N/m and the reference lies 30 mm past the point of contact.
  // The task frame is the base frame, so base z is the stiffness axis.
  const Vector6d wrench = result.log.contact_wrench.back();
  const double expected_n = 500.0 * 0.03;
  EXPECT_NEAR(wrench[2], expected_n, 0.1 * expected_n);
  EXPECT_LT(std::hypot(wrench[0], wrench[1]), 0.1 * expected_n);
  // Before the approach there is no contact at all.
  EXPECT_EQ(result.log.contact_wrench.front().norm(), 0.0);
  // The tank's account is logged every cycle; this controller does not turn the tank on.
  EXPECT_EQ(result.log.passivity.size(), result.log.size());
  EXPECT_FALSE(result.log.passivityEnabled());
}

// The drives a plant's actuation gives it: a position servo settles on a step of its command, a
// velocity servo moves at its command, a PD drive applies kp (q_d - q) + kd (dq_d - dq) + tau_ff;
// each refuses the other modes (and torque, except the PD drive).
TEST(SimulatedRobot, PositionVelocityAndPdDrivesFollowTheirCommands) {
  const model::RobotDescription ur5e = model::loadRobotDescription("ur5e");
  for (const OutputMode mode : {OutputMode::kPosition, OutputMode::kVelocity}) {
    SCOPED_TRACE(std::string(toString(mode)));
    sim::PlantOptions options;
    options.actuation = mode;
    sim::SimulatedRobot robot(ur5e, options);
    EXPECT_TRUE(robot.accepts(mode));
    EXPECT_FALSE(robot.accepts(OutputMode::kTorque));
    EXPECT_FALSE(robot.accepts(OutputMode::kJointPd));
    ActuatorCommand command = holdWhereItIs(robot, mode);
    const JointVector start = command.position;
    const std::vector<double> torque(static_cast<std::size_t>(robot.dof()), 0.0);
    EXPECT_FALSE(robot.write(torque)) << "servos take no torque";
    command.mode = OutputMode::kJointPd;
    EXPECT_FALSE(robot.writeCommand(command)) << "nor another mode";
    command.mode = mode;
    if (mode == OutputMode::kPosition) {
      command.position[1] += 0.1;  // a step of 0.1 rad on the shoulder
    } else {
      command.velocity[1] = 0.1;  // 0.1 rad/s for 1 s
    }
    JointState state = JointState::zero(robot.dof());
    for (int cycle = 0; cycle < 1000; ++cycle) {
      ASSERT_TRUE(robot.writeCommand(command));
      robot.step();
    }
    robot.read(state);
    EXPECT_NEAR(state.position[1] - start[1], 0.1, 2e-3);
    EXPECT_NEAR(state.position[0], start[0], 1e-3) << "the other joints held";
  }
  sim::PlantOptions options;
  options.actuation = OutputMode::kJointPd;
  sim::SimulatedRobot robot(ur5e, options);
  EXPECT_TRUE(robot.accepts(OutputMode::kJointPd));
  EXPECT_TRUE(robot.accepts(OutputMode::kTorque)) << "a PD drive given a torque alone";
  ActuatorCommand command = holdWhereItIs(robot, OutputMode::kJointPd);
  command.position[2] += 0.05;
  command.stiffness.setConstant(400.0);
  command.damping.setConstant(20.0);
  command.effort.setConstant(1.5);
  ASSERT_TRUE(robot.writeCommand(command));
  robot.step();
  // One substep: the applied effort is the drive's law at the state it started from.
  const std::span<const double> applied = robot.appliedEffort();
  EXPECT_NEAR(applied[2], 400.0 * 0.05 + 1.5, 1e-9);
  EXPECT_NEAR(applied[0], 1.5, 1e-9);
  command.position[0] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(robot.writeCommand(command)) << "a non-finite command is refused";
}

// The wrist sensor reads as a real one: at rest the tool's weight at its centre of mass plus the
// sensor's offset (fixed in the TCP frame), the applied wrench on top of them, and while the tool
// accelerates its inertial force too.
TEST(SimulatedRobot, TheWristSensorReadsWeightOffsetAppliedWrenchAndTheToolsInertia) {
  sim::PlantOptions options;
  options.actuation = OutputMode::kPosition;
  options.scene.tool = kSourceDir / "examples" / "sim" / "payload_3kg.xml";
  options.wrench_sensor_offset << 2.0, -1.0, 3.0, 0.2, -0.1, 0.05;
  sim::SimulatedRobot robot(model::loadRobotDescription("ur5e"), options);
  const ActuatorCommand hold = holdWhereItIs(robot, OutputMode::kPosition);
  const auto settle = [&](const ActuatorCommand& command, int cycles) {
    for (int cycle = 0; cycle < cycles; ++cycle) {
      ASSERT_TRUE(robot.writeCommand(command));
      robot.step();
    }
  };
  // The tool as the file declares it: 3 kg at 5 cm and 10 g at 10 cm along TCP z.
  const Eigen::Isometry3d tcp = robot.tcpPose();
  const double mass = 3.01;
  const Eigen::Vector3d arm = tcp.linear() * Eigen::Vector3d(0.0, 0.0, (0.15 + 0.001) / mass);
  const Eigen::Vector3d weight(0.0, 0.0, -9.81 * mass);
  Vector6d expected;
  expected << weight + tcp.linear() * options.wrench_sensor_offset.head<3>(),
      arm.cross(weight) + tcp.linear() * options.wrench_sensor_offset.tail<3>();
  settle(hold, 1000);
  Vector6d reading;
  ASSERT_TRUE(robot.readWrench(reading));
  EXPECT_LT((reading - expected).head<3>().norm(), 0.05) << reading.transpose();
  EXPECT_LT((reading - expected).tail<3>().norm(), 0.01) << reading.transpose();

  Vector6d applied;
  applied << 5.0, -3.0, 8.0, 0.4, 0.2, -0.3;
  robot.setExternalWrench(applied);
  settle(hold, 2000);
  ASSERT_TRUE(robot.readWrench(reading));
  const Eigen::Isometry3d held = robot.tcpPose();  // the servo yields a little to the push
  const Eigen::Vector3d held_arm = held.linear() * Eigen::Vector3d(0.0, 0.0, (0.15 + 0.001) / mass);
  expected << weight + held.linear() * options.wrench_sensor_offset.head<3>(),
      held_arm.cross(weight) + held.linear() * options.wrench_sensor_offset.tail<3>();
  EXPECT_LT((reading - expected - applied).head<3>().norm(), 0.05) << reading.transpose();
  EXPECT_LT((reading - expected - applied).tail<3>().norm(), 0.01) << reading.transpose();

  // Swing the shoulder: the 3 kg tool accelerates and the reading leaves the static one.
  const Vector6d at_rest = reading;
  ActuatorCommand swing = hold;
  swing.position[0] += 0.3;
  double largest_inertial_n = 0.0;
  for (int cycle = 0; cycle < 200; ++cycle) {
    settle(swing, 1);
    ASSERT_TRUE(robot.readWrench(reading));
    largest_inertial_n = std::max(largest_inertial_n, (reading - at_rest).head<3>().norm());
  }
  EXPECT_GT(largest_inertial_n, 1.0);
}

TEST(SimulatedRobot, ToolFragmentWithoutMujocoincludeRootIsRefused) {
  const std::filesystem::path file =
      std::filesystem::temp_directory_path() / "comply_bad_tool_fragment.xml";
  std::ofstream(file) << "<mujoco><worldbody/></mujoco>\n";
  sim::PlantOptions options;
  options.scene.tool = file;
  try {
    sim::SimulatedRobot robot(model::loadRobotDescription("ur5e"), options);
    FAIL() << "expected SimError";
  } catch (const sim::SimError& error) {
    EXPECT_NE(std::string(error.what()).find("mujocoinclude"), std::string::npos) << error.what();
    EXPECT_NE(std::string(error.what()).find(file.string()), std::string::npos) << error.what();
  }
  std::filesystem::remove(file);
}

TEST(SimulatedRobot, MujocoErrorsInAFragmentAreReported) {
  const std::filesystem::path file =
      std::filesystem::temp_directory_path() / "comply_broken_object.xml";
  std::ofstream(file) << "<mujocoinclude><geom type=\"box\" size=\"0.1 0.1\" bogus=\"1\"/>"
                         "</mujocoinclude>\n";
  sim::PlantOptions options;
  options.scene.objects.push_back(file);
  try {
    sim::SimulatedRobot robot(model::loadRobotDescription("fr3"), options);
    FAIL() << "expected SimError";
  } catch (const sim::SimError& error) {
    EXPECT_NE(std::string(error.what()).find("MuJoCo cannot load"), std::string::npos)
        << error.what();
  }
  std::filesystem::remove(file);
}

/// A one-row Cartesian log of a 2-joint arm, with the tank's account `tank`.
host::SimLog oneRowLog(const pipeline::PassivitySnapshot& tank) {
  host::SimLog log;
  log.dof = 2;
  log.time_s = {0.001};
  log.position = log.velocity = log.torque = {JointVector::Zero(2)};
  log.tcp_position = log.reference_position = {Eigen::Vector3d::Zero()};
  log.tcp_orientation = log.reference_orientation = {Eigen::Quaterniond::Identity()};
  log.contact_wrench = {Vector6d::Zero()};
  log.passivity = {tank};
  return log;
}

std::string csvOf(const host::SimLog& log) {
  std::ostringstream out;
  host::writeLogHeader(log, out);
  host::writeLogRow(log, 0, out);
  return out.str();
}

TEST(SimLog, TankColumnsOnlyWhenTheTankIsOn) {
  const std::string off = csvOf(oneRowLog({}));
  EXPECT_NE(off.find(",contact_tz\n"), std::string::npos) << off;  // log.csv as it always was
  EXPECT_EQ(off.find("tank"), std::string::npos) << off;

  const std::string on = csvOf(oneRowLog({.enabled = true,
                                          .tank_energy_j = 0.75,
                                          .nullspace_tank_energy_j = 0.25,
                                          .injected_j = 1.5,
                                          .dissipated_j = 2.125,
                                          .refused_j = 0.0625,
                                          .gain_fraction = 0.4}));
  EXPECT_NE(on.find(",contact_tz,tank_energy_j,nullspace_tank_energy_j,energy_injected_j,"
                    "energy_dissipated_j,energy_refused_j,gain_fraction\n"),
            std::string::npos)
      << on;
  EXPECT_NE(on.find(",0.75,0.25,1.5,2.125,0.0625,0.4\n"), std::string::npos) << on;
}

// A run on drives that take positions logs their command beside the joints, and in admittance the
// wrist sensor's wrench the virtual arm answered; a torque run's log stays as it was.
TEST(SimLog, PositionDrivesLogTheirCommandAndAdmittanceItsWrench) {
  const auto run = [](OutputMode mode) {
    host::SimRunOptions options = fr3ExampleRun("step_response.yaml");
    options.config.output.mode = mode;
    options.duration_s = 0.05;
    options.snapshots = false;
    return host::runSimulation(options);
  };
  const host::SimResult torque = run(OutputMode::kTorque);
  EXPECT_FALSE(torque.log.commandLogged());
  EXPECT_EQ(csvOf(torque.log).find("qcmd"), std::string::npos);
  const host::SimResult pd = run(OutputMode::kJointPd);
  EXPECT_TRUE(pd.log.commandLogged());
  EXPECT_FALSE(pd.log.sensorLogged());
  const host::SimResult admittance = run(OutputMode::kPosition);
  ASSERT_TRUE(admittance.log.commandLogged() && admittance.log.sensorLogged());
  EXPECT_EQ(admittance.log.position_command.size(), admittance.log.size());
  const std::string csv = csvOf(admittance.log);
  EXPECT_NE(csv.find(",qcmd0,qcmd1,qcmd2,qcmd3,qcmd4,qcmd5,qcmd6,sensor_fx,sensor_fy,sensor_fz,"
                     "sensor_tx,sensor_ty,sensor_tz\n"),
            std::string::npos)
      << csv.substr(0, 600);
  // The command is the virtual arm, near the measured joints.
  const std::size_t last = admittance.log.size() - 1;
  EXPECT_LT(
      (admittance.log.position_command[last] - admittance.log.position[last]).cwiseAbs().maxCoeff(),
      0.05);
}

}  // namespace
}  // namespace comply::testing
