// `comply validate` end to end through its library entry points: the model quantities it writes
// agree with KDL, the law's torque agrees with the joint impedance formula, and every malformed
// input is refused with a message naming the sample and the field.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>

#include "command_json.hpp"
#include "comply/model/robot_description.hpp"
#include "kdl_reference.hpp"
#include "validate_command.hpp"

namespace comply::app {
namespace {

using nlohmann::json;

class ValidateTest : public ::testing::Test {
 protected:
  std::string writeJson(const std::string& name, const json& document) {
    const std::filesystem::path path =
        std::filesystem::path(::testing::TempDir()) / (std::to_string(::getpid()) + "_" + name);
    std::ofstream(path) << document.dump();
    return path.string();
  }

  static json homeSample(const json& command = json::object()) {
    const model::RobotDescription fr3 = model::loadRobotDescription("fr3");
    return {{"q", fr3.home}, {"dq", std::vector<double>(7, 0.0)}, {"command", command}};
  }

  ValidateOptions options(const std::string& plugin, const std::string& inputs) {
    ValidateOptions result;
    result.robot = "fr3";
    result.plugin = plugin;
    result.inputs = inputs;
    return result;
  }
};

std::vector<double> flat(const json& value) {
  std::vector<double> out;
  for (const json& row : value) {
    if (row.is_array()) {
      for (const json& entry : row) {
        out.push_back(entry.get<double>());
      }
    } else {
      out.push_back(row.get<double>());
    }
  }
  return out;
}

TEST_F(ValidateTest, ModelQuantitiesAgreeWithKdl) {
  const model::RobotDescription fr3 = model::loadRobotDescription("fr3");
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> offset(-0.5, 0.5);
  json samples = json::array();
  for (int s = 0; s < 20; ++s) {
    std::vector<double> q = fr3.home;
    std::vector<double> dq(7);
    for (int i = 0; i < 7; ++i) {
      q[static_cast<std::size_t>(i)] += offset(rng);
      dq[static_cast<std::size_t>(i)] = offset(rng);
    }
    samples.push_back({{"q", q}, {"dq", dq}});
  }
  const json output =
      runValidation(options("cartesian_impedance", writeJson("kdl.json", {{"samples", samples}})));

  const testing::KdlReference kdl(fr3.urdf_path.string(), fr3.base_frame, fr3.tcp_frame,
                                  fr3.joints);
  double worst = 0.0;
  for (std::size_t s = 0; s < samples.size(); ++s) {
    const Eigen::VectorXd q =
        Eigen::Map<const Eigen::VectorXd>(samples[s]["q"].get<std::vector<double>>().data(), 7);
    const Eigen::VectorXd dq =
        Eigen::Map<const Eigen::VectorXd>(samples[s]["dq"].get<std::vector<double>>().data(), 7);
    testing::ReferenceResult reference = kdl.compute(q, dq);
    // The controller's M(q) carries the rotor inertias robot.yaml declares.
    for (int i = 0; i < 7; ++i) {
      reference.mass_matrix(i, i) += fr3.joint_dynamics->armature[static_cast<std::size_t>(i)];
    }
    const json& out = output["samples"][s];
    const auto compare = [&worst](const std::vector<double>& got, const double* want, int n) {
      ASSERT_EQ(static_cast<int>(got.size()), n);
      for (int k = 0; k < n; ++k) {
        worst = std::max(worst, std::abs(got[static_cast<std::size_t>(k)] - want[k]));
      }
    };
    compare(flat(out["tcp_position"]), reference.position.data(), 3);
    compare(flat(out["gravity"]), reference.gravity.data(), 7);
    compare(flat(out["coriolis"]), reference.coriolis.data(), 7);
    // Written row by row; the references are column-major.
    const Eigen::Matrix<double, 6, 7, Eigen::RowMajor> jacobian = reference.jacobian;
    compare(flat(out["jacobian"]), jacobian.data(), 42);
    const Eigen::Matrix<double, 7, 7, Eigen::RowMajor> mass = reference.mass_matrix;
    compare(flat(out["mass_matrix"]), mass.data(), 49);
    ASSERT_TRUE(out.contains("torque")) << out.dump();
  }
  EXPECT_LT(worst, 1e-9);
}

TEST_F(ValidateTest, JointLawTorqueFollowsTheFormula) {
  const model::RobotDescription fr3 = model::loadRobotDescription("fr3");
  std::vector<double> target = fr3.home;
  target[3] += 0.1;
  const json command = {{"position", target},
                        {"stiffness", std::vector<double>(7, 200.0)},
                        {"damping", std::vector<double>(7, 20.0)},
                        {"torque_feedforward", {0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.5}}};
  json sample = homeSample(command);
  sample["dq"] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.5, 0.0};
  const json output =
      runValidation(options("joint_impedance", writeJson("joint.json", json::array({sample}))));
  const std::vector<double> torque = flat(output["samples"][0]["torque"]);
  ASSERT_EQ(torque.size(), 7U);
  EXPECT_NEAR(torque[3], 200.0 * 0.1, 1e-12);
  EXPECT_NEAR(torque[5], -20.0 * 0.5, 1e-12);
  EXPECT_NEAR(torque[6], 1.5, 1e-12);
  EXPECT_NEAR(torque[0], 0.0, 1e-12);
}

TEST_F(ValidateTest, ExpectedOutputsAreComparedPerKey) {
  const std::string inputs = writeJson("cmp.json", json::array({homeSample()}));
  json output = runValidation(options("cartesian_impedance", inputs));
  json expected = output;
  expected["samples"][0]["gravity"][2] = expected["samples"][0]["gravity"][2].get<double>() + 0.25;
  const std::map<std::string, double> errors = compareOutputs(output, expected);
  EXPECT_NEAR(errors.at("gravity"), 0.25, 1e-12);
  EXPECT_EQ(errors.at("torque"), 0.0);

  ValidateOptions with_expected = options("cartesian_impedance", inputs);
  with_expected.expected = writeJson("expected.json", expected);
  std::ostringstream out;
  std::ostringstream err;
  EXPECT_EQ(validateCommand(with_expected, out, err), 1);
  EXPECT_NE(out.str().find("gravity"), std::string::npos);
  with_expected.tolerance = 0.3;
  EXPECT_EQ(validateCommand(with_expected, out, err), 0);
}

TEST_F(ValidateTest, NonFiniteOutputsNeverMatch) {
  // std::max drops a NaN error: a plugin returning NaN used to match any expected torque.
  const std::string inputs = writeJson("nan.json", json::array({homeSample()}));
  const json output = runValidation(options("cartesian_impedance", inputs));
  json nan_output = output;
  nan_output["samples"][0]["torque"][1] = std::nan("");
  EXPECT_TRUE(std::isinf(compareOutputs(nan_output, output).at("torque")));
  EXPECT_TRUE(std::isinf(compareOutputs(output, nan_output).at("torque")));
  json infinite = output;
  infinite["samples"][0]["gravity"][0] = std::numeric_limits<double>::infinity();
  EXPECT_TRUE(std::isinf(compareOutputs(infinite, infinite).at("gravity")));
  EXPECT_EQ(compareOutputs(output, output).at("torque"), 0.0);
}

TEST_F(ValidateTest, UnknownOutputInExpectedIsAnError) {
  json output = runValidation(
      options("cartesian_impedance", writeJson("u.json", json::array({homeSample()}))));
  json expected = output;
  expected["samples"][0]["torques"] = {1.0};
  EXPECT_THROW(compareOutputs(output, expected), InputError);
}

void expectInputError(const ValidateOptions& validate, const std::string& needle) {
  try {
    runValidation(validate);
    FAIL() << "accepted input that should name '" << needle << "'";
  } catch (const std::exception& error) {
    EXPECT_NE(std::string(error.what()).find(needle), std::string::npos) << error.what();
  }
}

TEST_F(ValidateTest, MoreSamplesThanTheLimitAreRefused) {
  json many = json::array();
  for (std::size_t i = 0; i <= kMaxValidateSamples; ++i) {
    many.push_back(json::object());
  }
  expectInputError(options("joint_impedance", writeJson("many.json", many)),
                   "more than 100000 (split it)");
}

TEST_F(ValidateTest, MalformedInputsNameTheField) {
  json unknown_sample_field = homeSample();
  unknown_sample_field["qd"] = {0.0};
  expectInputError(
      options("cartesian_impedance", writeJson("e1.json", json::array({unknown_sample_field}))),
      "unknown field 'qd'");

  json missing_dq = homeSample();
  missing_dq.erase("dq");
  expectInputError(options("cartesian_impedance", writeJson("e2.json", json::array({missing_dq}))),
                   "missing field 'dq'");

  json short_q = homeSample();
  short_q["q"] = {0.0, 0.0};
  expectInputError(options("cartesian_impedance", writeJson("e3.json", json::array({short_q}))),
                   "'q' has 2 entries");

  expectInputError(options("cartesian_impedance",
                           writeJson("e4.json", json::array({homeSample(json{{"stifness", 1}})}))),
                   "unknown command field 'stifness'");

  expectInputError(
      options("cartesian_impedance",
              writeJson("e5.json", json::array({homeSample(json{{"position", {0.1, 0.2}}})}))),
      "'position' has 2 numbers");

  expectInputError(options("cartesian_impedance", writeJson("e6.json", json::array())),
                   "holds no samples");
}

TEST(CommandJson, FieldMaskFollowsKeysOrTheFieldsList) {
  const CartesianCommand base = CartesianCommand::zero(7);
  const CartesianCommand gains_only = commandFromJson(
      json{{"stiffness_translational", {100, 0, 0, 0, 200, 0, 0, 0, 300}}}, 7, base);
  EXPECT_EQ(gains_only.fields, CommandField::kStiffness);
  EXPECT_EQ(gains_only.stiffness_translational(1, 1), 200.0);
  // The other block of the group keeps the base value.
  EXPECT_EQ(gains_only.stiffness_rotational, base.stiffness_rotational);

  const CartesianCommand listed =
      commandFromJson(json{{"fields", {"position", "task_frame"}}}, 7, base);
  EXPECT_EQ(listed.fields, CommandField::kPosition | CommandField::kTaskFrame);

  const CartesianCommand row_major = commandFromJson(
      json{{"stiffness_translational", {{1, 2, 3}, {4, 5, 6}, {7, 8, 9}}}}, 7, base);
  EXPECT_EQ(row_major.stiffness_translational(0, 1), 2.0);
  EXPECT_EQ(row_major.stiffness_translational(1, 0), 4.0);

  EXPECT_THROW(commandFromJson(json{{"fields", {"pose"}}}, 7, base), CommandJsonError);
  EXPECT_THROW(commandFromJson(json{{"damping_mode", "critical"}}, 7, base), CommandJsonError);
}

}  // namespace
}  // namespace comply::app
