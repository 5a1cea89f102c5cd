#pragma once
// Everything one control cycle does that does not depend on the command type: model update,
// plugin call, compensation, torque shaping, watchdog clock, FAULT state and diagnostics. The joint
// and Cartesian wrappers (wrapper.hpp) add command intake and reference seeding around it.

#include <atomic>
#include <memory>
#include <span>

#include "comply/core/state.hpp"
#include "comply/core/triple_buffer.hpp"
#include "comply/model/update.hpp"
#include "comply/pipeline/command_validation.hpp"
#include "comply/pipeline/config.hpp"
#include "comply/pipeline/diagnostics.hpp"
#include "comply/pipeline/torque_shaper.hpp"
#include "comply/plugin/loader.hpp"

namespace comply::pipeline {

enum class CycleStatus {
  kOk,
  kInactive,  ///< not activated: torque output untouched
  kFault,     ///< in FAULT: the safe holding torque was written
};

class ExecutionCore {
 public:
  /// configure: resolves the robot, builds the model, loads and creates the plugin of
  /// `command_kind` (COMPLY_COMMAND_*). Throws model::ModelError, plugin::PluginError or
  /// std::runtime_error with a clear message.
  ExecutionCore(const WrapperConfig& config, int command_kind);
  ~ExecutionCore();
  ExecutionCore(const ExecutionCore&) = delete;
  ExecutionCore& operator=(const ExecutionCore&) = delete;

  [[nodiscard]] const WrapperConfig& config() const noexcept { return config_; }
  [[nodiscard]] const model::Model& model() const noexcept { return *model_; }
  [[nodiscard]] const model::Data& modelData() const noexcept { return *data_; }
  [[nodiscard]] int dof() const noexcept { return dof_; }
  [[nodiscard]] model::Quantity modelQuantities() const noexcept { return quantities_; }
  [[nodiscard]] const plugin::PluginInstance& plugin() const noexcept { return *plugin_; }
  [[nodiscard]] Diagnostics& diagnostics() noexcept { return diagnostics_; }
  [[nodiscard]] const Diagnostics& diagnostics() const noexcept { return diagnostics_; }
  [[nodiscard]] const JointVector& effortLimit() const noexcept { return effort_limit_; }

  /// Latest pose the cycle measured, for command validation. Single reader: the wrapper calls it
  /// under its intake mutex.
  [[nodiscard]] MeasuredPose measuredPose();

  /// Non-RT: checks `state`, computes the model there and returns the pose for reference seeding.
  /// Throws std::runtime_error on a state of the wrong size or with non-finite entries.
  MeasuredPose prepareActivation(const JointState& state);
  /// Non-RT: runs the plugin's activate() and a trial step on `command` (a bus of the plugin's
  /// kind) at the state given to prepareActivation(), then starts the cycle. Throws
  /// plugin::PluginError if the law fails or returns a non-finite torque; the core stays inactive.
  void activate(const void* command);
  void deactivate() noexcept;
  /// Leaves FAULT (explicit operator action); the next cycle with a usable state runs the law
  /// again. Ignored outside FAULT, so that it cannot stay armed and clear a later fault unasked; a
  /// cycle whose state is unusable refuses it (the law would run on the last good state).
  void requestReset() noexcept {
    if (diagnostics_.state.load() == WrapperState::kFault) {
      reset_requested_.store(true);
    }
  }

  // ---- real-time: no allocation, no locks, no exceptions --------------------------------------
  /// First half of a cycle: checks and stores the state, updates the model, publishes the
  /// measured pose, advances the clock. An unusable state (wrong size, NaN) enters FAULT.
  void beginCycle(const JointState& state, double period_s) noexcept;
  /// Second half: plugin step on `command`, compensation, shaping; writes dof() torques.
  CycleStatus finishCycle(const void* command, std::span<double> torque) noexcept;

  /// Marks that a new command arrived this cycle (watchdog).
  void noteCommand() noexcept;
  /// True once per timeout: on the first cycle command_timeout_s after the last command.
  [[nodiscard]] bool watchdogFired() noexcept;

  [[nodiscard]] const comply_input& input() const noexcept { return input_; }
  /// Plugin step alone on the current input (benchmark protocol); no shaping, no state change.
  comply_status stepPluginOnly(const void* command, comply_output& output) noexcept {
    return plugin_->step(input_, command, output);
  }

 private:
  void enterFault(const char* prefix, const char* detail) noexcept;
  CycleStatus writeSafeTorque(std::span<double> torque) noexcept;
  bool computeModel(const JointState& state) noexcept;
  void fillInput(double period_s) noexcept;
  void addCompensation() noexcept;
  [[nodiscard]] MeasuredPose currentPose() const noexcept;

  WrapperConfig config_;
  int dof_ = 0;
  std::unique_ptr<model::Model> model_;
  std::unique_ptr<model::Data> data_;
  std::unique_ptr<plugin::PluginInstance> plugin_;
  model::Quantity quantities_ = model::Quantity::kNone;
  JointVector lower_limit_;
  JointVector upper_limit_;
  JointVector effort_limit_;
  JointVector fault_damping_;
  std::unique_ptr<TorqueShaper> shaper_;
  Diagnostics diagnostics_;
  TripleBuffer<MeasuredPose> measured_;
  std::atomic<bool> reset_requested_{false};

  // Cycle state (real-time thread only, or non-RT while inactive).
  JointState state_;
  comply_input input_{};
  comply_output output_{};
  JointVector torque_;
  JointVector scratch_;
  double period_s_ = 0.001;
  double time_s_ = 0.0;
  double last_command_time_s_ = 0.0;
  bool watchdog_expired_ = false;
  bool state_usable_ = false;  // this cycle's state passed beginCycle(), so input_ is current
};

}  // namespace comply::pipeline
