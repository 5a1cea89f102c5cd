#pragma once
// The joint and Cartesian wrappers: command intake (any non-real-time thread), lifecycle, and the
// real-time update around the execution core.
//
//   configure  WrapperT wrapper(loadWrapperConfig("controller.yaml"));
//   activate   wrapper.activate(measured_state);            // seeds the reference from the state
//   command    wrapper.submit(command);                      // any thread, returns a Verdict
//   cycle      wrapper.update(state, period_s, torque);      // real-time thread
//   deactivate wrapper.deactivate();
//
// Commands are validated and merged off the real-time thread and handed over through a triple
// buffer, so update() never blocks on a sender and never sees a half-written command. Lifecycle
// calls (activate, deactivate) run between cycles, as in ros2_control: never concurrently with
// update(). submit(), reset() and diagnostics() may run at any time.

#include <atomic>
#include <memory>
#include <mutex>
#include <span>
#include <type_traits>

#include "comply/core/commands.hpp"
#include "comply/core/state.hpp"
#include "comply/core/triple_buffer.hpp"
#include "comply/pipeline/command_validation.hpp"
#include "comply/pipeline/config.hpp"
#include "comply/pipeline/diagnostics.hpp"
#include "comply/pipeline/execution_core.hpp"
#include "comply/plugin/abi.h"

namespace comply::pipeline {

template <typename Command>
struct CommandTraits;
template <>
struct CommandTraits<JointCommand> {
  using Bus = comply_joint_command;
  static constexpr int kKind = COMPLY_COMMAND_JOINT;
};
template <>
struct CommandTraits<CartesianCommand> {
  using Bus = comply_cartesian_command;
  static constexpr int kKind = COMPLY_COMMAND_CARTESIAN;
};

/// Sets the motion reference of `command` to the measured pose with zero velocity (and, for a
/// Cartesian command, the nullspace target to the measured joints): the reference a freshly
/// activated or re-anchored controller holds, so nothing moves.
void seedReference(JointCommand& command, const MeasuredPose& pose);
void seedReference(CartesianCommand& command, const MeasuredPose& pose);

template <typename Command>
class Wrapper {
 public:
  using Bus = typename CommandTraits<Command>::Bus;

  /// configure. Throws with a clear message (see ExecutionCore).
  explicit Wrapper(const WrapperConfig& config);

  /// Non-RT. Seeds the reference (pose or joint target, nullspace target) from `state`, keeps the
  /// gains and task frame in force, checks the law with a trial step and starts the cycle.
  /// Reactivation after deactivate() seeds again. Throws on a bad state or a failing plugin.
  void activate(const JointState& state);
  /// Non-RT. update() outputs nothing until the next activate().
  void deactivate() noexcept;
  /// Non-RT. Leaves FAULT; the law runs again from the next cycle with a usable state. Ignored
  /// outside FAULT (see ExecutionCore::requestReset()).
  void reset() noexcept { core_.requestReset(); }

  /// Any non-RT thread. Validates `command` against the last accepted one and the measured pose,
  /// merges the fields it sets, and hands the result to the cycle. A rejected command changes
  /// nothing; the reason is counted in the diagnostics.
  Verdict submit(const Command& command);
  /// The command in force (last accepted, merged), as the senders' side sees it.
  [[nodiscard]] Command lastAccepted() const;

  /// Real-time. One control cycle at measured `state`; writes dof() torques [N m] to `torque`
  /// unless inactive. Never allocates, locks or throws.
  CycleStatus update(const JointState& state, double period_s, std::span<double> torque) noexcept;

  [[nodiscard]] DiagnosticsSnapshot diagnostics() const { return core_.diagnostics().snapshot(); }
  [[nodiscard]] int dof() const noexcept { return core_.dof(); }
  [[nodiscard]] ExecutionCore& core() noexcept { return core_; }
  [[nodiscard]] const ExecutionCore& core() const noexcept { return core_; }
  /// The bus the cycle currently runs on (real-time thread only, e.g. for benchmarks).
  [[nodiscard]] const Bus& activeCommand() const noexcept { return active_; }

 private:
  void reanchor() noexcept;

  ExecutionCore core_;
  mutable std::mutex intake_mutex_;  // senders and lifecycle calls only, never the cycle
  Command merged_;
  TripleBuffer<Bus> bus_;
  // Reference the cycle re-anchored to on a watchdog timeout, for the senders' merged command.
  TripleBuffer<MeasuredPose> anchor_;
  // Set by the cycle when a "hold" timeout stopped the motion reference, for the same reason.
  std::atomic<bool> motion_stopped_{false};
  Bus active_{};  // real-time thread's copy
};

using JointWrapper = Wrapper<JointCommand>;
using CartesianWrapper = Wrapper<CartesianCommand>;

extern template class Wrapper<JointCommand>;
extern template class Wrapper<CartesianCommand>;

}  // namespace comply::pipeline
