#pragma once
// The energy the arm holds, counted the way the tank counts what it pays for: kinetic energy from
// the plant (MuJoCo's mass matrix, rotor armature included: 1/2 dq^T M dq via mj_mulM) plus the
// controller's springs with the gains the law reads this cycle (Controller::lawBus()):
// 1/2 e^T R K R^T e for the translational and rotational blocks, with e the TCP error of the
// controller's kinematics at the measured joints and R the task frame, and 1/2 sum k_i e_i^2 for
// the nullspace spring. Gravity is compensated by the controller, so its potential is left out;
// the soft-limit springs act only near a joint limit and are left out too.

#include <mujoco/mujoco.h>

#include <vector>

#include "comply/core/state.hpp"
#include "comply/model/data.hpp"
#include "comply/pipeline/controller.hpp"
#include "comply/sim/simulated_robot.hpp"

namespace comply::experiments::passivity {

/// 1/2 e^T R K R^T e [J]: a spring of row-major stiffness K in the task frame R, stretched by e
/// (base frame).
double taskSpringEnergy(const double* stiffness_row_major, const Eigen::Quaterniond& task_frame,
                        const Eigen::Vector3d& error);

class EnergyMeter {
 public:
  EnergyMeter(const pipeline::Controller& controller, const sim::SimulatedRobot& plant);

  /// Takes the pose of the controller's kinematics at `position` (measured joints); the springs
  /// are then evaluated at it.
  void measure(const JointVector& position);
  /// The springs of `law` at the measured pose [J]. Two buses at one pose differ by what their
  /// change of gains put into the springs.
  [[nodiscard]] double springEnergy(const comply_cartesian_command& law) const;
  /// The plant's kinetic energy now [J].
  [[nodiscard]] double kineticEnergy();

 private:
  const pipeline::Controller& controller_;
  const sim::SimulatedRobot& plant_;
  model::Data pose_;
  JointVector position_;
  std::vector<mjtNum> momentum_;
};

}  // namespace comply::experiments::passivity
