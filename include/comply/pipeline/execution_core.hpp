#pragma once
// Everything one control cycle does that does not depend on the command type: model update,
// plugin call, compensation, torque shaping, watchdog clock, FAULT state and diagnostics. The joint
// and Cartesian wrappers (wrapper.hpp) add command intake and reference seeding around it.

#include <memory>
#include <span>

#include "comply/core/state.hpp"
#include "comply/core/triple_buffer.hpp"
#include "comply/model/robot_description.hpp"
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

/// Per-stage timing hooks for benchmarks (all optional, zero cost when unused).
struct CycleBreakdown {
  bool plugin_only = false;  ///< when set, update() runs only the plugin step (timing protocol)
};

class ExecutionCore {
 public:
  /// configure: resolves robot, builds the model, loads and creates the plugin. Throws
  /// model::ModelError, plugin::PluginError or std::runtime_error with a clear message.
  ExecutionCore(const WrapperConfig& config, int command_kind);

  [[nodiscard]] const WrapperConfig& config() const noexcept { return config_; }
  [[nodiscard]] const model::Model& model() const noexcept { return *model_; }
  [[nodiscard]] const model::Data& modelData() const noexcept { return *data_; }
  [[nodiscard]] int dof() const noexcept { return model_->dof(); }
  [[nodiscard]] model::Quantity modelQuantities() const noexcept { return quantities_; }
  [[nodiscard]] std::uint32_t pluginQuantities() const noexcept { return plugin_->requiredQuantities(); }
  [[nodiscard]] const plugin::PluginInstance& plugin() const noexcept { return *plugin_; }
  [[nodiscard]] Diagnostics& diagnostics() noexcept { return diagnostics_; }
  [[nodiscard]] const Diagnostics& diagnostics() const noexcept { return diagnostics_; }
  /// Latest measured pose published by the cycle (for command validation; any thread).
  [[nodiscard]] MeasuredPose measuredPose();

  /// Computes the model at `state` and runs the plugin's activate() and a trial step on `command`.
  /// Throws plugin::PluginError if the law fails or returns a non-finite torque; the wrapper stays
  /// inactive then.
  void activate(const JointState& state, const void* command);
  void deactivate() noexcept;
  /// Leaves FAULT (explicit operator action); the next cycle runs the law again.
  void requestReset() noexcept { reset_requested_.store(true); }

  // ---- real-time ------------------------------------------------------------------------------
  /// First half of a cycle: checks and stores the state, updates the model, publishes the
  /// measured pose, advances the clock. Returns false if the state is unusable (-> FAULT).
  bool beginCycle(const JointState& state, double period_s) noexcept;
  /// Second half: plugin step on `command`, compensation, shaping; writes dof torques.
  CycleStatus finishCycle(const void* command, std::span<double> torque) noexcept;

  /// Marks that a new command arrived this cycle (watchdog).
  void noteCommand() noexcept;
  /// True once per timeout (the first cycle after command_timeout_s without a command).
  bool watchdogFired() noexcept;
  [[nodiscard]] const comply_input& input() const noexcept { return input_; }
  [[nodiscard]] double time() const noexcept { return time_s_; }

  /// Plugin step alone on the current input (benchmark protocol); no shaping, no state change.
  comply_status stepPluginOnly(const void* command, comply_output& output) noexcept {
    return plugin_->step(input_, command, output);
  }

 private:
  void enterFault(const char* reason, const char* detail) noexcept;
  CycleStatus writeSafeTorque(std::span<double> torque) noexcept;
  void fillInput(const JointState& state, double period_s) noexcept;

  WrapperConfig config_;
  std::unique_ptr<model::Model> model_;
  std::unique_ptr<model::Data> data_;
  std::unique_ptr<plugin::PluginInstance> plugin_;
  model::Quantity quantities_ = model::Quantity::kNone;
  JointVector lower_limit_;
  JointVector upper_limit_;
  JointVector fault_damping_;
  std::unique_ptr<TorqueShaper> shaper_;
  Diagnostics diagnostics_;
  TripleBuffer<MeasuredPose> measured_;
  std::atomic<bool> reset_requested_{false};

  // Cycle state (real-time thread only).
  JointState state_;
  comply_input input_{};
  comply_output output_{};
  JointVector torque_;
  JointVector scratch_;
  double period_s_ = 0.001;
  double time_s_ = 0.0;
  double last_command_time_s_ = 0.0;
  bool watchdog_expired_ = false;
};

}  // namespace comply::pipeline
