// CartesianController in a ros2_control harness (loaned interfaces over plain doubles, as the
// controller manager hands them out): configured from comply's own controller file given as a
// ROS parameters file, it writes the torque comply's wrapper computes from that same file, the
// options are declared as parameters with their types, ranges and descriptions and read back as
// the file reads, update() allocates nothing, commands pass the command gate of `comply run` with
// its rules, and the state and diagnostics are `comply run`'s messages.

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <lifecycle_msgs/msg/state.hpp>
#include <map>
#include <new>
#include <nlohmann/json.hpp>
#include <optional>
#include <rclcpp_lifecycle/lifecycle_node.hpp>
#include <sstream>

#include "comply/model/robot_description.hpp"
#include "comply/pipeline/config.hpp"
#include "comply/pipeline/config_parameters.hpp"
#include "comply/record/mcap_reader.hpp"
#include "comply/schema/schema.hpp"
#include "comply_msgs/msg/cartesian_command.hpp"
#include "comply_msgs/msg/controller_state.hpp"
#include "comply_msgs/msg/diagnostics.hpp"
#include "comply_ros2_control/comply_controller.hpp"
#include "comply_ros2_control/comply_parameters.hpp"
#include "controller_harness.hpp"

namespace {

std::atomic<long> allocations{0};
thread_local bool counting = false;
double* volatile allocation_probe = nullptr;  // volatile: the probe's new is not optimised away

}  // namespace

// Counts the allocations of the thread that set `counting` (the test's "real-time" thread only),
// at malloc: operator new's and Eigen's alike. glibc exports its allocator as __libc_* for exactly
// this replacement.
extern "C" {
void* __libc_malloc(std::size_t size);                     // NOLINT(bugprone-reserved-identifier)
void* __libc_calloc(std::size_t count, std::size_t size);  // NOLINT(bugprone-reserved-identifier)
void* __libc_realloc(void* memory, std::size_t size);      // NOLINT(bugprone-reserved-identifier)
void* __libc_memalign(std::size_t alignment, std::size_t size);  // NOLINT

void* malloc(std::size_t size) {
  allocations.fetch_add(counting ? 1 : 0, std::memory_order_relaxed);
  return __libc_malloc(size);
}
void* calloc(std::size_t count, std::size_t size) {
  allocations.fetch_add(counting ? 1 : 0, std::memory_order_relaxed);
  return __libc_calloc(count, size);
}
void* realloc(void* memory, std::size_t size) {
  allocations.fetch_add(counting ? 1 : 0, std::memory_order_relaxed);
  return __libc_realloc(memory, size);
}
int posix_memalign(void** memory, std::size_t alignment, std::size_t size) {
  allocations.fetch_add(counting ? 1 : 0, std::memory_order_relaxed);
  *memory = __libc_memalign(alignment, size);
  return *memory != nullptr || size == 0 ? 0 : ENOMEM;
}
void* aligned_alloc(std::size_t alignment, std::size_t size) {
  allocations.fetch_add(counting ? 1 : 0, std::memory_order_relaxed);
  return __libc_memalign(alignment, size);
}
}

namespace comply_ros2_control {
namespace {

TEST_F(ControllerHarness, WritesTheTorqueOfComplysWrapperOnTheSameFile) {
  comply::pipeline::Wrapper<comply::CartesianCommand> reference(
      comply::pipeline::parseWrapperConfig(fileText(kConfig), kConfig, "cartesian_impedance"));
  reference.activate(jointState());
  std::vector<double> expected(dof_);
  const rclcpp::Duration period(0, 1'000'000);
  for (int cycle = 0; cycle < 50; ++cycle) {
    values_[1] = 0.01 * cycle;  // joint 1 moving: damping acts
    ASSERT_EQ(controller_.update(rclcpp::Time(0), period), controller_interface::return_type::OK);
    auto state = jointState();
    state.velocity[0] = values_[1];
    reference.update(state, 0.001, expected);
    for (std::size_t i = 0; i < dof_; ++i) {
      ASSERT_DOUBLE_EQ(torque(i), expected[i]) << "joint " << i << ", cycle " << cycle;
    }
  }
  EXPECT_NE(torque(0), 0.0);
}

TEST_F(ControllerHarness, UpdateAllocatesNothing) {
  const rclcpp::Duration period(0, 1'000'000);
  // Warm-up (first publications, lazy statics) on a moving joint: a state repeated while the
  // torque ramps up would be a frozen sensor stream, and the cycle measured below would be FAULT's.
  for (int cycle = 0; cycle < 100; ++cycle) {
    values_[1] = 1e-3 * (cycle % 7);
    controller_.update(rclcpp::Time(0), period);
  }
  allocations = 0;
  counting = true;
  for (int cycle = 0; cycle < 2000; ++cycle) {
    values_[1] = 1e-3 * (cycle % 7);
    controller_.update(rclcpp::Time(0), period);
  }
  counting = false;
  EXPECT_EQ(allocations.load(), 0);
  // The counter counts: one allocation is seen.
  counting = true;
  allocation_probe = new double(1.0);
  counting = false;
  delete allocation_probe;
  EXPECT_EQ(allocations.load(), 1);
}

// Not only a warmed-up loop: the first cycles after activation (first state sample, first use of
// the gate and of the law) allocate nothing either.
TEST_F(ControllerHarness, FirstCyclesAllocateNothing) {
  const rclcpp::Duration period(0, 1'000'000);
  allocations = 0;
  counting = true;
  for (int cycle = 0; cycle < 10; ++cycle) {
    values_[1] = 1e-3 * cycle;
    controller_.update(rclcpp::Time(0), period);
  }
  counting = false;
  EXPECT_EQ(allocations.load(), 0);
}

class OutputModeHarness : public ControllerHarness,
                          public ::testing::WithParamInterface<std::string> {
 protected:
  OutputModeHarness() { output_mode_ = GetParam(); }
};

// Every output.mode under ros2_control (an arm with an onboard PD, position or velocity drives):
// the controller claims that mode's command interfaces and writes exactly what comply's wrapper
// computes in it on the same file.
TEST_P(OutputModeHarness, WritesTheCommandOfComplysWrapperInItsMode) {
  comply::pipeline::WrapperConfig config =
      comply::pipeline::parseWrapperConfig(fileText(kConfig), kConfig, "cartesian_impedance");
  config.output.mode =
      comply::valueIn(comply::kOutputModeNames, output_mode_).value_or(config.output.mode);
  ASSERT_EQ(comply::toString(config.output.mode), output_mode_);
  comply::pipeline::Wrapper<comply::CartesianCommand> reference(config);
  reference.activate(jointState());
  comply::ActuatorCommand expected;
  expected.resize(static_cast<int>(dof_));
  const std::map<std::string, comply::JointVector comply::ActuatorCommand::*> fields = {
      {"position", &comply::ActuatorCommand::position},
      {"velocity", &comply::ActuatorCommand::velocity},
      {"effort", &comply::ActuatorCommand::effort},
      {"stiffness", &comply::ActuatorCommand::stiffness},
      {"damping", &comply::ActuatorCommand::damping}};
  const std::vector<std::string> kinds = commandKinds();
  const rclcpp::Duration period(0, 1'000'000);
  for (int cycle = 0; cycle < 50; ++cycle) {
    values_[1] = 0.01 * cycle;  // joint 1 moving
    ASSERT_EQ(controller_.update(rclcpp::Time(0), period), controller_interface::return_type::OK);
    auto state = jointState();
    state.velocity[0] = values_[1];
    ASSERT_TRUE(reference.cycle(state, 0.001, expected));
    for (std::size_t i = 0; i < dof_; ++i) {
      for (std::size_t k = 0; k < kinds.size(); ++k) {
        ASSERT_DOUBLE_EQ(command(i, k),
                         (expected.*fields.at(kinds[k]))[static_cast<Eigen::Index>(i)])
            << kinds[k] << " of joint " << i << ", cycle " << cycle;
      }
    }
  }
  EXPECT_TRUE(std::any_of(command_values_.begin(), command_values_.end(), [](double value) {
    return value != 0.0;
  })) << "no command reached the drives";
}

INSTANTIATE_TEST_SUITE_P(Modes, OutputModeHarness,
                         ::testing::Values("joint_pd", "position", "velocity"),
                         [](const auto& info) { return info.param; });

// ~/reset_fault through a real service call: refused outside FAULT, accepted in it (a NaN
// position sends the controller there), and the controller leaves FAULT once the state is usable.
TEST_F(ControllerHarness, ResetFaultServiceLeavesFault) {
  auto client_node = std::make_shared<rclcpp::Node>("reset_client");
  auto client =
      client_node->create_client<std_srvs::srv::Trigger>("/cartesian_impedance/reset_fault");
  rclcpp::executors::SingleThreadedExecutor executor;
  executor.add_node(controller_.get_node()->get_node_base_interface());
  executor.add_node(client_node);
  ASSERT_TRUE(client->wait_for_service(std::chrono::seconds(5)));
  auto reset = [&] {
    auto future = client->async_send_request(std::make_shared<std_srvs::srv::Trigger::Request>());
    EXPECT_EQ(executor.spin_until_future_complete(future, std::chrono::seconds(5)),
              rclcpp::FutureReturnCode::SUCCESS);
    return future.get()->success;
  };
  const rclcpp::Duration period(0, 1'000'000);
  controller_.update(rclcpp::Time(0), period);
  EXPECT_FALSE(reset());  // not in FAULT
  const double home = values_[0];
  values_[0] = std::nan("");
  controller_.update(rclcpp::Time(0), period);
  EXPECT_TRUE(reset());  // in FAULT: reset requested
  values_[0] = home;
  for (int cycle = 0; cycle < 10; ++cycle) {
    controller_.update(rclcpp::Time(0), period);
  }
  EXPECT_FALSE(reset());  // left FAULT
  for (std::size_t i = 0; i < dof_; ++i) {
    EXPECT_TRUE(std::isfinite(torque(i)));
  }
}

// The cases comply run's gate is tested on (tests/pipeline/command_gate_test.cpp and
// tests/live), here through ROS 2 topics: applied with the cycle that took it, an equal stamp
// refused (stamps increase strictly), a second sender refused while the first is active, a burst
// beyond the wrapper's queue refused as queue_full, every command accounted once.
TEST_F(TopicHarness, CommandsPassComplyRunsGate) {
  const rclcpp::Time first = controller_.get_node()->now();
  sender_a_->publish(holdCommand(first));
  const auto applied = outcomeOf(first);
  ASSERT_TRUE(applied);
  EXPECT_EQ(applied->outcome, CommandOutcome::OUTCOME_APPLIED);
  EXPECT_EQ(applied->reason, CommandOutcome::REASON_NONE);
  EXPECT_GT(applied->cycle, 0U);
  EXPECT_LT(applied->cycle, cycles_);
  EXPECT_GE(rclcpp::Time(applied->applied), rclcpp::Time(applied->received));

  // Back to back: the second sender within A's command_timeout_s of silence, so A holds the
  // topics however slowly the diagnostics come.
  sender_a_->publish(holdCommand(first));
  const rclcpp::Time other = controller_.get_node()->now();
  sender_b_->publish(holdCommand(other));
  const auto equal = outcomeOf(first, 1);
  ASSERT_TRUE(equal);
  EXPECT_EQ(equal->outcome, CommandOutcome::OUTCOME_REJECTED);
  EXPECT_EQ(equal->reason, CommandOutcome::REASON_STALE_STAMP);
  const auto second = outcomeOf(other);
  ASSERT_TRUE(second);
  EXPECT_EQ(second->reason, CommandOutcome::REASON_OTHER_PUBLISHER);

  const rclcpp::Time burst = controller_.get_node()->now();
  constexpr int kBurst = 200;
  for (int i = 1; i <= kBurst; ++i) {
    sender_a_->publish(holdCommand(burst + rclcpp::Duration(0, i)));
  }
  // Delivered with no update() in between: more than the wrapper queues between two cycles (64).
  const auto delivered = std::chrono::steady_clock::now() + std::chrono::milliseconds(500);
  while (std::chrono::steady_clock::now() < delivered) {
    executor_->spin_some(std::chrono::milliseconds(1));
  }
  ASSERT_TRUE(runUntil([&] { return outcomes_.size() >= 3 + kBurst; }));
  std::size_t queue_full = 0;
  for (const CommandOutcome& outcome : outcomes_) {
    queue_full += outcome.reason == CommandOutcome::REASON_QUEUE_FULL ? 1 : 0;
  }
  EXPECT_GT(queue_full, 0U);
  runUntil([&] { return diagnostics_received_.back().commands_received == 3 + kBurst; });
  const Diagnostics& last = diagnostics_received_.back();
  EXPECT_EQ(last.commands_received, 3U + kBurst);
  EXPECT_EQ(last.commands_applied + last.commands_rejected, last.commands_received);
  EXPECT_EQ(last.rejections[CommandOutcome::REASON_QUEUE_FULL], queue_full);
  EXPECT_EQ(last.rejections[CommandOutcome::REASON_OTHER_PUBLISHER], 1U);
  EXPECT_EQ(outcomes_.size(), last.commands_received) << "every command accounted once";
}

// ~/state and ~/diagnostics carry comply run's messages, built by the same code: every table
// field set, the contact wrench and the tank's account included.
TEST_F(TopicHarness, StateAndDiagnosticsAreComplyRunsMessages) {
  ASSERT_TRUE(runUntil([&] { return states_.size() >= 5 && diagnostics_received_.size() >= 2; }));
  const ControllerState& state = states_.back();
  EXPECT_EQ(state.state, ControllerState::STATE_ACTIVE);
  EXPECT_EQ(state.command_kind, ControllerState::COMMAND_KIND_CARTESIAN);
  EXPECT_EQ(state.joint_names.size(), dof_);
  EXPECT_EQ(state.position.size(), dof_);
  EXPECT_EQ(state.header.frame_id, "fr3_link0");
  EXPECT_GT(state.cycle, 0U);
  EXPECT_LT(state.cycle, cycles_);
  // The FR3's TCP at home, and the reference the activation seeded there.
  EXPECT_NEAR(state.tcp_position[0], 0.307, 1e-3);
  EXPECT_NEAR(state.tcp_position[2], 0.590, 1e-3);
  EXPECT_NEAR(state.reference_position[2], state.tcp_position[2], 1e-6);
  EXPECT_EQ(state.contact_wrench_source, ControllerState::WRENCH_SOURCE_NONE);
  EXPECT_EQ(state.gain_fraction, 1.0);
  EXPECT_TRUE(state.reference_joint_position.empty());
  // A cycle's torque as the command interfaces hold it.
  for (std::size_t i = 0; i < dof_; ++i) {
    EXPECT_TRUE(std::isfinite(state.torque_command[i]));
  }

  const Diagnostics& diagnostics = diagnostics_received_.back();
  EXPECT_EQ(diagnostics.header.frame_id, "cartesian_impedance");
  EXPECT_EQ(diagnostics.state, ControllerState::STATE_ACTIVE);
  EXPECT_EQ(diagnostics.period, 0.001);
  EXPECT_GT(diagnostics.cycles, 0U);
  EXPECT_GT(diagnostics.histogram_bin, 0.0);
  std::uint64_t timed = 0;
  for (const std::uint64_t count : diagnostics.compute_time_histogram) {
    timed += count;
  }
  EXPECT_EQ(timed, diagnostics.cycles) << "every update() timed";
  std::uint64_t started = 0;
  for (const std::uint64_t count : diagnostics.start_lateness_histogram) {
    started += count;
  }
  EXPECT_EQ(started, diagnostics.cycles - 1) << "every start after the first";
  EXPECT_EQ(diagnostics.rejections.size(), comply::pipeline::kCommandReasonCount)
      << "one count per reason";
}

// A wrist force/torque sensor on ros2_control's interfaces (force_torque_sensor.name): its
// reading is the state's contact wrench, reported as the sensor's; in the TCP frame it is the
// reading itself (the sensor's axes are the TCP's, no tool is declared, no filter).
TEST_F(SensorTopicHarness, TheWristSensorIsTheStatesContactWrench) {
  wrench_ = {1.0, -2.0, 5.0, 0.1, 0.2, -0.3};
  ASSERT_TRUE(runUntil([&] {
    return states_.back().contact_wrench_source == ControllerState::WRENCH_SOURCE_SENSOR &&
           std::abs(states_.back().contact_wrench_tcp[2] - 5.0) < 1e-9;
  })) << "the sensor's reading never reached the state";
  const ControllerState& state = states_.back();
  for (std::size_t k = 0; k < 6; ++k) {
    EXPECT_NEAR(state.contact_wrench_tcp[k], wrench_[k], 1e-9) << "axis " << k;
  }
  // In the base frame, the same force turned by the TCP's orientation: its norm is kept.
  const double norm_tcp = std::hypot(wrench_[0], wrench_[1], wrench_[2]);
  EXPECT_NEAR(std::hypot(state.contact_wrench[0], state.contact_wrench[1], state.contact_wrench[2]),
              norm_tcp, 1e-9);
}

/// A lifecycle node holding comply's controller file as parameters, its options declared.
std::shared_ptr<rclcpp_lifecycle::LifecycleNode> declaredNode(const std::string& params_file) {
  auto node = std::make_shared<rclcpp_lifecycle::LifecycleNode>(
      "cartesian_impedance",
      rclcpp::NodeOptions().automatically_declare_parameters_from_overrides(true).arguments(
          {"--ros-args", "--params-file", params_file}));
  declareOptions(*node);
  return node;
}

TEST(ComplyParameters, OptionsAreDeclaredWithTypeRangeAndDescriptionAndKeepTheFilesValues) {
  rclcpp::init(0, nullptr);
  auto node = declaredNode(kConfig);
  const auto descriptors =
      node->describe_parameters({"validation.max_position_jump_m", "timeout_behavior",
                                 "soft_limits.stiffness", "passivity.enabled"});
  ASSERT_EQ(descriptors.size(), 4u);
  EXPECT_EQ(descriptors[0].type, rcl_interfaces::msg::ParameterType::PARAMETER_DOUBLE);
  EXPECT_EQ(descriptors[0].description, "target vs measured TCP position");
  EXPECT_EQ(descriptors[0].additional_constraints, "must be > 0");
  ASSERT_EQ(descriptors[0].floating_point_range.size(), 1u);
  EXPECT_EQ(descriptors[0].floating_point_range[0].from_value, 0.0);
  EXPECT_EQ(descriptors[1].type, rcl_interfaces::msg::ParameterType::PARAMETER_STRING);
  EXPECT_EQ(descriptors[1].additional_constraints, "must be hold or reanchor");
  EXPECT_EQ(descriptors[3].type, rcl_interfaces::msg::ParameterType::PARAMETER_BOOL);
  // Every option is declared, set or not.
  for (const auto& option : comply::pipeline::optionDeclarations()) {
    EXPECT_TRUE(node->has_parameter(option.name)) << option.name;
  }
  // The parameters read as the file does, option for option.
  const auto parameters = node->get_parameters(node->list_parameters({}, 0).names);
  const auto from_parameters = comply::pipeline::parseWrapperParameters(
      complyParameters(parameters), "test", "cartesian_impedance");
  const auto from_file =
      comply::pipeline::parseWrapperText(fileText(kConfig), kConfig, "cartesian_impedance");
  node.reset();
  rclcpp::shutdown();
  for (const auto& option : comply::pipeline::optionDeclarations()) {
    EXPECT_EQ(comply::pipeline::optionValue(from_parameters, option.name),
              comply::pipeline::optionValue(from_file, option.name))
        << option.name;
  }
  EXPECT_EQ(from_parameters.plugin, from_file.plugin);
  EXPECT_EQ(from_parameters.robot, from_file.robot);
  ASSERT_TRUE(from_parameters.initial_block && from_file.initial_block);
  EXPECT_EQ(*from_parameters.initial_block, *from_file.initial_block);
}

TEST(ComplyParameters, AnUnknownParameterIsComplysErrorAndAValueOutOfRangeIsRefusedAtInit) {
  rclcpp::init(0, nullptr);
  std::vector<rclcpp::Parameter> parameters;
  {
    const auto node = declaredNode(kConfig);
    node->declare_parameter("use_sim_time_extra_is_not_ros_side", 1.0);
    parameters = node->get_parameters(node->list_parameters({}, 0).names);
  }
  rclcpp::shutdown();
  // The ROS-side filter lets everything else through to comply's parser, which names it.
  try {
    comply::pipeline::parseWrapperParameters(complyParameters(parameters), "test",
                                             "cartesian_impedance");
    ADD_FAILURE() << "accepted";
  } catch (const std::exception& error) {
    EXPECT_NE(std::string(error.what()).find("use_sim_time_extra_is_not_ros_side"),
              std::string::npos)
        << error.what();
  }

  const std::string file = ::testing::TempDir() + "/comply_out_of_range.yaml";
  std::ofstream(file) << "cartesian_impedance:\n  ros__parameters:\n    plugin: x\n"
                         "    robot: fr3\n    command_timeout_s: -1.0\n";
  rclcpp::init(0, nullptr);
  try {
    declaredNode(file);
    ADD_FAILURE() << "accepted";
  } catch (const std::exception& error) {
    EXPECT_NE(std::string(error.what()).find("command_timeout_s must be >= 0"), std::string::npos)
        << error.what();
  }
  rclcpp::shutdown();
}

}  // namespace
}  // namespace comply_ros2_control

namespace comply_ros2_control {
namespace {

/// The controller recording to an MCAP file in a folder of its own (the `record` parameter).
class RecordingHarness : public ControllerHarness {
 protected:
  RecordingHarness() {
    folder_ = std::filesystem::temp_directory_path() /
              ("comply_ros2_recording_" + std::to_string(::getpid()));
    std::filesystem::create_directories(folder_);
    path_ = (folder_ / "run.mcap").string();
    extra_parameters_ = {"record:=" + path_};
  }
  ~RecordingHarness() override { std::filesystem::remove_all(folder_); }

  /// `cycles` updates on a moving joint (a repeated state would be a frozen sensor stream).
  void run(int cycles) {
    for (int cycle = 0; cycle < cycles; ++cycle) {
      values_[1] = 1e-3 * (cycle % 7);
      controller_.update(rclcpp::Time(0), rclcpp::Duration(0, 1'000'000));
    }
  }

  std::filesystem::path folder_;
  std::string path_;
};

// Every update() is a cycle record on /<name>/cycle, as `comply run --record` writes it: the
// file closes when the controller is cleaned up, in the ROS 2 profile with the messages'
// definitions, and holds exactly the cycles run.
TEST_F(RecordingHarness, EveryCycleIsRecordedToMcap) {
  constexpr int kCycles = 500;
  run(kCycles);
  controller_.get_node()->deactivate();
  ASSERT_EQ(controller_.get_node()->cleanup().id(),
            lifecycle_msgs::msg::State::PRIMARY_STATE_UNCONFIGURED);
  std::map<std::uint16_t, std::uint64_t> counts;
  const comply::record::McapContents contents = comply::record::readMcap(
      path_, [&](const comply::record::McapMessageView& message) { ++counts[message.channel_id]; });
  EXPECT_EQ(contents.profile, "ros2");
  const auto cycle =
      std::find_if(contents.channels.begin(), contents.channels.end(),
                   [](const auto& c) { return c.topic == "/cartesian_impedance/cycle"; });
  ASSERT_NE(cycle, contents.channels.end());
  EXPECT_EQ(cycle->schema_name, "comply_msgs/msg/CycleRecord");
  EXPECT_EQ(cycle->schema_encoding, "ros2msg");
  EXPECT_FALSE(cycle->schema_data.empty());
  EXPECT_EQ(counts[cycle->id], static_cast<std::uint64_t>(kCycles));
}

// Recording costs update() no allocation: a cycle is copied into a lane the writer drains.
TEST_F(RecordingHarness, UpdateAllocatesNothingWhileRecording) {
  run(100);
  allocations = 0;
  counting = true;
  run(2000);
  counting = false;
  EXPECT_EQ(allocations.load(), 0);
}

// A path in a folder that does not exist: configure fails naming the parameter and the file,
// and the controller stays unconfigured (not finalized).
TEST(RecordingParameter, AnUnwritablePathRefusesConfigure) {
  rclcpp::init(0, nullptr);
  CartesianController controller;
  const auto options = rclcpp::NodeOptions()
                           .allow_undeclared_parameters(true)
                           .automatically_declare_parameters_from_overrides(true)
                           .arguments({"--ros-args", "--params-file", kConfig, "-p",
                                       "record:=/nonexistent-folder/run.mcap"});
  ASSERT_EQ(controller.init("cartesian_impedance", "", options),
            controller_interface::return_type::OK);
  EXPECT_EQ(controller.configure().id(), lifecycle_msgs::msg::State::PRIMARY_STATE_UNCONFIGURED);
  rclcpp::shutdown();
}

}  // namespace
}  // namespace comply_ros2_control
