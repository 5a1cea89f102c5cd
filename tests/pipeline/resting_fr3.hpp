#pragma once
// A fixture for the tests that drive the Cartesian wrapper cycle by cycle on the FR3: the arm at
// rest at home (its measured state never changes), the wrapper activated and one cycle run, a
// host clock that starts at `host_start_s` and advances one period per cycle.

#include <gtest/gtest.h>

#include <string>

#include "comply/pipeline/wrapper.hpp"
#include "wrapper_support.hpp"

namespace comply::pipeline::test {

class RestingFr3 : public ::testing::Test {
 protected:
  /// `parameter_lines`: the controller file's lines (fr3Config).
  RestingFr3(const std::string& parameter_lines, double host_start_s)
      : wrapper(fr3Config(kCartesianImpedancePlugin, parameter_lines)),
        host_start_s_(host_start_s) {}

  void SetUp() override {
    state = restingAt(wrapper.controller(), fr3Home());
    wrapper.activate(state);
    cycles(1);
    home_position = wrapper.measuredPose().tcp_position;
    home_orientation = wrapper.measuredPose().tcp_orientation;
  }

  /// The host's clock now: activation at host_start_s, one period per cycle.
  [[nodiscard]] double hostTime() const { return host_start_s_ + cycle_count * kPeriod; }

  void cycles(int count) {
    for (int i = 0; i < count; ++i) {
      ASSERT_EQ(wrapper.update(state, kPeriod, torque.span()), CycleStatus::kOk)
          << wrapper.diagnostics().last_fault;
      ++cycle_count;
    }
  }

  /// The command the law read in the last cycle.
  [[nodiscard]] const comply_cartesian_command& law() const {
    return std::get<comply_cartesian_command>(wrapper.controller().lawBus());
  }
  [[nodiscard]] Eigen::Vector3d reference() const {
    return Eigen::Map<const Eigen::Vector3d>(law().position);
  }

  CartesianWrapper wrapper;
  JointState state;
  TorqueBuffer torque;
  int cycle_count = 0;
  Eigen::Vector3d home_position;
  Eigen::Quaterniond home_orientation;

 private:
  double host_start_s_;
};

}  // namespace comply::pipeline::test
