#include "comply/pipeline/execution_core.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "comply/model/robot_description.hpp"
#include "comply/pipeline/compensation.hpp"
#include "comply/pipeline/plugin_input.hpp"

namespace comply::pipeline {
namespace {

using model::Quantity;

JointVector toJointVector(const std::vector<double>& values) {
  JointVector result(static_cast<Eigen::Index>(values.size()));
  for (std::size_t i = 0; i < values.size(); ++i) {
    result[static_cast<Eigen::Index>(i)] = values[i];
  }
  return result;
}

bool usable(const JointState& state, int dof) {
  return state.position.size() == dof && state.velocity.size() == dof &&
         state.effort.size() == dof && state.position.allFinite() && state.velocity.allFinite();
}

}  // namespace

ExecutionCore::ExecutionCore(const WrapperConfig& config, int command_kind) : config_(config) {
  const model::RobotDescription robot = model::loadRobotDescription(config_.robot);
  model::ModelOptions options = robot.modelOptions(config_.tip_frame);
  options.joint_names = config_.joints;
  options.base_frame = config_.base_frame;
  model_ = std::make_unique<model::Model>(model::Model::fromUrdfFile(robot.urdf_path, options));
  data_ = std::make_unique<model::Data>(*model_);
  data_->payload = config_.payload;
  dof_ = model_->dof();
  if (dof_ != config_.dof) {
    throw std::runtime_error(config_.name + ": the model has " + std::to_string(dof_) +
                             " joints but the configuration lists " + std::to_string(config_.dof));
  }

  auto library = std::make_shared<const plugin::PluginLibrary>(config_.plugin, command_kind);
  plugin_ =
      std::make_unique<plugin::PluginInstance>(std::move(library), dof_, config_.plugin_parameters);
  // The pose is always computed (validation and re-anchoring need it) and gravity too (the FAULT
  // state holds the arm against it even when gravity compensation is off).
  quantities_ = quantitiesFor(plugin_->requiredQuantities()) | Quantity::kPose | Quantity::kGravity;
  if (config_.payload_compensation) {
    quantities_ = quantities_ | Quantity::kPayloadGravity;
  }

  lower_limit_.resize(dof_);
  upper_limit_.resize(dof_);
  effort_limit_.resize(dof_);
  for (int i = 0; i < dof_; ++i) {
    const model::JointLimits& limits = model_->limits(i);
    lower_limit_[i] = limits.lower;
    upper_limit_[i] = limits.upper;
    effort_limit_[i] = config_.effort_limit.empty() ? limits.effort : config_.effort_limit[i];
    if (!(effort_limit_[i] > 0.0)) {
      throw std::runtime_error(config_.name + ": joint '" + config_.joints[i] +
                               "' has no effort limit in the URDF; set effort_limit_nm");
    }
  }
  fault_damping_ = toJointVector(config_.fault_damping);
  shaper_ = std::make_unique<TorqueShaper>(
      ShapingLimits{config_.filter_alpha, toJointVector(config_.torque_rate_limit), effort_limit_});

  state_.position.setZero(dof_);
  state_.velocity.setZero(dof_);
  state_.effort.setZero(dof_);
  torque_.setZero(dof_);
  scratch_.setZero(dof_);
  input_.dof = dof_;
}

ExecutionCore::~ExecutionCore() = default;

MeasuredPose ExecutionCore::measuredPose() {
  measured_.update();
  return measured_.read();
}

bool ExecutionCore::computeModel(const JointState& state) noexcept {
  const std::span<const double> q(state.position.data(), static_cast<std::size_t>(dof_));
  const std::span<const double> dq(state.velocity.data(), static_cast<std::size_t>(dof_));
  return model::update(*model_, *data_, q, dq, quantities_) == model::UpdateStatus::kOk;
}

MeasuredPose ExecutionCore::currentPose() const noexcept {
  return measuredPoseFrom(state_.position, *data_);
}

MeasuredPose ExecutionCore::prepareActivation(const JointState& state) {
  if (!usable(state, dof_)) {
    throw std::runtime_error(config_.name + ": activation needs a finite joint state with " +
                             std::to_string(dof_) + " positions, velocities and efforts");
  }
  if (!computeModel(state)) {
    throw std::runtime_error(config_.name + ": the model could not be evaluated at this state");
  }
  state_ = state;
  fillInput(period_s_);
  return currentPose();
}

void ExecutionCore::activate(const void* command) {
  input_.time_s = 0.0;
  if (plugin_->activate(input_) != COMPLY_OK) {
    throw plugin::PluginError(plugin::PluginErrc::kTrialStepFailed,
                              plugin_->library().path().string() + ": activate() failed");
  }
  plugin_->trialStep(input_, command);
  // Start the rate limit from what the joints carry now, so the first torque does not jump.
  if (state_.effort.allFinite()) {
    shaper_->reset(state_.effort);
  } else {
    shaper_->reset(data_->gravity);
  }
  time_s_ = 0.0;
  last_command_time_s_ = 0.0;
  watchdog_expired_ = false;
  reset_requested_.store(false);
  measured_.publishFromSoleWriter(currentPose());  // the cycle is not running during activation
  diagnostics_.state.store(WrapperState::kActive);
}

void ExecutionCore::deactivate() noexcept {
  diagnostics_.state.store(WrapperState::kInactive);
}

void ExecutionCore::fillInput(double period_s) noexcept {
  fillPluginInput(state_, *data_, quantities_, time_s_, period_s, input_);
}

void ExecutionCore::beginCycle(const JointState& state, double period_s) noexcept {
  diagnostics_.cycles.fetch_add(1, std::memory_order_relaxed);
  if (std::isfinite(period_s) && period_s > 0.0) {
    period_s_ = period_s;
  }
  time_s_ += period_s_;
  state_usable_ = false;
  const WrapperState current = diagnostics_.state.load(std::memory_order_relaxed);
  if (current == WrapperState::kInactive) {
    return;
  }
  if (!usable(state, dof_)) {
    enterFault("state: ", "joint state of the wrong size or with NaN/inf position or velocity");
    return;
  }
  if (!computeModel(state)) {
    enterFault("model: ", "update failed");
    return;
  }
  state_ = state;
  state_usable_ = true;
  fillInput(period_s_);
  measured_.publishFromSoleWriter(currentPose());
}

void ExecutionCore::enterFault(const char* prefix, const char* detail) noexcept {
  if (diagnostics_.state.load(std::memory_order_relaxed) != WrapperState::kFault) {
    diagnostics_.faults.fetch_add(1, std::memory_order_relaxed);
    diagnostics_.setError(prefix, detail);
  }
  diagnostics_.state.store(WrapperState::kFault, std::memory_order_relaxed);
}

CycleStatus ExecutionCore::writeSafeTorque(std::span<double> torque) noexcept {
  // Hold the arm against gravity (and the payload) and damp every joint: the arm comes to rest
  // where it is, without a reference that may be the cause of the fault.
  for (int i = 0; i < dof_; ++i) {
    torque_[i] = data_->gravity[i] - fault_damping_[i] * state_.velocity[i];
  }
  if (config_.payload_compensation) {
    torque_ += data_->payload_gravity.head(dof_);
  }
  const ShapingResult shaped = shaper_->apply(torque_, period_s_, /*filter=*/false);
  diagnostics_.rate_limit_hits.fetch_add(shaped.rate_limited, std::memory_order_relaxed);
  diagnostics_.effort_limit_hits.fetch_add(shaped.effort_limited, std::memory_order_relaxed);
  for (int i = 0; i < dof_ && i < static_cast<int>(torque.size()); ++i) {
    torque[i] = torque_[i];
  }
  return CycleStatus::kFault;
}

void ExecutionCore::addCompensation() noexcept {
  if (config_.gravity_compensation) {
    torque_ += data_->gravity.head(dof_);
  }
  if (config_.payload_compensation) {
    torque_ += data_->payload_gravity.head(dof_);
  }
  if (config_.friction.model != FrictionModel::kNone) {
    frictionTorque(config_.friction, state_.velocity, scratch_);
    torque_ += scratch_;
  }
  if (config_.soft_limits.enabled) {
    softLimitTorque(config_.soft_limits, lower_limit_, upper_limit_, state_.position,
                    state_.velocity, scratch_);
    torque_ += scratch_;
  }
}

CycleStatus ExecutionCore::finishCycle(const void* command, std::span<double> torque) noexcept {
  switch (diagnostics_.state.load(std::memory_order_relaxed)) {
    case WrapperState::kInactive:
      return CycleStatus::kInactive;
    case WrapperState::kFault:
      // Consumed either way: a reset refused for a bad state is not carried over to a later cycle.
      if (!reset_requested_.exchange(false) || !state_usable_) {
        return writeSafeTorque(torque);
      }
      diagnostics_.state.store(WrapperState::kActive, std::memory_order_relaxed);
      break;
    case WrapperState::kActive:
      break;
  }
  if (static_cast<int>(torque.size()) < dof_) {
    enterFault("output: ", "torque buffer smaller than the number of joints");
    return CycleStatus::kFault;
  }

  output_.message[0] = '\0';
  if (plugin_->step(input_, command, output_) != COMPLY_OK) {
    enterFault("plugin: ", output_.message[0] != '\0' ? output_.message : "step failed");
    return writeSafeTorque(torque);
  }
  for (int i = 0; i < dof_; ++i) {
    torque_[i] = output_.torque[i];
  }
  if (!torque_.allFinite()) {
    enterFault("plugin: ", "non-finite torque");
    return writeSafeTorque(torque);
  }
  addCompensation();
  const ShapingResult shaped = shaper_->apply(torque_, period_s_);
  if (!shaped.finite) {
    enterFault("shaping: ", "non-finite torque after compensation and filtering");
    return writeSafeTorque(torque);
  }
  diagnostics_.rate_limit_hits.fetch_add(shaped.rate_limited, std::memory_order_relaxed);
  diagnostics_.effort_limit_hits.fetch_add(shaped.effort_limited, std::memory_order_relaxed);
  for (int i = 0; i < dof_; ++i) {
    torque[i] = torque_[i];
  }
  return CycleStatus::kOk;
}

void ExecutionCore::noteCommand() noexcept {
  last_command_time_s_ = time_s_;
  watchdog_expired_ = false;
}

bool ExecutionCore::watchdogFired() noexcept {
  if (watchdog_expired_ || config_.command_timeout_s <= 0.0 ||
      time_s_ - last_command_time_s_ < config_.command_timeout_s) {
    return false;
  }
  watchdog_expired_ = true;
  diagnostics_.watchdog_timeouts.fetch_add(1, std::memory_order_relaxed);
  return true;
}

}  // namespace comply::pipeline
