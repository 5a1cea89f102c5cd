// A plain rclcpp node against any comply host (`comply run`, or these controllers): reads the
// host's state, sends one Cartesian target 2 cm away and waits until the state shows the target
// in force and the TCP settled (below 1 mm/s) within 2 mm of it. Exit 0 on success, 1 otherwise.
//
//   comply_rclcpp_probe HOST_NAME [TIMEOUT_S]

#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>
#include <rclcpp/rclcpp.hpp>
#include <string>

#include "comply_msgs/msg/cartesian_command.hpp"
#include "comply_msgs/msg/controller_state.hpp"

namespace {

using comply_msgs::msg::CartesianCommand;
using comply_msgs::msg::ControllerState;

double distance(const std::array<double, 3>& a, const std::array<double, 3>& b) {
  return std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
                   (a[2] - b[2]) * (a[2] - b[2]));
}

}  // namespace

int main(int argc, char** argv) {
  rclcpp::init(argc, argv);
  const auto arguments = rclcpp::remove_ros_arguments(argc, argv);
  if (arguments.size() < 2) {
    std::fprintf(stderr, "usage: comply_rclcpp_probe HOST_NAME [TIMEOUT_S]\n");
    return 2;
  }
  const std::string host = arguments[1];
  const double timeout_s = arguments.size() > 2 ? std::stod(arguments[2]) : 30.0;
  auto node = rclcpp::Node::make_shared("comply_rclcpp_probe");
  std::optional<ControllerState> last;
  auto subscription = node->create_subscription<ControllerState>(
      "/" + host + "/state", rclcpp::SensorDataQoS(),
      [&last](const ControllerState::SharedPtr state) { last = *state; });
  auto publisher = node->create_publisher<CartesianCommand>("/" + host + "/cartesian_command",
                                                            rclcpp::QoS(10).reliable());
  const auto deadline = node->now() + rclcpp::Duration::from_seconds(timeout_s);
  auto spin_until = [&](auto done) {
    while (rclcpp::ok() && node->now() < deadline && !done()) {
      rclcpp::spin_some(node);
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
    return done();
  };
  if (!spin_until(
          [&] { return last.has_value() && last->state == ControllerState::STATE_ACTIVE; })) {
    std::fprintf(stderr, "probe: no active state on /%s/state within %.0f s\n", host.c_str(),
                 timeout_s);
    return 1;
  }
  CartesianCommand command;
  command.header.stamp = node->now();
  command.fields = CartesianCommand::FIELD_POSITION;
  command.position = {last->tcp_position[0], last->tcp_position[1] + 0.02,
                      last->tcp_position[2] - 0.02};
  command.orientation = last->tcp_orientation;
  // Wait until the host's reader matched, else the one message may go nowhere.
  spin_until([&] { return publisher->get_subscription_count() > 0; });
  publisher->publish(command);
  const bool reached = spin_until([&] {
    const std::array<double, 3> linear_velocity{last->tcp_twist[0], last->tcp_twist[1],
                                                last->tcp_twist[2]};
    return distance(last->reference_position, command.position) < 1e-9 &&
           distance(last->tcp_position, command.position) < 2e-3 &&
           distance(linear_velocity, {0.0, 0.0, 0.0}) < 1e-3;
  });
  // Settle a second more: the error reported is where the arm rests, not where it crossed 2 mm.
  const auto settle_end = node->now() + rclcpp::Duration::from_seconds(1.0);
  while (reached && rclcpp::ok() && node->now() < settle_end) {
    rclcpp::spin_some(node);
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  std::printf(
      "probe: target %s, reference %s, TCP %.3f mm from the target\n",
      reached ? "reached" : "missed",
      distance(last->reference_position, command.position) < 1e-9 ? "in force" : "not taken",
      1e3 * distance(last->tcp_position, command.position));
  rclcpp::shutdown();
  return reached ? 0 : 1;
}
