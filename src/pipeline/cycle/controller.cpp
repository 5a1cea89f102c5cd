#include "comply/pipeline/controller.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "comply/pipeline/command_bus.hpp"
#include "comply/pipeline/command_validation.hpp"
#include "comply/pipeline/plugin_input.hpp"

namespace comply::pipeline {
namespace {

using model::Quantity;

CommandBus initialBus(const ResolvedController& resolved) {
  CommandBus bus = resolved.cartesian()
                       ? CommandBus(toBus(resolved.config.initial_cartesian, resolved.dof))
                       : CommandBus(toBus(resolved.config.initial_joint, resolved.dof));
  std::visit([](auto& typed) { typed.fields = static_cast<std::uint32_t>(CommandField::kAll); },
             bus);
  return bus;
}

}  // namespace

Controller::Controller(std::shared_ptr<const ResolvedController> resolved)
    : resolved_(std::move(resolved)),
      parameters_(resolved_->parameters),
      dof_(resolved_->dof),
      data_(*resolved_->model),
      measured_(MeasuredPose{}),
      in_force_(emptyBus(resolved_->command_kind)),
      frozen_(parameters_.frozen_state_timeout_s),
      wrist_(*resolved_),
      guard_(*resolved_),
      active_(initialBus(*resolved_)),
      chunks_(resolved_->command_kind, dof_, parameters_.chunk_blend_time_s),
      watchdog_(parameters_.command_timeout_s),
      sensor_check_(*resolved_),
      reflex_(parameters_.reflex),
      gains_(parameters_.gain_ramps, parameters_.passivity),
      force_bus_(emptyBus(resolved_->command_kind)),
      walls_(parameters_, resolved_->cartesian()),
      walls_bus_(emptyBus(resolved_->command_kind)),
      governor_(*resolved_, resolved_->cartesian()),
      contact_speed_(parameters_, dof_, resolved_->cartesian()),
      shaper_(ShapingLimits{parameters_.filter_alpha, parameters_.torque_rate_limit,
                            parameters_.effort_limit}),
      safe_hold_(parameters_, dof_),
      output_stage_(*resolved_) {
  data_.payload = parameters_.payload;
  plugin_ = std::make_unique<plugin::PluginInstance>(resolved_->plugin, dof_,
                                                     resolved_->config.plugin_parameters);
  // The pose is always computed (validation and re-anchoring need it) and gravity too (the FAULT
  // state holds the arm against it even when gravity compensation is off).
  quantities_ = quantitiesFor(plugin_->requiredQuantities()) | Quantity::kPose | Quantity::kGravity;
  quantities_ = quantities_ | gains_.quantities(resolved_->cartesian());
  if (parameters_.payload_compensation) {
    quantities_ = quantities_ | Quantity::kPayloadGravity;
  }
  // What the output stage reads (output_stage.hpp): the virtual arm's inertia and Jacobian in
  // admittance; the joint-space gains of a Cartesian law for a PD drive (the joint law's are the
  // command's own).
  const OutputMode mode = parameters_.output.mode;
  if (isAdmittance(mode) || (mode == OutputMode::kJointPd && resolved_->cartesian())) {
    quantities_ = quantities_ | Quantity::kMassMatrix | Quantity::kJacobian;
  }
  // The force stage measures the TCP's speed along its axes.
  force_.configure(parameters_.force_control);
  if (resolved_->cartesian()) {
    quantities_ = quantities_ | Quantity::kJacobian;
  }
  // The contact-speed stage's mass along the TCP's motion (contact_speed.hpp).
  if (contact_speed_.enabled()) {
    quantities_ = quantities_ | Quantity::kMassMatrix | Quantity::kJacobian;
  }
  // A joint-torque sensor reads the torque after the rotors: their inertia, in the laws' M(q),
  // is not what that torque accelerates.
  const std::vector<double>& armature = resolved_->model->armature();
  observer_.configure(parameters_.observer, dof_,
                      parameters_.observer.measured_torque && !armature.empty()
                          ? JointVector(Eigen::Map<const Eigen::VectorXd>(armature.data(), dof_))
                          : JointVector());
  if (observer_.enabled()) {
    quantities_ = quantities_ | Quantity::kMassMatrix | Quantity::kCoriolis | Quantity::kJacobian;
  }
  state_ = JointState::zero(dof_);
  torque_.setZero(dof_);
  law_torque_.setZero(dof_);
  scratch_.setZero(dof_);
  input_.dof = dof_;
}

Controller::~Controller() = default;

void Controller::activate(const JointState& state) {
  deactivate();
  if (!state.usable(dof_)) {
    throw std::runtime_error(resolved_->config.name +
                             ": activation needs a finite joint state with " +
                             std::to_string(dof_) + " positions, velocities and efforts");
  }
  const std::span<const double> q(state.position.data(), static_cast<std::size_t>(dof_));
  const std::span<const double> dq(state.velocity.data(), static_cast<std::size_t>(dof_));
  if (model::update(*resolved_->model, data_, q, dq, quantities_) != model::UpdateStatus::kOk) {
    throw std::runtime_error(resolved_->config.name +
                             ": the model could not be evaluated at this state");
  }
  state_ = state;
  safe_hold_.keepGravity(data_);  // a FAULT in the first cycle holds at this state
  time_s_ = 0.0;
  fillPluginInput(state_, data_, quantities_, time_s_, period_s_, input_);

  // Commands accepted while inactive are in force (whether or not this activation succeeds);
  // the motion reference then starts where the arm is.
  for (const IntakeMessage* message = intake_.front(); message != nullptr;
       message = intake_.front()) {
    if (message->type == IntakeMessage::Type::kCommand) {
      mergeInto(active_, message->command);
      id_in_force_ = message->id;
    } else if (message->type == IntakeMessage::Type::kChunk) {
      chunks_.release(message->chunk_slot);  // a chunk's times were for the cycle that ran
    } else if (message->type == IntakeMessage::Type::kReset) {
      (void)reset_results_.push({message->id.sequence, ResetResult::End::kInactive});
    }
    intake_.pop();
  }
  chunks_.stop();
  CommandBus seeded = active_;
  seedFromMeasured(seeded, currentPose());
  if (plugin_->activate(input_) != COMPLY_OK) {
    throw plugin::PluginError(
        plugin::PluginErrc::kTrialStepFailed,
        plugin_->library().path().string() + ": activate() failed (returned an error or threw)");
  }
  plugin_->trialStep(input_, busPointer(seeded));  // throws before anything changes
  active_ = seeded;
  // Start the rate limit from what the joints carry now, so the first torque does not jump. Of
  // that, a robot that compensates gravity itself supplies the gravity: comply's share is the rest.
  torque_ = state_.effort.allFinite() ? state_.effort : data_.gravity.head(dof_);
  if (parameters_.hardware_compensates_gravity) {
    torque_ -= data_.gravity.head(dof_);
  }
  resetStages();
  in_force_changed_ = false;
  reset_pending_ = false;
  state_usable_ = true;
  measured_.publishFromSoleWriter(currentPose());  // the cycle is not running during activation
  publishInForce();
  diagnostics_.state.store(WrapperState::kActive);
}

void Controller::resetStages() noexcept {
  frozen_.reset();
  observer_.reset();  // the torque before activation is not known
  wrist_.reset();     // its low-pass starts from the next reading; the tare stays
  guard_.reset();
  watchdog_.reset();
  sensor_check_.reset();  // the first reading at rest is checked
  reflex_.reset();        // armed; the thresholds in force stay, as the gains do
  diagnostics_.reflex_latched.store(false, std::memory_order_relaxed);
  gains_.reset(active_, data_, state_, diagnostics_);
  force_.reset();
  force_active_ = false;
  walls_.reset();
  walls_active_ = false;
  contact_speed_.reset();
  safe_hold_.reset();
  shaper_.reset(torque_);
  output_stage_.reset(state_);
}

void Controller::deactivate() noexcept {
  diagnostics_.state.store(WrapperState::kInactive);
}

MeasuredPose Controller::measuredPose() {
  measured_.update();
  return measured_.read();
}

const CommandBus& Controller::commandInForce() {
  in_force_.update();
  return in_force_.read();
}

void Controller::warm(const JointState& last_state) noexcept {
  if (!state_usable_ ||
      diagnostics_.state.load(std::memory_order_relaxed) != WrapperState::kActive ||
      last_state.position != state_.position || last_state.velocity != state_.velocity) {
    return;  // only the state the data were computed from: the same numbers again
  }
  const std::span<const double> q(state_.position.data(), static_cast<std::size_t>(dof_));
  const std::span<const double> dq(state_.velocity.data(), static_cast<std::size_t>(dof_));
  (void)model::update(*resolved_->model, data_, q, dq, quantities_);
  const auto touch = [](const void* data, std::size_t bytes) noexcept {
    const auto* byte = static_cast<const char*>(data);
    for (std::size_t at = 0; at < bytes; at += 64) {
      __builtin_prefetch(byte + at);
    }
  };
  touch(&input_, sizeof input_);
  touch(&law_output_, sizeof law_output_);
  touch(busPointer(active_), sizeof(CommandBus));
  touch(busPointer(lawBus()), sizeof(CommandBus));
}

comply_status Controller::stepPluginOnly(comply_output& output) noexcept {
  return plugin_->step(input_, busPointer(lawBus()), output);
}

void Controller::advanceClock(double period_s) noexcept {
  diagnostics_.cycles.fetch_add(1, std::memory_order_relaxed);
  if (std::isfinite(period_s) && period_s > 0.0) {
    period_s_ = period_s;  // else the last good one: a glitch in the host's clock is not a fault
  }
  time_s_ += period_s_;
}

void Controller::enterFault(const char* prefix, const char* detail) noexcept {
  if (diagnostics_.state.load(std::memory_order_relaxed) != WrapperState::kFault) {
    diagnostics_.faults.fetch_add(1, std::memory_order_relaxed);
    diagnostics_.setFault(prefix, detail);
  }
  diagnostics_.state.store(WrapperState::kFault, std::memory_order_relaxed);
}

MeasuredPose Controller::currentPose() const noexcept {
  MeasuredPose pose = measuredPoseFrom(state_.position, data_);
  pose.time_s = time_s_;
  pose.period_s = period_s_;
  return pose;
}

void Controller::publishInForce() noexcept {
  in_force_.publishFromSoleWriter(active_);
  in_force_changed_ = true;
}

}  // namespace comply::pipeline
