#pragma once
// The joint and Cartesian wrappers: command intake (any non-real-time thread) around the control
// cycle (controller.hpp), which is the same for both.
//
//   resolve    auto resolved = resolveController(loadWrapperConfig("controller.yaml"));
//   configure  CartesianWrapper wrapper(resolved);
//   activate   wrapper.activate(measured_state);            // seeds the reference from the state
//   command    wrapper.submit(command);                      // any thread, returns a Verdict
//   cycle      wrapper.update(state, period_s, torque);      // real-time thread
//   deactivate wrapper.deactivate();
//
// A submitted command is validated here, against the pose the cycle last published and the one
// stamp floor (the last accepted stamp, integer nanoseconds), numbered (CommandId) and queued with
// its field mask; the cycle merges it into the command in force. So update() never blocks on
// a sender, never sees a half-written command, and a rejected command changes nothing. Lifecycle
// calls (activate, deactivate) run between cycles, as in ros2_control. submit(), reset(),
// lastAccepted() and diagnostics() may run at any time.

#include <memory>
#include <mutex>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "comply/core/chunk.hpp"
#include "comply/core/commands.hpp"
#include "comply/core/state.hpp"
#include "comply/hardware/control_loop.hpp"
#include "comply/pipeline/command_validation.hpp"
#include "comply/pipeline/config.hpp"
#include "comply/pipeline/controller.hpp"
#include "comply/pipeline/diagnostics.hpp"
#include "comply/pipeline/output_stage.hpp"
#include "comply/pipeline/resolved_controller.hpp"

namespace comply::pipeline {

template <typename Command>
class Wrapper final : public hardware::CycleController {
 public:
  /// configure from an already resolved controller. Throws plugin::PluginError
  /// (kWrongCommandKind) when the plugin takes the other kind of command.
  explicit Wrapper(std::shared_ptr<const ResolvedController> resolved);
  /// configure: resolves `config` first (see resolveController()).
  explicit Wrapper(const WrapperConfig& config);

  /// Non-RT. See Controller::activate(). Reactivation after deactivate() seeds again (and, in an
  /// admittance mode, starts the virtual arm at `state`).
  void activate(const JointState& state) { controller_.activate(state); }
  /// Non-RT. update() outputs nothing until the next activate().
  void deactivate() noexcept { controller_.deactivate(); }
  /// Any thread. Asks the cycle to leave FAULT; the law runs again from the next cycle with a
  /// usable state. Ends the contact reflex's hold the same way (contact_reflex.hpp): the measured
  /// pose held, the file's thresholds; commands are taken again from this request on. Ignored
  /// otherwise. Clears the stamp floor either way: the next command may carry any stamp; and a
  /// chunk still waiting for its first waypoint is dropped.
  /// Returns the request's number, which the cycle's ResetResult names
  /// (Controller::takeResetResult), or 0 when the intake queue was full and it was not queued.
  std::uint64_t reset();
  /// Any thread. The next cycle drops the chunk numbered `sequence` (Verdict::sequence) if it
  /// still waits for its first waypoint: its sender left (CommandGate::releasePublisher), and a
  /// motion no one is there to follow up must not start later. A reset drops any waiting chunk.
  void dropWaitingChunk(std::uint64_t sequence);
  /// Any thread. The next cycle takes the wrist sensor's reading, less the declared tool's
  /// weight, as its zero (Controller::sensorWrench; wrist_sensor.hpp). Returns why not, empty
  /// when queued: the hardware has never given a reading, or the intake queue is full.
  [[nodiscard]] std::string tare();

  /// Any non-RT thread. Validates `command` (the field groups it sets) against the measured pose
  /// and the last accepted stamp and queues it for the next cycle. A rejected command changes
  /// nothing; the reason is counted in the diagnostics. Its stamp_s may repeat the last accepted
  /// one, never go back (a task file's or an experiment's commands).
  Verdict submit(const Command& command);
  /// The same for a command whose exact wire stamp `wire_stamp_ns` names it (a transport's,
  /// through the command gate): it must be strictly newer than the last accepted, compared in
  /// integer nanoseconds. Not counted in the diagnostics: the gate counts what it offers.
  Verdict submit(const Command& command, std::int64_t wire_stamp_ns);
  /// Any non-RT thread. Validates a timed chunk as a whole (validateChunk) and queues it: the
  /// next cycle starts it, blending in from the reference in force. `host_time_s` is the host's
  /// clock now, in the timebase of the waypoints' times; the cycle meets those times to within
  /// one control period. A rejected chunk changes nothing.
  Verdict submitChunk(const Chunk<Command>& chunk, double host_time_s);
  /// The same for a chunk named by its exact wire stamp (see submit()).
  Verdict submitChunk(const Chunk<Command>& chunk, double host_time_s, std::int64_t wire_stamp_ns);
  /// Any non-RT thread. The reference the cycle will write at each of `times_s` (the host's clock,
  /// increasing) if no new command or chunk arrives: the command in force, the running chunk's
  /// curve, or a waiting chunk's from its takeover (ChunkPlayer::predict), evaluated with the
  /// player's own code. `host_time_s` is the host's clock now, mapped onto the controller's as a
  /// chunk's times are: times on the cycle's grid then fall on cycles. `out` gets one command per
  /// time (the groups no chunk drives as in force); an entry whose position is NaN could not be
  /// answered (a time before the running chunk whose slot is reused). False when one could not.
  bool predict(std::span<const double> times_s, double host_time_s, std::vector<Command>& out);
  /// The command in force (merged) as of the last cycle.
  [[nodiscard]] Command lastAccepted() const;
  /// The pose the cycle last measured (what commands are validated against).
  [[nodiscard]] MeasuredPose measuredPose() const;

  /// Real-time. One control cycle at measured `state`; writes dof() torques [N m] to `torque`
  /// unless inactive: the cycle of output.mode torque, whatever the mode. Never allocates, locks
  /// or throws.
  CycleStatus update(const JointState& state, double period_s, std::span<double> torque) noexcept {
    return controller_.update(state, period_s, torque);
  }
  /// One control cycle for a control loop (hardware/control_loop.hpp), in the configured
  /// output.mode (output_stage.hpp): true when `command` holds a command to write.
  bool cycle(const JointState& state, double period_s, ActuatorCommand& command) noexcept override {
    return controller_.cycle(state, period_s, command);
  }
  [[nodiscard]] OutputMode outputMode() const noexcept override {
    return controller_.output().mode();
  }
  /// The output stage (the virtual arm of an admittance mode).
  [[nodiscard]] const OutputStage& output() const noexcept { return controller_.output(); }
  [[nodiscard]] bool wantsHold() const noexcept override { return controller_.holdRequested(); }
  bool contactAllowance(double& force_n, double& torque_n_m) const noexcept override {
    return controller_.contactAllowance(force_n, torque_n_m);
  }
  void warm(const JointState& last_state) noexcept override { controller_.warm(last_state); }

  [[nodiscard]] DiagnosticsSnapshot diagnostics() const {
    return controller_.diagnostics().snapshot();
  }
  [[nodiscard]] int dof() const noexcept override { return controller_.dof(); }
  [[nodiscard]] Controller& controller() noexcept { return controller_; }
  [[nodiscard]] const Controller& controller() const noexcept { return controller_; }

 private:
  mutable Controller controller_;  // mutable: reading its published values is a reader's update

  /// A command's stamp as the stamp floor judges it.
  struct IntakeStamp {
    std::int64_t ns = 0;
    /// The wire stamp names the command: strictly newer than the last accepted. Else (stamp_s
    /// of a direct caller) it may repeat it, never go back; and a non-finite one is left to the
    /// validation, which names it.
    bool names_command = false;
    bool finite = true;
  };
  static IntakeStamp directStamp(double stamp_s) noexcept;
  /// Why `stamp` is refused by the stamp floor; accepted when it passes.
  [[nodiscard]] Verdict checkFloor(const IntakeStamp& stamp) const;
  Verdict submitStamped(const Command& command, const IntakeStamp& stamp);
  Verdict submitChunkStamped(const Chunk<Command>& chunk, double host_time_s,
                             const IntakeStamp& stamp);
  std::uint64_t resets_ = 0;  // reset requests numbered so far
  /// Diagnostics::reflex_trips when the last reset was queued: the reflex's hold it ends.
  std::uint64_t reflex_trips_at_reset_ = 0;
  /// predict() under the intake's lock, on buses.
  bool predictLocked(std::span<const double> times_s, double host_time_s,
                     const MeasuredPose& measured, std::vector<CommandBus>& out);
  /// Where a chunk taking over at `takeover_s` (host clock) starts from.
  ChunkTakeover takeoverAt(double takeover_s, double host_time_s, const MeasuredPose& measured);
  /// The number and stamp the command queued next will carry.
  [[nodiscard]] CommandId nextId(const IntakeStamp& stamp) const noexcept {
    return {.sequence = last_sequence_ + 1, .stamp_ns = stamp.ns};
  }
  /// A command or chunk queued: the stamp floor moves to it, it takes its number (into
  /// `verdict`), and its gains are the intake's from now on.
  void accept(const IntakeStamp& stamp, const Command& gains, Verdict& verdict);
  /// Counts a direct caller's verdict in the diagnostics (the gate counts what it offers).
  Verdict account(Verdict verdict, const IntakeStamp& stamp);

  /// The command the intake has let through (the one in force when first asked, then every
  /// accepted command and chunk merged in): a damping ratio sent alone is checked against the
  /// stiffness it will act with (gain_bound.hpp). Under intake_mutex_.
  Command intakeGains();
  /// Checks the gains of `command` (its groups `fields`) merged into `base` at the control
  /// period `period_s`; `candidate` receives the merge.
  Verdict checkGains(const Command& command, CommandField fields, const Command& base,
                     double period_s, Command& candidate);

  mutable std::mutex intake_mutex_;  // senders and lifecycle calls only, never the cycle
  // The one stamp floor: the last accepted stamp [ns]; a reset clears it.
  std::int64_t floor_ns_ = 0;
  bool accepted_any_ = false;
  std::uint64_t last_sequence_ = 0;
  std::optional<Command> intake_gains_;
};

using JointWrapper = Wrapper<JointCommand>;
using CartesianWrapper = Wrapper<CartesianCommand>;

extern template class Wrapper<JointCommand>;
extern template class Wrapper<CartesianCommand>;

}  // namespace comply::pipeline
