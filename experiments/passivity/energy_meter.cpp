#include "passivity/energy_meter.hpp"

#include <span>
#include <stdexcept>

#include "comply/core/rotation.hpp"
#include "comply/model/update.hpp"
#include "comply/schema/schema.hpp"

namespace comply::experiments::passivity {
double taskSpringEnergy(const double* stiffness_row_major, const Eigen::Quaterniond& task_frame,
                        const Eigen::Vector3d& error) {
  const Eigen::Vector3d in_task = task_frame.conjugate() * error;
  return 0.5 * in_task.dot(Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(
                               stiffness_row_major) *
                           in_task);
}

EnergyMeter::EnergyMeter(const pipeline::Controller& controller, const sim::SimulatedRobot& plant)
    : controller_(controller),
      plant_(plant),
      pose_(controller.model()),
      momentum_(static_cast<std::size_t>(plant.mujocoModel().nv)) {}

void EnergyMeter::measure(const JointVector& position) {
  position_ = position;
  const std::span<const double> q(position_.data(), static_cast<std::size_t>(position_.size()));
  if (model::update(controller_.model(), pose_, q, q, model::Quantity::kPose) !=
      model::UpdateStatus::kOk) {
    throw std::runtime_error("passivity: the controller's kinematics failed at a measured pose");
  }
}

double EnergyMeter::springEnergy(const comply_cartesian_command& law) const {
  const Eigen::Quaterniond frame = schema::fromXyzw(law.task_frame).normalized();
  const Eigen::Vector3d position_error =
      pose_.tip_position - Eigen::Vector3d(law.position[0], law.position[1], law.position[2]);
  const Eigen::Vector3d orientation_error =
      orientationError(pose_.tip_orientation, schema::fromXyzw(law.orientation).normalized());
  double energy = taskSpringEnergy(law.stiffness_translational, frame, position_error) +
                  taskSpringEnergy(law.stiffness_rotational, frame, orientation_error);
  for (Eigen::Index i = 0; i < position_.size(); ++i) {
    const double error = law.nullspace_position[i] - position_[i];
    energy += 0.5 * law.nullspace_stiffness[i] * error * error;
  }
  return energy;
}

double EnergyMeter::kineticEnergy() {
  const mjModel& model = plant_.mujocoModel();
  const mjData& data = plant_.mujocoData();
  mj_mulM(&model, &data, momentum_.data(), data.qvel);
  return 0.5 * mju_dot(data.qvel, momentum_.data(), model.nv);
}

}  // namespace comply::experiments::passivity
