#include "wrapper_support.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>

#include "comply/model/robot_description.hpp"
#include "comply/model/update.hpp"

namespace comply::pipeline::test {

WrapperConfig controllerConfig(const std::string& plugin, const std::string& robot,
                               const std::string& parameter_lines) {
  std::string yaml = "arm_controller:\n  ros__parameters:\n    plugin: \"" + plugin +
                     "\"\n    robot: \"" + robot + "\"\n";
  std::istringstream lines(parameter_lines);
  for (std::string line; std::getline(lines, line);) {
    yaml += "    " + line + "\n";
  }
  return parseWrapperConfig(yaml, "wrapper_test.yaml");
}

WrapperConfig fr3Config(const std::string& plugin, const std::string& parameter_lines) {
  return controllerConfig(plugin, "fr3", parameter_lines);
}

JointVector fr3Home() {
  const std::vector<double> home = model::loadRobotDescription("fr3").home;
  JointVector q(static_cast<Eigen::Index>(home.size()));
  for (std::size_t i = 0; i < home.size(); ++i) {
    q[static_cast<Eigen::Index>(i)] = home[i];
  }
  return q;
}

JointVector gravityAt(const Controller& core, const JointVector& q) {
  model::Data data(core.model());
  const std::span<const double> positions(q.data(), static_cast<std::size_t>(q.size()));
  if (model::update(core.model(), data, positions, positions, model::Quantity::kGravity) !=
      model::UpdateStatus::kOk) {
    ADD_FAILURE() << "gravity could not be computed at " << q.transpose();
    return JointVector::Constant(q.size(), std::numeric_limits<double>::quiet_NaN());
  }
  return data.gravity;
}

JointState restingAt(const Controller& core, const JointVector& q) {
  JointState state = JointState::zero(static_cast<int>(q.size()));
  state.position = q;
  state.effort = gravityAt(core, q);
  return state;
}

JointVector offset(const JointVector& q, int joint, double delta) {
  JointVector result = q;
  result[joint] += delta;
  return result;
}

JointState movingState(const JointVector& home, int cycle, double amplitude, double base_hz) {
  JointState state = JointState::zero(kFr3Dof);
  const double t = cycle * kPeriod;
  for (int i = 0; i < kFr3Dof; ++i) {
    const double omega = 2.0 * std::numbers::pi * (base_hz + 0.1 * i);
    state.position[i] = home[i] + amplitude * std::sin(omega * t + i);
    state.velocity[i] = amplitude * omega * std::cos(omega * t + i);
  }
  return state;
}

double maxDifference(const JointVector& a, const JointVector& b) {
  if (a.size() != b.size()) {
    return std::numeric_limits<double>::infinity();
  }
  double worst = 0.0;
  for (Eigen::Index i = 0; i < a.size(); ++i) {
    const double difference = std::abs(a[i] - b[i]);
    if (!std::isfinite(difference)) {
      return std::numeric_limits<double>::infinity();  // a NaN must never compare as close
    }
    worst = std::max(worst, difference);
  }
  return worst;
}

}  // namespace comply::pipeline::test
