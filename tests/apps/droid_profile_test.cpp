// The DROID profile (profiles/droid/droid.yaml) end to end through `comply validate`: its torque
// matches polymetis' HybridJointImpedanceControl with DROID's gains,
//
//   tau = (J^T Kx J + Kq)(q_d - q) - (J^T Kxd J + Kqd) dq + C(q, dq) dq + tau_ff,
//
// on random states of the FR3. The golden torques are computed here from that formula with the
// gains written down below, not read from the profile, and with J and C(q, dq) dq from KDL
// (ChainJntToJacSolver, ChainDynParam), not from comply's model: a wrong gain in the file, a wrong
// Jacobian or a law that damps dq - dq_d all show up as a failed validate.

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "comply/model/robot_description.hpp"
#include "kdl_reference.hpp"
#include "scratch.hpp"

namespace comply::testing {
namespace {

using Vector6d = Eigen::Matrix<double, 6, 1>;
using Vector7d = Eigen::Matrix<double, 7, 1>;

// DROID's Franka under polymetis (profiles/README.md gives the sources).
const Vector7d kKq = (Vector7d() << 40, 30, 50, 25, 35, 25, 10).finished();
const Vector7d kKqd = (Vector7d() << 4, 6, 5, 5, 3, 2, 1).finished();
const Vector6d kKx = (Vector6d() << 400, 400, 400, 15, 15, 15).finished();
const Vector6d kKxd = (Vector6d() << 37, 37, 37, 2, 2, 2).finished();

// Max absolute torque error [N m] `comply validate` may report. The law and the golden torque
// differ only in where J and C(q, dq) dq come from (comply's model, KDL) and in the order of the
// operations; on these samples the error stays below 1e-13 N m, so 1e-9 leaves room for other
// compilers while a gain off by a millionth of its value, or any change of the law, still fails.
constexpr double kTolerance = 1e-9;
constexpr int kSamples = 100;

struct Sample {
  Vector7d q, dq, q_d, dq_d, feedforward;
};

std::string numbers(const Eigen::Ref<const Eigen::VectorXd>& v) {
  std::ostringstream text;
  text << std::setprecision(17) << "[";
  for (Eigen::Index i = 0; i < v.size(); ++i) {
    text << (i > 0 ? ", " : "") << v[i];
  }
  return text.str() + "]";
}

std::string writeFile(const std::string& name, const std::string& text) {
  const std::filesystem::path path = scratchPath("comply_droid_profile", name);
  std::ofstream(path) << text;
  return path.string();
}

/// {"samples": [{"torque": [...]}, ...]}, the shape `comply validate --expected` reads.
std::string expectedDocument(const std::vector<Vector7d>& torques) {
  std::string text = "{\"samples\": [";
  for (std::size_t s = 0; s < torques.size(); ++s) {
    text += (s > 0 ? ",\n" : "\n") + std::string("{\"torque\": ") + numbers(torques[s]) + "}";
  }
  return text + "]}\n";
}

struct Validation {
  int exit_code = -1;
  std::string output;
};

Validation validate(const std::string& inputs, const std::string& expected) {
  const std::string profile =
      (std::filesystem::path(COMPLY_TEST_SOURCE_DIR) / "profiles" / "droid" / "droid.yaml")
          .string();
  std::ostringstream tolerance;
  tolerance << std::setprecision(17) << kTolerance;
  const auto [code, output] =
      runCommand(std::string(COMPLY_TEST_CLI) + " validate --config " + profile + " --inputs " +
                 inputs + " --expected " + expected + " --tolerance " + tolerance.str() + " 2>&1");
  return {code, output};
}

class DroidProfile : public ::testing::Test {
 protected:
  void SetUp() override {
    const model::RobotDescription fr3 = model::loadRobotDescription("fr3");
    const model::Model model = fr3.loadModel();
    ASSERT_EQ(model.dof(), 7);
    const KdlReference kdl(fr3.urdf_path.string(), fr3.base_frame, fr3.tcp_frame, fr3.joints);

    std::mt19937 rng(20240314);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    const auto uniform = [&](double low, double high) { return low + (high - low) * unit(rng); };
    std::string inputs = "[";
    for (int s = 0; s < kSamples; ++s) {
      Sample sample;
      for (int i = 0; i < 7; ++i) {
        sample.q[i] = uniform(model.limits(i).lower, model.limits(i).upper);
        sample.dq[i] = uniform(-1.5, 1.5);
        // Within the default validation.max_joint_jump_rad (0.5), or validate rejects the target.
        sample.q_d[i] = sample.q[i] + uniform(-0.3, 0.3);
        sample.dq_d[i] = uniform(-1.0, 1.0);
        sample.feedforward[i] = uniform(-2.0, 2.0);
      }
      const ReferenceResult reference = kdl.compute(sample.q, sample.dq);
      const Eigen::Matrix<double, 6, 7> jacobian = reference.jacobian;
      const Eigen::Matrix<double, 7, 7> stiffness =
          jacobian.transpose() * kKx.asDiagonal() * jacobian +
          Eigen::Matrix<double, 7, 7>(kKq.asDiagonal());
      const Eigen::Matrix<double, 7, 7> damping =
          jacobian.transpose() * kKxd.asDiagonal() * jacobian +
          Eigen::Matrix<double, 7, 7>(kKqd.asDiagonal());
      const Vector7d common =
          stiffness * (sample.q_d - sample.q) + reference.coriolis + sample.feedforward;
      golden_.push_back(common - damping * sample.dq);
      // What a law damping the velocity error would give: the command's dq_d must not count.
      velocity_error_.push_back(common - damping * (sample.dq - sample.dq_d));

      // Stiffness and damping are left to the profile's `initial:` gains.
      inputs += std::string(s > 0 ? ",\n" : "\n") + "{\"q\": " + numbers(sample.q) +
                ", \"dq\": " + numbers(sample.dq) +
                ", \"command\": {\"position\": " + numbers(sample.q_d) +
                ", \"velocity\": " + numbers(sample.dq_d) +
                ", \"torque_feedforward\": " + numbers(sample.feedforward) + "}}";
    }
    inputs_ = writeFile("inputs.json", inputs + "]\n");
  }

  std::string inputs_;
  std::vector<Vector7d> golden_;
  std::vector<Vector7d> velocity_error_;
};

TEST_F(DroidProfile, TorqueMatchesThePublishedFormula) {
  const Validation result = validate(inputs_, writeFile("golden.json", expectedDocument(golden_)));
  EXPECT_EQ(result.exit_code, 0) << result.output;
  EXPECT_NE(result.output.find("all outputs within tolerance"), std::string::npos) << result.output;
  // The line "torque  <max |error|>  ok", kept in the test log as the error actually reached.
  const std::size_t line = result.output.find("\ntorque");
  ASSERT_NE(line, std::string::npos) << result.output;
  std::istringstream fields(result.output.substr(line + 1));
  std::string key;
  double max_error = -1.0;
  fields >> key >> max_error;
  EXPECT_LE(max_error, kTolerance);
  RecordProperty("max_torque_error_nm", std::to_string(max_error));
  std::cout << "max |torque error| over " << kSamples << " samples: " << max_error << " N m\n";
}

TEST_F(DroidProfile, WrongExpectedTorquesFail) {
  std::vector<Vector7d> nudged = golden_;
  nudged[kSamples / 2][4] += 1e-6;  // one joint of one sample, a thousand times the tolerance
  const Validation off = validate(inputs_, writeFile("nudged.json", expectedDocument(nudged)));
  EXPECT_EQ(off.exit_code, 1) << off.output;
  EXPECT_NE(off.output.find("ABOVE TOLERANCE"), std::string::npos) << off.output;

  const Validation damped =
      validate(inputs_, writeFile("velocity_error.json", expectedDocument(velocity_error_)));
  EXPECT_EQ(damped.exit_code, 1) << damped.output;
}

}  // namespace
}  // namespace comply::testing
