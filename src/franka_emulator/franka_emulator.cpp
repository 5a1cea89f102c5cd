// The emulated Franka robot: construction, and the calls from outside its cycle
// (franka_emulator.hpp).

#include "comply/franka_emulator/franka_emulator.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "comply/core/realtime_scheduling.hpp"
#include "comply/franka/franka_arm.hpp"
#include "comply/model/update.hpp"
#include "emulator_impl.hpp"

namespace comply::franka {
namespace {

sim::PlantOptions plantOptions(const FrankaEmulatorOptions& options) {
  sim::PlantOptions plant;
  plant.control_period_s = 0.001;
  plant.substeps = 1;
  plant.actuation = OutputMode::kJointPd;  // torques, and the robot's joint impedance
  plant.link_side_torque = true;           // the joints' torque sensors
  plant.scene = options.scene;
  return plant;
}

}  // namespace

FrankaEmulator::Impl::Impl(const FrankaEmulatorOptions& options)
    : options_(options),
      robot_(model::loadRobotDescription(options.robot)),
      model_(robot_.loadModel()),
      model_data_(model_) {
  if (robot_.joints.size() != 7) {
    throw std::runtime_error("the Franka emulator needs a 7-joint arm; '" + options.robot +
                             "' has " + std::to_string(robot_.joints.size()));
  }
  if (options.lost_in_a_row_limit < 1) {
    throw std::runtime_error("lost_in_a_row_limit must be at least 1");
  }
  collision_ = frankaCollisionThresholds(options.collision_torque_n_m, options.collision_force_n);
  plant_ = std::make_unique<sim::SimulatedRobot>(robot_, plantOptions(options));
  const std::vector<double> home(robot_.home.begin(), robot_.home.end());
  plant_->setJointPositions(home);
  measured_ = JointState::zero(7);
  plant_->read(measured_);
  // The joint impedance's damping: critical for each joint's own inertia at home.
  updateModel(model::Quantity::kMassMatrix | model::Quantity::kPose | model::Quantity::kGravity);
  for (int joint = 0; joint < 7; ++joint) {
    const auto j = static_cast<std::size_t>(joint);
    joint_damping_[j] =
        2.0 * std::sqrt(joint_stiffness_[j] * model_data_.mass_matrix(joint, joint));
  }
  listen();
  server_thread_ = std::jthread([this](const std::stop_token& stop) { serve(stop); });
  cycle_thread_ = std::jthread([this](const std::stop_token& stop) {
    (void)makeThreadRealtime(options_.priority);
    runCycles(stop);
  });
}

FrankaEmulator::Impl::~Impl() {
  cycle_thread_ = {};
  server_thread_ = {};
  if (listener_ >= 0) {
    ::close(listener_);
  }
  if (udp_ >= 0) {
    ::close(udp_);
  }
}

void FrankaEmulator::Impl::reflex(int error_index) {
  if (error_index < 0 || error_index >= fci::kErrorCount) {
    throw std::invalid_argument("no robot error " + std::to_string(error_index));
  }
  const std::lock_guard lock(mutex_);
  enterReflex(error_index);
}

void FrankaEmulator::Impl::loseCommands(int count) {
  const std::lock_guard lock(mutex_);
  lose_ += std::max(0, count);
}

void FrankaEmulator::Impl::dropStates(int count) {
  const std::lock_guard lock(mutex_);
  drop_ += std::max(0, count);
}

void FrankaEmulator::Impl::push(const Vector6d& wrench) {
  const std::lock_guard lock(mutex_);
  push_ = wrench;
}

FrankaEmulatorStats FrankaEmulator::Impl::stats() const {
  const std::lock_guard lock(mutex_);
  FrankaEmulatorStats stats = stats_;
  stats.collision = collision_;
  return stats;
}

FrankaEmulatorState FrankaEmulator::Impl::state() const {
  const std::lock_guard lock(mutex_);
  FrankaEmulatorState state;
  state.mode = mode_;
  state.torque_control = motion_ && motion_->controller == fci::MoveController::kExternal;
  state.position = measured_.position;
  state.tcp = plant_->tcpPose();
  state.contact_wrench = plant_->toolContactWrench();
  state.time_ms = time_ms_;
  return state;
}

void FrankaEmulator::Impl::withPlant(const std::function<void(sim::SimulatedRobot&)>& edit) {
  const std::lock_guard lock(mutex_);
  edit(*plant_);
}

FrankaEmulator::FrankaEmulator(const FrankaEmulatorOptions& options)
    : impl_(std::make_unique<Impl>(options)) {}
FrankaEmulator::~FrankaEmulator() = default;
std::uint16_t FrankaEmulator::commandPort() const noexcept {
  return impl_->commandPort();
}
void FrankaEmulator::reflex(int error_index) {
  impl_->reflex(error_index);
}
void FrankaEmulator::loseCommands(int count) {
  impl_->loseCommands(count);
}
void FrankaEmulator::dropStates(int count) {
  impl_->dropStates(count);
}
void FrankaEmulator::push(const Vector6d& wrench) {
  impl_->push(wrench);
}
void FrankaEmulator::closeConnection() {
  impl_->closeConnection();
}
FrankaEmulatorStats FrankaEmulator::stats() const {
  return impl_->stats();
}
FrankaEmulatorState FrankaEmulator::state() const {
  return impl_->state();
}
void FrankaEmulator::withPlant(const std::function<void(sim::SimulatedRobot&)>& edit) {
  impl_->withPlant(edit);
}

}  // namespace comply::franka
