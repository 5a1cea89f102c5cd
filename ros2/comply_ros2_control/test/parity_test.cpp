// What `comply run` does with its senders, sensors and safety stages, under ros2_control: a
// sender that leaves releases the command topics at once (not after command_timeout_s), every
// outcome names the process that sent the command (checked against the ROS graph's own record of
// the writer), a wrist sensor is read from the interface names vendors' drivers export, the
// motion governor brakes a fast joint, an overspeed FAULT brakes the arm, and a reset request on
// ~/request holds the measured pose.

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "comply_msgs/msg/cartesian_chunk.hpp"
#include "comply_msgs/msg/committed.hpp"
#include "comply_msgs/msg/committed_request.hpp"
#include "comply_msgs/msg/request.hpp"
#include "controller_harness.hpp"

namespace comply_ros2_control {
namespace {

/// The topics held for 10 s of a sender's silence: far longer than any departure takes to notice.
class LongTimeoutTopicHarness : public TopicHarness {
 protected:
  LongTimeoutTopicHarness() { extra_parameters_ = {"command_timeout_s:=10.0"}; }
};

// A second process (its own participant) holds the topics; the first is refused as
// other_publisher. The holder's writer is deleted: the next command of the first is applied at
// once, where comply's gate would otherwise make it wait out command_timeout_s.
TEST_F(LongTimeoutTopicHarness, ASenderThatLeavesReleasesTheTopicsAtOnce) {
  ASSERT_EQ(controller_.get_node()->get_parameter("command_timeout_s").as_double(), 10.0);
  const rclcpp::Time held = controller_.get_node()->now();
  sender_b_->publish(holdCommand(held));
  const auto applied = outcomeOf(held);
  ASSERT_TRUE(applied);
  EXPECT_EQ(applied->outcome, CommandOutcome::OUTCOME_APPLIED);
  const rclcpp::Time refused = controller_.get_node()->now();
  sender_a_->publish(holdCommand(refused));
  const auto other = outcomeOf(refused);
  ASSERT_TRUE(other);
  EXPECT_EQ(other->reason, CommandOutcome::REASON_OTHER_PUBLISHER);

  sender_b_.reset();  // the writer is deleted: its process leaves the topics
  const auto left = std::chrono::steady_clock::now();
  std::optional<CommandOutcome> taken;
  while (!taken && std::chrono::steady_clock::now() - left < std::chrono::seconds(5)) {
    const rclcpp::Time stamp = controller_.get_node()->now();
    sender_a_->publish(holdCommand(stamp));
    const auto outcome = outcomeOf(stamp);
    ASSERT_TRUE(outcome);
    if (outcome->outcome == CommandOutcome::OUTCOME_APPLIED) {
      taken = outcome;
    } else {
      EXPECT_EQ(outcome->reason, CommandOutcome::REASON_OTHER_PUBLISHER);
    }
  }
  const double waited_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - left).count();
  ASSERT_TRUE(taken) << "the topics were not released within 5 s of the holder leaving";
  EXPECT_LT(waited_s, 5.0) << "released by the departure, not by command_timeout_s (10 s)";
}

/// The writer GUID the ROS graph records for the publisher of `node_name` on `topic`.
std::optional<std::array<std::uint8_t, RMW_GID_STORAGE_SIZE>> writerGid(
    rclcpp::Node& observer, const std::string& topic, const std::string& node_name) {
  for (const rclcpp::TopicEndpointInfo& info : observer.get_publishers_info_by_topic(topic)) {
    if (info.node_name() == node_name) {
      return info.endpoint_gid();
    }
  }
  return std::nullopt;
}

// Each outcome names its sender as `comply run`'s do: the sending participant's GUID, the
// writer's GUID prefix with the participant's entity id 0x000001c1. The ROS graph (from DDS
// discovery, independently of the controller) gives each writer's GUID; two processes differ.
TEST_F(TopicHarness, EveryOutcomeNamesTheProcessThatSentIt) {
  const std::string topic = "/cartesian_impedance/cartesian_command";
  std::optional<std::array<std::uint8_t, RMW_GID_STORAGE_SIZE>> gid_a, gid_b;
  ASSERT_TRUE(runUntil([&] {
    gid_a = writerGid(*listener_, topic, "listener");
    gid_b = writerGid(*listener_, topic, "second_sender");
    return gid_a && gid_b;
  })) << "the graph never listed both writers";
  const rclcpp::Time stamp = controller_.get_node()->now();
  // One stamp from both: the sender tells the two outcomes apart.
  sender_a_->publish(holdCommand(stamp));
  sender_b_->publish(holdCommand(stamp));
  ASSERT_TRUE(outcomeOf(stamp, 1));
  std::vector<CommandOutcome> both;
  std::copy_if(outcomes_.begin(), outcomes_.end(), std::back_inserter(both),
               [&](const CommandOutcome& o) { return rclcpp::Time(o.stamp) == stamp; });
  ASSERT_EQ(both.size(), 2U);
  const auto expected = [](const std::array<std::uint8_t, RMW_GID_STORAGE_SIZE>& writer) {
    std::array<std::uint8_t, 16> participant{};
    std::copy_n(writer.begin(), 12, participant.begin());
    participant[14] = 0x01;
    participant[15] = 0xc1;
    return participant;
  };
  const auto sender = [](const CommandOutcome& o) {
    std::array<std::uint8_t, 16> id{};
    std::copy(o.sender.begin(), o.sender.end(), id.begin());
    return id;
  };
  const auto by_a = std::find_if(both.begin(), both.end(), [&](const CommandOutcome& o) {
    return o.outcome == CommandOutcome::OUTCOME_APPLIED;
  });
  const auto by_b = std::find_if(both.begin(), both.end(), [&](const CommandOutcome& o) {
    return o.reason == CommandOutcome::REASON_OTHER_PUBLISHER;
  });
  ASSERT_NE(by_a, both.end());
  ASSERT_NE(by_b, both.end());
  EXPECT_EQ(sender(*by_a), expected(*gid_a));
  EXPECT_EQ(sender(*by_b), expected(*gid_b));
  EXPECT_NE(sender(*by_a), sender(*by_b));
}

// The committed prefix over ROS 2 (docs/policies.md): a ROS 2 node asks what the controller will
// execute at observation + k dt; the answer names the request's stamp and sender, one entry per
// time stamped exactly, and the reference of the command in force (a hold at the measured pose).
TEST_F(TopicHarness, TheCommittedPrefixIsAnsweredOverRos2) {
  const rclcpp::Time held = controller_.get_node()->now();
  const CartesianCommand hold = holdCommand(held);
  sender_a_->publish(hold);
  ASSERT_TRUE(outcomeOf(held));
  std::vector<comply_msgs::msg::Committed> answers;
  auto answer_subscription = listener_->create_subscription<comply_msgs::msg::Committed>(
      "/cartesian_impedance/committed", rclcpp::QoS(10).reliable(),
      [&](const comply_msgs::msg::Committed& answer) { answers.push_back(answer); });
  auto asker = listener_->create_publisher<comply_msgs::msg::CommittedRequest>(
      "/cartesian_impedance/committed_request", rclcpp::QoS(10).reliable());
  ASSERT_TRUE(runUntil([&] {
    return asker->get_subscription_count() > 0 && answer_subscription->get_publisher_count() > 0;
  }));
  comply_msgs::msg::CommittedRequest request;
  request.header.stamp = controller_.get_node()->now();
  request.observation = states_.back().header.stamp;
  request.dt = 0.1;
  request.count = 5;
  asker->publish(request);
  ASSERT_TRUE(runUntil([&] { return !answers.empty(); })) << "no answer on ~/committed";
  const comply_msgs::msg::Committed& answer = answers.back();
  EXPECT_TRUE(answer.answered) << answer.message;
  EXPECT_TRUE(answer.known);
  EXPECT_EQ(rclcpp::Time(answer.request_stamp), rclcpp::Time(request.header.stamp));
  EXPECT_EQ(answer.header.frame_id, "fr3_link0");
  EXPECT_NE(answer.sender, decltype(answer.sender){}) << "the answer names its sender";
  ASSERT_EQ(answer.cartesian.size(), 5U);
  EXPECT_TRUE(answer.joint.empty());
  for (std::size_t k = 0; k < 5; ++k) {
    const auto expected = rclcpp::Time(request.observation) +
                          rclcpp::Duration(0, static_cast<std::uint32_t>(k * 100'000'000));
    EXPECT_EQ(rclcpp::Time(answer.cartesian[k].header.stamp), expected) << "entry " << k;
    for (std::size_t axis = 0; axis < 3; ++axis) {
      EXPECT_NEAR(answer.cartesian[k].position[axis], hold.position[axis], 1e-9)
          << "entry " << k << ", axis " << axis;
    }
  }

  // A request comply's rules refuse is answered too, naming the field.
  request.header.stamp = controller_.get_node()->now();
  request.count = 0;
  asker->publish(request);
  ASSERT_TRUE(runUntil([&] { return answers.size() >= 2; }));
  EXPECT_FALSE(answers.back().answered);
  EXPECT_NE(answers.back().message.find("count is 0"), std::string::npos) << answers.back().message;
}

// A chunk planned for an observation, over ROS 2: its outcome carries its timing record as under
// `comply run` (chunks.md): it took over, when, from which cycle, and how many of its waypoints
// were already past by then, the delay measured in the chunk's own steps.
TEST_F(TopicHarness, AChunksOutcomeCarriesItsMeasuredDelay) {
  auto chunks = listener_->create_publisher<comply_msgs::msg::CartesianChunk>(
      "/cartesian_impedance/cartesian_chunk", rclcpp::QoS(10).reliable());
  ASSERT_TRUE(runUntil([&] { return chunks->get_subscription_count() > 0; }));
  const ControllerState observed = states_.back();
  const rclcpp::Time observation(observed.header.stamp);
  comply_msgs::msg::CartesianChunk chunk;
  chunk.header.stamp = controller_.get_node()->now();
  chunk.fields = static_cast<std::uint32_t>(comply::CommandField::kPosition);
  chunk.observation = observed.header.stamp;
  for (int k = 0; k < 20; ++k) {  // 50 ms apart from the observation on: a hold, timed
    CartesianCommand waypoint = holdCommand(observation + rclcpp::Duration(0, k * 50'000'000));
    chunk.waypoints.push_back(waypoint);
  }
  chunks->publish(chunk);
  const auto outcome = outcomeOf(rclcpp::Time(chunk.header.stamp));
  ASSERT_TRUE(outcome);
  ASSERT_EQ(outcome->outcome, CommandOutcome::OUTCOME_APPLIED) << outcome->message;
  ASSERT_EQ(outcome->chunk.size(), 1U) << "no timing record with the chunk's outcome";
  const comply_msgs::msg::ChunkTiming& timing = outcome->chunk[0];
  EXPECT_EQ(timing.end, comply_msgs::msg::ChunkTiming::END_TOOK_OVER);
  EXPECT_EQ(timing.waypoints, 20U);
  EXPECT_GT(timing.takeover_cycle, 0U);
  EXPECT_GE(rclcpp::Time(timing.takeover), rclcpp::Time(timing.received));
  // The record's times come back from the controller's clock, which this harness advances by the
  // nominal 1 ms per update() while the executor spins in between: within a few ms of the node's.
  EXPECT_NEAR((rclcpp::Time(timing.observation) - observation).seconds(), 0.0, 5e-3);
  // Sent after the observation, taken over later still: at least waypoint 0 was past, and the
  // count is the delay in the chunk's 50 ms steps.
  const double delay_s = (rclcpp::Time(timing.takeover) - observation).seconds();
  EXPECT_GE(timing.waypoints_past, 1U);
  EXPECT_NEAR(static_cast<double>(timing.waypoints_past), std::ceil(delay_s / 0.05), 1.0)
      << "delay " << delay_s << " s";
}

/// A virtual wall 1 cm in front of the FR3's TCP at home (x = 0.307 m), given as ROS 2 parameters
/// hold it: the YAML text of the file's list.
class WallHarness : public TopicHarness {
 protected:
  WallHarness() { extra_parameters_ = {"walls:='[{point: [0.317, 0, 0], normal: [1, 0, 0]}]'"}; }
};

// The walls of a controller file under ros2_control: the state reports them and the TCP's
// distance to the nearest; a target beyond the wall has the law's reference moved back inside,
// counted on ~/diagnostics.
TEST_F(WallHarness, AWallHoldsTheReferenceInside) {
  ASSERT_TRUE(runUntil([&] { return !states_.empty() && states_.back().walls; }));
  EXPECT_NEAR(states_.back().wall_distance, 0.01, 1e-3);
  const rclcpp::Time stamp = controller_.get_node()->now();
  CartesianCommand beyond = holdCommand(stamp);
  beyond.position[0] += 0.05;
  sender_a_->publish(beyond);
  const auto outcome = outcomeOf(stamp);
  ASSERT_TRUE(outcome);
  EXPECT_EQ(outcome->outcome, CommandOutcome::OUTCOME_APPLIED) << outcome->message;
  ASSERT_TRUE(runUntil([&] { return diagnostics_received_.back().wall_reference_hits > 0; }))
      << "the reference beyond the wall was never moved back";
}

/// A wrist sensor named as a vendor's driver exports it: the controller's parameter and the six
/// state interfaces of the hardware.
struct VendorSensor {
  const char* label;
  const char* parameter;
  std::vector<std::string> interfaces;
};

class VendorSensorHarness : public TopicHarness,
                            public ::testing::WithParamInterface<VendorSensor> {
 protected:
  VendorSensorHarness() {
    sensor_parameter_ = GetParam().parameter;
    sensor_interfaces_ = GetParam().interfaces;
  }
};

// The reading reaches the state as the sensor's contact wrench, axis for axis, whatever the
// interfaces are called.
TEST_P(VendorSensorHarness, TheSensorIsReadUnderItsVendorsNames) {
  wrench_ = {2.0, -1.0, 7.5, 0.05, -0.1, 0.2};
  ASSERT_TRUE(runUntil([&] {
    return states_.back().contact_wrench_source == ControllerState::WRENCH_SOURCE_SENSOR &&
           std::abs(states_.back().contact_wrench_tcp[2] - 7.5) < 1e-9;
  })) << "the sensor's reading never reached the state";
  for (std::size_t k = 0; k < 6; ++k) {
    EXPECT_NEAR(states_.back().contact_wrench_tcp[k], wrench_[k], 1e-9) << "axis " << k;
  }
}

INSTANTIATE_TEST_SUITE_P(
    Names, VendorSensorHarness,
    ::testing::Values(
        // UR's driver (and comply's MuJoCo hardware): ros2_control's force-torque names.
        VendorSensor{
            "tcp_fts_sensor",
            "force_torque_sensor.name:=tcp_fts_sensor",
            {"tcp_fts_sensor/force.x", "tcp_fts_sensor/force.y", "tcp_fts_sensor/force.z",
             "tcp_fts_sensor/torque.x", "tcp_fts_sensor/torque.y", "tcp_fts_sensor/torque.z"}},
        // Six names of a driver's own, in the order force x y z, torque x y z.
        VendorSensor{"interface_names",
                     "force_torque_sensor.interface_names:=[wrist/fx, wrist/fy, wrist/fz, "
                     "wrist/tx, wrist/ty, wrist/tz]",
                     {"wrist/fx", "wrist/fy", "wrist/fz", "wrist/tx", "wrist/ty", "wrist/tz"}}),
    [](const auto& info) { return std::string(info.param.label); });

/// Joint 1 of the FR3 turning at `speed_rad_per_s` for `cycles` cycles (its position following),
/// the executor spun between them; the last diagnostics and state the listener received.
class MotionHarness : public TopicHarness {
 protected:
  void turn(double speed_rad_per_s, int cycles) {
    for (int cycle = 0; cycle < cycles; ++cycle) {
      values_[0] += speed_rad_per_s * 0.001;
      values_[1] = speed_rad_per_s;
      controller_.update(controller_.get_node()->now(), rclcpp::Duration(0, 1'000'000));
      ++cycles_;
      executor_->spin_some(std::chrono::milliseconds(1));
    }
  }
  /// Diagnostics received after this call began, once `done` holds for one (or 10 s).
  template <typename Done>
  std::optional<Diagnostics> diagnosticsWhen(Done&& done) {
    const std::size_t seen = diagnostics_received_.size();
    std::optional<Diagnostics> found;
    runUntil([&] {
      for (std::size_t i = seen; i < diagnostics_received_.size(); ++i) {
        if (done(diagnostics_received_[i])) {
          found = diagnostics_received_[i];
          return true;
        }
      }
      return false;
    });
    return found;
  }
};

// The FR3's joint 1 at 2.0 rad/s: past 0.85 of its governed speed (0.8 x 2.62 rad/s), below the
// overspeed FAULT (2.62). The governor brakes it: its torque opposes the motion, the controller
// stays active, and ~/diagnostics counts the cycles it acted in.
TEST_F(MotionHarness, TheGovernorBrakesAFastJoint) {
  turn(2.0, 30);
  EXPECT_LT(torque(0), 0.0) << "joint 1's torque opposes its motion";
  const auto diagnostics =
      diagnosticsWhen([](const Diagnostics& d) { return d.governor_hits > 0; });
  ASSERT_TRUE(diagnostics) << "the governor never acted";
  EXPECT_EQ(diagnostics->state, ControllerState::STATE_ACTIVE);
  EXPECT_EQ(diagnostics->faults, 0U);
}

// Joint 1 at 3.0 rad/s, past its URDF speed: the overspeed FAULT, and the stop brakes the arm
// (the torque opposes the motion). A reset request on ~/request (comply run's request, from a
// ROS 2 node) is answered on ~/diagnostics, leaves FAULT, and the reference is the measured pose.
TEST_F(MotionHarness, AnOverspeedFaultBrakesAndAResetRequestHoldsTheMeasuredPose) {
  turn(3.0, 20);
  const auto faulted =
      diagnosticsWhen([](const Diagnostics& d) { return d.state == ControllerState::STATE_FAULT; });
  ASSERT_TRUE(faulted) << "no FAULT at 3 rad/s";
  EXPECT_FALSE(faulted->last_fault.empty());
  turn(3.0, 5);
  EXPECT_LT(torque(0), 0.0) << "the FAULT's stop brakes joint 1";

  values_[1] = 0.0;  // at rest again, where the reset finds it
  auto requester = listener_->create_publisher<comply_msgs::msg::Request>(
      "/cartesian_impedance/request", rclcpp::QoS(10).reliable());
  ASSERT_TRUE(runUntil([&] { return requester->get_subscription_count() > 0; }));
  comply_msgs::msg::Request reset;
  reset.header.stamp = controller_.get_node()->now();
  reset.request = comply_msgs::msg::Request::REQUEST_RESET;
  requester->publish(reset);
  const auto answered = outcomeOf(rclcpp::Time(reset.header.stamp));
  ASSERT_TRUE(answered) << "the reset request was not answered";
  EXPECT_EQ(answered->outcome, CommandOutcome::OUTCOME_APPLIED) << answered->message;
  ASSERT_TRUE(runUntil([&] {
    return !states_.empty() && states_.back().state == ControllerState::STATE_ACTIVE;
  })) << "still in FAULT after the reset";
  const ControllerState& state = states_.back();
  for (std::size_t k = 0; k < 3; ++k) {
    EXPECT_NEAR(state.reference_position[k], state.tcp_position[k], 1e-6) << "axis " << k;
  }
}

}  // namespace
}  // namespace comply_ros2_control
