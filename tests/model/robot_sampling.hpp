#pragma once
// Random joint states inside a model's limits, reproducible from a seed, and the fixture of the
// tests run on every shipped robot.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "comply/model/data.hpp"
#include "comply/model/model.hpp"
#include "comply/model/robot_description.hpp"

namespace comply::testing {

/// The robots on the search path (robots/ and COMPLY_ROBOT_PATH): a robot added as a folder is
/// covered by every test over this list with no line to add.
inline const std::vector<std::string>& shippedRobots() {
  static const std::vector<std::string> names = model::availableRobots();
  return names;
}

struct JointSample {
  std::vector<double> q;
  std::vector<double> dq;
};

class JointSampler {
 public:
  JointSampler(const model::Model& model, unsigned seed) : model_(model), engine_(seed) {}

  /// Positions uniform within the limits (continuous joints within +-pi), velocities uniform
  /// within the velocity limits (1 rad/s where the URDF gives none).
  JointSample next() {
    JointSample sample;
    for (int i = 0; i < model_.dof(); ++i) {
      const model::JointLimits& limits = model_.limits(i);
      const double lower = std::isfinite(limits.lower) ? limits.lower : -std::numbers::pi;
      const double upper = std::isfinite(limits.upper) ? limits.upper : std::numbers::pi;
      const double speed = limits.velocity > 0.0 ? limits.velocity : 1.0;
      sample.q.push_back(std::uniform_real_distribution<double>(lower, upper)(engine_));
      sample.dq.push_back(std::uniform_real_distribution<double>(-speed, speed)(engine_));
    }
    return sample;
  }

 private:
  const model::Model& model_;
  std::mt19937 engine_;
};

/// A test on the robot its parameter names: its description, model and data, loaded per test.
class ShippedRobotTest : public ::testing::TestWithParam<std::string> {
 protected:
  void SetUp() override {
    robot_ = model::loadRobotDescription(GetParam());
    model_ = std::make_unique<model::Model>(robot_.loadModel());
    data_ = std::make_unique<model::Data>(*model_);
  }

  model::RobotDescription robot_;
  std::unique_ptr<model::Model> model_;
  std::unique_ptr<model::Data> data_;
};

}  // namespace comply::testing
