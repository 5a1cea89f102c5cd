// The Franka backend's own logic (franka_arm.hpp) through a scripted session: what reaches the
// state, the robot's stops as FAULT texts, the recovery a reset runs, the collision thresholds,
// the torque control started and ended. No robot, no libfranka.

#include "comply/franka/franka_arm.hpp"

#include <gtest/gtest.h>

#include <deque>
#include <future>
#include <thread>

#include "comply/franka/franka_errors.hpp"
#include "comply/hardware/backend.hpp"

namespace comply::franka {
namespace {

/// A robot as a list of states; records what the arm asks of it.
struct Script {
  std::deque<FrankaSample> states;
  FrankaSample last;
  bool link_lost = false;
  std::vector<std::array<double, 7>> torques;
  int starts = 0;
  int stops = 0;
  int recoveries = 0;
  std::vector<fci::CollisionThresholds> thresholds;
  std::string refuse_thresholds;
  bool controlling = false;
};

class ScriptedSession final : public FrankaSession {
 public:
  explicit ScriptedSession(Script& script) : script_(script) {}
  bool read(FrankaSample& sample, double timeout_s) noexcept override {
    (void)timeout_s;
    if (script_.link_lost) {
      return false;
    }
    if (!script_.states.empty()) {
      script_.last = script_.states.front();
      script_.states.pop_front();
    } else {
      ++script_.last.time_ms;  // the robot goes on as it was
    }
    script_.last.torque_control = script_.last.torque_control && script_.controlling;
    sample = script_.last;
    return true;
  }
  bool writeTorque(std::span<const double, 7> torque) noexcept override {
    std::array<double, 7> sent{};
    std::copy(torque.begin(), torque.end(), sent.begin());
    script_.torques.push_back(sent);
    return script_.controlling;
  }
  [[nodiscard]] const char* failure() const noexcept override {
    return script_.link_lost ? "the test's link is down" : nullptr;
  }
  std::string startTorqueControl(FrankaSample& first) override {
    ++script_.starts;
    script_.controlling = true;
    script_.last.torque_control = true;
    script_.last.robot_mode = fci::RobotMode::kMove;
    ++script_.last.time_ms;  // the robot switched within a state
    first = script_.last;
    return {};
  }
  std::string stopTorqueControl() override {
    ++script_.stops;
    script_.controlling = false;
    script_.last.torque_control = false;
    script_.last.robot_mode = fci::RobotMode::kIdle;
    return {};
  }
  std::string recover() override {
    ++script_.recoveries;
    script_.last.robot_mode = fci::RobotMode::kIdle;
    script_.last.errors.fill(false);
    return {};
  }
  std::string setCollisionThresholds(const fci::CollisionThresholds& thresholds) override {
    if (!script_.refuse_thresholds.empty()) {
      return script_.refuse_thresholds;
    }
    script_.thresholds.push_back(thresholds);
    return {};
  }
  [[nodiscard]] std::string description() const override { return "a scripted robot"; }

 private:
  Script& script_;
};

FrankaSample idleState(std::uint64_t time_ms) {
  FrankaSample sample;
  sample.time_ms = time_ms;
  sample.robot_mode = fci::RobotMode::kIdle;
  sample.command_success_rate = 1.0;
  for (std::size_t j = 0; j < 7; ++j) {
    sample.q[j] = 0.1 * static_cast<double>(j);
    sample.dq[j] = -0.01 * static_cast<double>(j);
    sample.tau_J[j] = 2.0 + static_cast<double>(j);
  }
  sample.O_F_ext_hat_K = {1.0, -2.0, 3.0, 0.1, -0.2, 0.3};
  return sample;
}

FrankaArm makeArm(Script& script, FrankaArmOptions options = {}) {
  if (script.states.empty()) {
    script.states.push_back(idleState(100));
  }
  if (options.collision.torque_collision_nominal[0] == 0.0) {
    options.collision = frankaCollisionThresholds(20.0, 20.0);
  }
  return FrankaArm(std::make_unique<ScriptedSession>(script), options);
}

TEST(FrankaArm, StateWrenchAndSequenceAreTheRobots) {
  Script script;
  FrankaArm arm = makeArm(script);
  JointState state = JointState::zero(7);
  ASSERT_TRUE(arm.read(state));
  EXPECT_DOUBLE_EQ(state.position[3], 0.3);
  EXPECT_DOUBLE_EQ(state.velocity[6], -0.06);
  EXPECT_DOUBLE_EQ(state.effort[0], 2.0);
  Vector6d wrench;
  ASSERT_TRUE(arm.readWrench(wrench));
  // The robot's estimate is what the arm exerts; the wrist-sensor convention is its opposite.
  EXPECT_DOUBLE_EQ(wrench[0], -1.0);
  EXPECT_DOUBLE_EQ(wrench[1], 2.0);
  EXPECT_DOUBLE_EQ(wrench[5], -0.3);
  std::uint64_t sequence = 0;
  ASSERT_TRUE(arm.readSequence(sequence));
  EXPECT_EQ(sequence, 100U);
  EXPECT_TRUE(arm.compensatesGravity());
  EXPECT_EQ(arm.robotStop(), nullptr);
  // The thresholds went to the robot before anything else.
  ASSERT_EQ(script.thresholds.size(), 1U);
  EXPECT_DOUBLE_EQ(script.thresholds[0].torque_collision_nominal[0], 20.0);
  EXPECT_DOUBLE_EQ(script.thresholds[0].torque_contact_nominal[0], 16.0);
  EXPECT_DOUBLE_EQ(script.thresholds[0].force_collision_nominal[2], 20.0);
  EXPECT_DOUBLE_EQ(script.thresholds[0].force_collision_nominal[3], 2.0);  // N m: 20 N x 0.1 m
}

/// One control cycle as the loop runs it: the next sample, then the torque (and a hold).
bool cycle(FrankaArm& arm, const std::array<double, 7>& torque, bool hold = false) {
  if (!arm.awaitSample() || !arm.write(torque)) {
    return false;
  }
  return !hold || arm.hold();
}

TEST(FrankaArm, TorqueControlStartsAfterAWriteAndHoldEndsIt) {
  Script script;
  FrankaArm arm = makeArm(script);
  const std::array<double, 7> torque{1, 2, 3, 4, 5, 6, 7};
  ASSERT_TRUE(arm.write(torque));
  EXPECT_EQ(script.starts, 0);  // the robot holds this cycle
  EXPECT_TRUE(script.torques.empty());
  ASSERT_TRUE(cycle(arm, torque));
  EXPECT_EQ(script.starts, 1);
  ASSERT_TRUE(cycle(arm, torque));
  EXPECT_EQ(script.starts, 1);  // one start for a run of cycles
  ASSERT_EQ(script.torques.size(), 2U);
  EXPECT_DOUBLE_EQ(script.torques[1][6], 7.0);
  EXPECT_TRUE(arm.hold());
  EXPECT_EQ(script.stops, 1);
  ASSERT_TRUE(arm.awaitSample());
  EXPECT_EQ(arm.robotStop(), nullptr);  // ended by comply: not a stop
  EXPECT_EQ(arm.stats().controls, 1U);
  const std::array<double, 6> six{};
  EXPECT_FALSE(arm.write(six));  // a wrong size never reaches the robot
}

TEST(FrankaArm, AHoldEveryCycleKeepsTheRobotHolding) {
  // A FAULT at rest writes its hold torque and asks for the robot's hold in every cycle: the
  // torque control must not start and end each time.
  Script script;
  FrankaArm arm = makeArm(script);
  const std::array<double, 7> torque{};
  for (int i = 0; i < 10; ++i) {
    ASSERT_TRUE(cycle(arm, torque, true));
  }
  EXPECT_EQ(script.starts, 0);
  EXPECT_EQ(script.stops, 0);
  ASSERT_TRUE(cycle(arm, torque));
  ASSERT_TRUE(cycle(arm, torque));
  EXPECT_EQ(script.starts, 1);
}

TEST(FrankaArm, AReflexIsAStopNamingItAndAResetRecovers) {
  Script script;
  FrankaArm arm = makeArm(script);
  const std::array<double, 7> torque{};
  ASSERT_TRUE(arm.write(torque));
  ASSERT_TRUE(cycle(arm, torque));
  FrankaSample reflex = idleState(101);
  reflex.robot_mode = fci::RobotMode::kReflex;
  reflex.errors[6] = true;  // joint_reflex
  reflex.last_motion_errors[6] = true;
  script.states.push_back(reflex);
  script.controlling = false;  // the robot ended the motion
  ASSERT_TRUE(arm.awaitSample());
  ASSERT_NE(arm.robotStop(), nullptr);
  EXPECT_NE(std::string(arm.robotStop()).find("reflex joint_reflex"), std::string::npos)
      << arm.robotStop();
  EXPECT_NE(std::string(arm.robotStop()).find("collision_torque_n_m"), std::string::npos);
  EXPECT_FALSE(arm.write(torque));  // nothing goes out while the robot is stopped
  EXPECT_EQ(script.starts, 1);

  // A reset's recovery, from another thread: carried out at the control thread's next sample.
  auto recovered = std::async(std::launch::async, [&] { return arm.recover(); });
  while (recovered.wait_for(std::chrono::milliseconds(1)) != std::future_status::ready) {
    ASSERT_TRUE(arm.awaitSample());
  }
  EXPECT_EQ(recovered.get(), "");
  EXPECT_EQ(script.recoveries, 1);
  EXPECT_EQ(arm.robotStop(), nullptr);
  ASSERT_TRUE(arm.write(torque));
  ASSERT_TRUE(cycle(arm, torque));
  EXPECT_EQ(script.starts, 2);
  const FrankaArmStats stats = arm.stats();
  EXPECT_EQ(stats.stops, 1U);
  EXPECT_EQ(stats.recoveries, 1U);
  EXPECT_NE(arm.summary().find("1 recoveries"), std::string::npos) << arm.summary();
}

TEST(FrankaArm, RecoverWithoutAStopDoesNothing) {
  Script script;
  FrankaArm arm = makeArm(script);
  EXPECT_EQ(arm.recover(), "");
  EXPECT_EQ(script.recoveries, 0);
}

TEST(FrankaArm, ModesWithoutAFlagHaveTheirOwnTexts) {
  Script script;
  FrankaSample stopped = idleState(100);
  stopped.robot_mode = fci::RobotMode::kUserStopped;
  script.states.push_back(stopped);
  FrankaArm arm = makeArm(script);
  ASSERT_NE(arm.robotStop(), nullptr);
  EXPECT_NE(std::string(arm.robotStop()).find("user stop"), std::string::npos);
  FrankaSample other = idleState(101);
  other.robot_mode = fci::RobotMode::kOther;
  script.states.push_back(other);
  ASSERT_TRUE(arm.awaitSample());
  EXPECT_NE(std::string(arm.robotStop()).find("not ready"), std::string::npos);
  script.states.push_back(idleState(102));
  ASSERT_TRUE(arm.awaitSample());
  EXPECT_EQ(arm.robotStop(), nullptr);
}

TEST(FrankaArm, ControlEndedFromOutsideStaysAStopUntilRecovered) {
  Script script;
  FrankaArm arm = makeArm(script);
  const std::array<double, 7> torque{};
  ASSERT_TRUE(arm.write(torque));
  ASSERT_TRUE(cycle(arm, torque));
  script.controlling = false;  // Desk or another client ended it, no error named
  script.states.push_back(idleState(101));
  ASSERT_TRUE(arm.awaitSample());
  ASSERT_NE(arm.robotStop(), nullptr);
  EXPECT_NE(std::string(arm.robotStop()).find("ended comply's torque control"), std::string::npos);
  ASSERT_TRUE(arm.awaitSample());
  EXPECT_NE(arm.robotStop(), nullptr);  // still, though the robot is Idle
}

TEST(FrankaArm, ALostLinkIsAStop) {
  Script script;
  FrankaArm arm = makeArm(script);
  script.link_lost = true;
  EXPECT_FALSE(arm.awaitSample());
  ASSERT_NE(arm.robotStop(), nullptr);
  EXPECT_NE(std::string(arm.robotStop()).find("link to the Franka robot is lost"),
            std::string::npos);
  Vector6d wrench;
  EXPECT_FALSE(arm.readWrench(wrench));  // nothing new to give
  JointState state = JointState::zero(7);
  EXPECT_TRUE(arm.read(state));  // the last state, for the controller's hold
  EXPECT_DOUBLE_EQ(state.position[1], 0.1);
}

TEST(FrankaArm, CollisionThresholdsChangeBetweenTwoTorqueControls) {
  Script script;
  FrankaArm arm = makeArm(script);
  const std::array<double, 7> torque{};
  ASSERT_TRUE(arm.write(torque));
  ASSERT_TRUE(cycle(arm, torque));
  ASSERT_TRUE(arm.requestCollisionThresholds(frankaCollisionThresholds(60.0, 80.0)));
  EXPECT_FALSE(arm.requestCollisionThresholds(frankaCollisionThresholds(30.0, 30.0)));
  ASSERT_TRUE(arm.awaitSample());
  // The robot takes thresholds only between motions: ended, set, started again.
  EXPECT_EQ(script.stops, 1);
  ASSERT_EQ(script.thresholds.size(), 2U);
  EXPECT_DOUBLE_EQ(script.thresholds[1].torque_collision_nominal[3], 60.0);
  EXPECT_DOUBLE_EQ(script.thresholds[1].force_collision_nominal[0], 80.0);
  EXPECT_EQ(script.starts, 2);
  EXPECT_EQ(arm.robotStop(), nullptr);
  EXPECT_EQ(arm.stats().threshold_changes, 1U);
  EXPECT_TRUE(arm.requestCollisionThresholds(frankaCollisionThresholds(30.0, 30.0)));
}

TEST(FrankaArm, CollisionThresholdsStayAboveTheContactComplyLetsThrough) {
  Script script;
  FrankaArm arm = makeArm(script);  // 20 N m, 20 N
  const std::array<double, 7> torque{};
  ASSERT_TRUE(arm.write(torque));
  ASSERT_TRUE(cycle(arm, torque));
  // comply's reflex at the file's 10 N: the robot's 20 N stay (never below what it started with).
  arm.allowContact(10.0, 2.0);
  ASSERT_TRUE(cycle(arm, torque));
  ASSERT_EQ(script.thresholds.size(), 2U);
  EXPECT_DOUBLE_EQ(script.thresholds[1].force_collision_nominal[0], 20.0);
  EXPECT_DOUBLE_EQ(script.thresholds[1].force_collision_nominal[3], 3.0);  // 1.5 x 2 N m
  // A command raises it to 40 N for a pressing phase: the robot's go to 1.5 x 40 N, the joints'
  // to 60 N over the 1 m lever; the torque control ends for it and starts again.
  arm.allowContact(40.0, 2.0);
  ASSERT_TRUE(cycle(arm, torque));
  ASSERT_EQ(script.thresholds.size(), 3U);
  EXPECT_DOUBLE_EQ(script.thresholds[2].force_collision_nominal[2], 60.0);
  EXPECT_DOUBLE_EQ(script.thresholds[2].force_contact_nominal[2], 48.0);
  EXPECT_DOUBLE_EQ(script.thresholds[2].torque_collision_nominal[0], 60.0);
  EXPECT_EQ(script.stops, 2);
  EXPECT_EQ(script.starts, 3);
  // The same allowance every cycle, or one within 10 %, changes nothing.
  for (int i = 0; i < 5; ++i) {
    arm.allowContact(41.0, 2.1);
    ASSERT_TRUE(cycle(arm, torque));
  }
  EXPECT_EQ(script.thresholds.size(), 3U);
  // The phase ends: back to the robot's own.
  arm.allowContact(10.0, 2.0);
  ASSERT_TRUE(cycle(arm, torque));
  ASSERT_EQ(script.thresholds.size(), 4U);
  EXPECT_DOUBLE_EQ(script.thresholds[3].force_collision_nominal[2], 20.0);
  EXPECT_DOUBLE_EQ(script.thresholds[3].torque_collision_nominal[0], 20.0);
  arm.allowContact(std::nan(""), 1.0);  // never taken
  ASSERT_TRUE(cycle(arm, torque));
  EXPECT_EQ(script.thresholds.size(), 4U);
}

TEST(FrankaArm, RefusedThresholdsAtStartAreAnError) {
  Script script;
  script.refuse_thresholds = "invalid thresholds";
  try {
    FrankaArm arm = makeArm(script);
    FAIL() << "no error";
  } catch (const hardware::BackendError& error) {
    EXPECT_NE(std::string(error.what()).find("invalid thresholds"), std::string::npos);
  }
  EXPECT_THROW((void)frankaCollisionThresholds(-1.0, 20.0), hardware::BackendError);
  EXPECT_THROW((void)frankaCollisionThresholds(20.0, std::nan("")), hardware::BackendError);
}

TEST(FrankaErrors, NamesAndTexts) {
  EXPECT_STREQ(errorName(25), "communication_constraints_violation");
  EXPECT_STREQ(errorName(6), "joint_reflex");
  EXPECT_STREQ(errorName(40), "base_acceleration_invalid_reading");
  EXPECT_STREQ(errorName(41), "");
  std::array<bool, fci::kErrorCount> flags{};
  EXPECT_EQ(errorNames(flags), "");
  flags[7] = true;
  flags[25] = true;
  EXPECT_EQ(errorNames(flags), "cartesian_reflex, communication_constraints_violation");
  EXPECT_EQ(stopText(flags, fci::RobotMode::kIdle), nullptr);
  EXPECT_NE(std::string(stopText(flags, fci::RobotMode::kReflex)).find("cartesian_reflex"),
            std::string::npos);
}

}  // namespace
}  // namespace comply::franka
