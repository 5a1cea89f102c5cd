#pragma once
// Shared plumbing of the control-law tests: loading the plugins, packing comply_input from a model
// update (or from hand-written values), and reading torques back as Eigen vectors. The laws
// themselves are recomputed in each test, never here.

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <initializer_list>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "bus_values.hpp"
#include "comply/model/data.hpp"
#include "comply/model/model.hpp"
#include "comply/model/robot_description.hpp"
#include "comply/model/update.hpp"
#include "comply/plugin/abi.h"
#include "comply/plugin/loader.hpp"

namespace comply::law_test {

using Matrix6d = Eigen::Matrix<double, 6, 6>;
using Vector6d = Eigen::Matrix<double, 6, 1>;
using Matrix6Xd = Eigen::Matrix<double, 6, Eigen::Dynamic>;

inline std::shared_ptr<const plugin::PluginLibrary> jointImpedanceLibrary() {
  return std::make_shared<const plugin::PluginLibrary>(COMPLY_TEST_JOINT_IMPEDANCE,
                                                       COMPLY_COMMAND_JOINT);
}

inline std::shared_ptr<const plugin::PluginLibrary> cartesianImpedanceLibrary() {
  return std::make_shared<const plugin::PluginLibrary>(COMPLY_TEST_CARTESIAN_IMPEDANCE,
                                                       COMPLY_COMMAND_CARTESIAN);
}

/// One numeric parameter, as a controller configuration would hand it over.
inline plugin::ParameterMap numberParameter(const std::string& name, double value) {
  plugin::ParameterMap parameters;
  parameters[name].numbers = {value};
  return parameters;
}

/// Runs one step and returns the first `dof` torques; throws (failing the test) with the plugin's
/// message when the law errors. Entries past `dof` are pre-filled with NaN and must stay so: a law
/// must not write torques for joints it does not control.
inline Eigen::VectorXd stepTorque(plugin::PluginInstance& instance, const comply_input& input,
                                  const void* command) {
  comply_output output{};
  for (double& torque : output.torque) {
    torque = std::numeric_limits<double>::quiet_NaN();
  }
  if (instance.step(input, command, output) != COMPLY_OK) {
    output.message[COMPLY_MESSAGE_CAPACITY - 1] = '\0';
    throw std::runtime_error(std::string("step failed: ") + output.message);
  }
  for (int i = instance.dof(); i < COMPLY_MAX_DOF; ++i) {
    EXPECT_TRUE(std::isnan(output.torque[i])) << "torque written past dof at index " << i;
  }
  return Eigen::Map<const Eigen::VectorXd>(output.torque, instance.dof());
}

inline void writeXyzw(const Eigen::Quaterniond& q, double* xyzw) {
  xyzw[0] = q.x();
  xyzw[1] = q.y();
  xyzw[2] = q.z();
  xyzw[3] = q.w();
}

/// Writes a 3x3 gain block in the command's row-major layout.
inline void writeRowMajor(const Eigen::Matrix3d& block, double* values) {
  for (int row = 0; row < 3; ++row) {
    for (int col = 0; col < 3; ++col) {
      values[row * 3 + col] = block(row, col);
    }
  }
}

/// Writes a 6 x dof Jacobian column-major with leading dimension 6.
inline void writeJacobian(const Matrix6Xd& jacobian, comply_input& input) {
  for (Eigen::Index col = 0; col < jacobian.cols(); ++col) {
    for (Eigen::Index row = 0; row < 6; ++row) {
      input.jacobian[col * 6 + row] = jacobian(row, col);
    }
  }
}

inline Matrix6Xd jacobianOf(const comply_input& input) {
  return Eigen::Map<const Matrix6Xd>(input.jacobian, 6, input.dof);
}

inline Eigen::MatrixXd massMatrixOf(const comply_input& input) {
  return Eigen::Map<const Eigen::MatrixXd, 0, Eigen::OuterStride<>>(
      input.mass_matrix, input.dof, input.dof, Eigen::OuterStride<>(COMPLY_MAX_DOF));
}

inline Eigen::Vector3d tcpPositionOf(const comply_input& input) {
  return Eigen::Map<const Eigen::Vector3d>(input.tcp_position);
}

inline Eigen::Quaterniond tcpOrientationOf(const comply_input& input) {
  return {input.tcp_orientation[3], input.tcp_orientation[0], input.tcp_orientation[1],
          input.tcp_orientation[2]};
}

/// Measured state plus pose, Jacobian and mass matrix from one model update at (q, dq).
inline comply_input inputFromModel(const model::Model& model, const std::vector<double>& q,
                                   const std::vector<double>& dq) {
  model::Data data(model);
  const auto status = model::update(
      model, data, q, dq,
      model::Quantity::kPose | model::Quantity::kJacobian | model::Quantity::kMassMatrix);
  if (status != model::UpdateStatus::kOk) {
    throw std::runtime_error("model update failed");
  }
  comply_input input{};
  input.dof = model.dof();
  input.available = COMPLY_NEED_POSE | COMPLY_NEED_JACOBIAN | COMPLY_NEED_MASS_MATRIX;
  input.period_s = 0.001;
  for (int i = 0; i < model.dof(); ++i) {
    input.position[i] = q[static_cast<std::size_t>(i)];
    input.velocity[i] = dq[static_cast<std::size_t>(i)];
  }
  for (int row = 0; row < 3; ++row) {
    input.tcp_position[row] = data.tip_position[row];
  }
  writeXyzw(data.tip_orientation, input.tcp_orientation);
  writeJacobian(data.jacobian, input);
  for (int col = 0; col < model.dof(); ++col) {
    for (int row = 0; row < model.dof(); ++row) {
      input.mass_matrix[col * COMPLY_MAX_DOF + row] = data.mass_matrix(row, col);
    }
  }
  return input;
}

/// A command that holds the TCP where `input` has it: zero gains everywhere, identity task frame,
/// absolute damping. Tests switch on only the terms they examine.
inline comply_cartesian_command holdCommand(const comply_input& input) {
  comply_cartesian_command command{};
  command.fields = COMPLY_FIELD_POSITION | COMPLY_FIELD_VELOCITY | COMPLY_FIELD_STIFFNESS |
                   COMPLY_FIELD_DAMPING | COMPLY_FIELD_TASK_FRAME |
                   COMPLY_FIELD_WRENCH_FEEDFORWARD | COMPLY_FIELD_TORQUE_FEEDFORWARD |
                   COMPLY_FIELD_NULLSPACE;
  command.dof = input.dof;
  for (int row = 0; row < 3; ++row) {
    command.position[row] = input.tcp_position[row];
  }
  for (int k = 0; k < 4; ++k) {
    command.orientation[k] = input.tcp_orientation[k];
  }
  command.damping_mode = COMPLY_DAMPING_ABSOLUTE;
  writeXyzw(Eigen::Quaterniond::Identity(), command.task_frame);
  for (int i = 0; i < input.dof; ++i) {
    command.nullspace_position[i] = input.position[i];
  }
  return command;
}

/// The FR3 (base to TCP) and its home pose from robots/fr3/robot.yaml.
struct Fr3 {
  model::RobotDescription robot = model::loadRobotDescription("fr3");
  model::Model model = robot.loadModel();

  [[nodiscard]] comply_input inputAtHome(const std::vector<double>& dq = {}) const {
    return inputFromModel(model, robot.home,
                          dq.empty() ? std::vector<double>(robot.home.size(), 0.0) : dq);
  }
};

/// Wrench w with J^T w = tau in the least-squares sense (exact when tau lies in the range of J^T,
/// which holds whenever the nullspace term is off).
inline Vector6d wrenchFromTorque(const Matrix6Xd& jacobian, const Eigen::VectorXd& torque) {
  return jacobian.transpose().colPivHouseholderQr().solve(torque);
}

/// |a - b| / max(|b|, floor): a relative error that stays meaningful when b is tiny.
inline double relativeError(const Eigen::VectorXd& actual, const Eigen::VectorXd& expected,
                            double floor = 1e-12) {
  return (actual - expected).norm() / std::max(expected.norm(), floor);
}

/// The Cartesian impedance law with default parameters and its input at the FR3's home pose.
class CartesianLawAtHome : public ::testing::Test {
 protected:
  Fr3 fr3_;
  comply_input input_ = fr3_.inputAtHome();
  plugin::PluginInstance law_{cartesianImpedanceLibrary(), fr3_.model.dof(), {}};
};

}  // namespace comply::law_test
