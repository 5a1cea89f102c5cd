#pragma once
// The control cycle. One function, update(), is the whole cycle as a table of contents over
// stages that live in their own files (cycle_*.cpp):
//
//   measure      state check (finite; not frozen), model update, the wrist sensor's reading
//                (tool weight and tare off), plugin input, publish the measured pose
//                                                               -> FAULT on a bad state
//   guard        overspeed, a joint past its limit, an oscillation whose energy grows
//                while the command holds still                  -> FAULT (stability_guard.*)
//   commands     take every command the intake queued, merged by field mask; a timed chunk
//                starts, and the running one writes its reference at this cycle's time
//   watchdog     no command for command_timeout_s: hold (stop the motion) or re-anchor
//   gains        ramps and the energy tank between the commanded gains and the law's (optional)
//   force        force along the task axes a command selects, the contact-force limit
//                (force_axes.hpp; Cartesian laws)
//   law          plugin step, finite check                      -> FAULT on failure
//   compensate   gravity, payload, friction, soft joint limits
//   shape        low-pass, finite check, torque-rate limit, effort limit; a joint held at its
//                effort limit too long                          -> FAULT (stability_guard.*)
//   write        torque out; in FAULT a safe holding torque instead
//
// Threads. update() runs on the real-time thread. The lifecycle (activate, deactivate) runs
// between cycles, never concurrently with update(), as in ros2_control. Exactly two things cross
// between the real-time thread and the others, both without a lock on the real-time side:
//   - the intake queue (commands and operator requests: reset, tare), pushed by the wrapper's
//     intake under its own mutex, drained by the cycle;
//   - the published measurement (measured pose every cycle, the command in force when it
//     changes), written by the cycle and read by the intake.
// Diagnostics counters are atomics the cycle writes and anyone reads.

#include <atomic>
#include <cstdint>
#include <memory>
#include <span>

#include "comply/core/spsc_queue.hpp"
#include "comply/core/state.hpp"
#include "comply/core/triple_buffer.hpp"
#include "comply/model/data.hpp"
#include "comply/model/update.hpp"
#include "comply/pipeline/chunk_player.hpp"
#include "comply/pipeline/command_bus_variant.hpp"
#include "comply/pipeline/diagnostics.hpp"
#include "comply/pipeline/energy_watch.hpp"
#include "comply/pipeline/force_axes.hpp"
#include "comply/pipeline/gain_guard.hpp"
#include "comply/pipeline/resolved_controller.hpp"
#include "comply/pipeline/torque_shaper.hpp"
#include "comply/plugin/loader.hpp"

namespace comply::pipeline {

/// How far the output torque must move [N m, any joint] while the joint state stays bit-identical
/// for frozen_state_timeout_s before the state counts as frozen. A simulator or an arm at rest
/// repeats its state only while the torque repeats too; a driver that resends its last sample
/// does not.
inline constexpr double kFrozenStateTorqueChangeNm = 1.0;
/// How far [rad | m] the reported velocity must carry a joint over frozen_state_timeout_s for
/// an unchanged position to betray a stale stream (a thousand times an FR3 encoder's resolution).
inline constexpr double kFrozenStateMotionRad = 1e-4;

enum class CycleStatus {
  kOk,
  kInactive,  ///< not activated: torque output untouched
  kFault,     ///< in FAULT: the safe holding torque was written
};

/// One entry of the intake queue.
struct IntakeMessage {
  enum class Type : std::uint8_t { kCommand, kReset, kChunk, kTare };
  Type type = Type::kCommand;
  CommandBus command;   ///< kCommand: a validated command with its field mask
  int chunk_slot = -1;  ///< kChunk: the ChunkPlayer slot the intake loaded it into
};

class Controller {
 public:
  /// Commands the intake may queue between two cycles before it refuses more.
  static constexpr std::size_t kIntakeCapacity = 64;

  /// configure: creates the plugin instance and the model scratch data. Throws
  /// plugin::PluginError when the plugin refuses its parameters.
  explicit Controller(std::shared_ptr<const ResolvedController> resolved);
  ~Controller();
  Controller(const Controller&) = delete;
  Controller& operator=(const Controller&) = delete;

  // ---- lifecycle (non-real-time, between cycles) ----------------------------------------------
  /// Checks `state`, takes what the intake queued, seeds the motion reference from the measured
  /// pose (gains and task frame stay), runs the plugin's activate() and a trial step, and starts
  /// the cycle. Throws std::runtime_error on a bad state, plugin::PluginError if the law refuses;
  /// the controller then stays inactive.
  void activate(const JointState& state);
  /// update() outputs nothing until the next activate().
  void deactivate() noexcept;

  // ---- real-time: no allocation, no locks, no exceptions --------------------------------------
  /// One control cycle at measured `state`; writes dof() torques [N m] to `torque` unless
  /// inactive.
  CycleStatus update(const JointState& state, double period_s, std::span<double> torque) noexcept;

  // ---- intake side (one producer at a time: the wrapper serialises its senders) ---------------
  /// Queues a message for the next cycle; false when the queue is full.
  bool enqueue(const IntakeMessage& message) noexcept { return intake_.push(message); }
  /// The timed chunks' slots: the intake loads a validated chunk here and then enqueues a
  /// kChunk message naming its slot.
  [[nodiscard]] ChunkPlayer& chunks() noexcept { return chunks_; }
  /// The pose the cycle last measured (reader: the intake, under its mutex).
  [[nodiscard]] MeasuredPose measuredPose();
  /// The command in force as of the last cycle (same reader).
  [[nodiscard]] const CommandBus& commandInForce();

  // ---- read-only -------------------------------------------------------------------------------
  [[nodiscard]] const ResolvedController& resolved() const noexcept { return *resolved_; }
  [[nodiscard]] int dof() const noexcept { return dof_; }
  [[nodiscard]] const model::Model& model() const noexcept { return *resolved_->model; }
  [[nodiscard]] const model::Data& modelData() const noexcept { return data_; }
  [[nodiscard]] model::Quantity modelQuantities() const noexcept { return quantities_; }
  [[nodiscard]] const plugin::PluginInstance& plugin() const noexcept { return *plugin_; }
  [[nodiscard]] Diagnostics& diagnostics() noexcept { return diagnostics_; }
  [[nodiscard]] const Diagnostics& diagnostics() const noexcept { return diagnostics_; }
  [[nodiscard]] const JointVector& effortLimit() const noexcept {
    return resolved_->parameters.effort_limit;
  }
  /// The plugin input of the last cycle and the bus in force (real-time thread; benchmarks).
  [[nodiscard]] const comply_input& input() const noexcept { return input_; }
  [[nodiscard]] const CommandBus& activeCommand() const noexcept { return active_; }
  /// What the law reads: the command in force with the gains the gain stage let through (the
  /// command in force itself when the stage is off), and force axes turned into reference and
  /// feedforward by the force stage. Real-time thread, or between cycles.
  [[nodiscard]] const CommandBus& lawBus() const noexcept {
    return force_active_ ? force_bus_ : guardedBus();
  }
  /// The force stage (force_axes.hpp): its loop's output and pull-back of the last cycle.
  [[nodiscard]] const ForceAxes& forceAxes() const noexcept { return force_; }
  /// The external wrench on the tool from `source`: at the TCP, base frame, force first [N, N m];
  /// nullptr when none this cycle. kAuto is the rule the state reports by: the observer's estimate
  /// when it runs, else the wrist sensor's reading; the force stage reads force_control.source.
  /// Real-time thread, or between cycles.
  [[nodiscard]] const Vector6d* contactWrench(
      ForceSource source = ForceSource::kAuto) const noexcept;
  /// The external wrench estimate (observer.enabled): at the TCP, base frame, force first
  /// [N, N m], and per joint [N m | N]. Real-time thread, or between cycles.
  [[nodiscard]] const MomentumObserver& observer() const noexcept { return observer_; }
  /// The wrist force/torque sensor's reading as the law's side sees it (cycle_wrench.cpp): the
  /// declared tool's weight and the tare taken off; at the TCP, base frame, force first [N, N m].
  /// Valid when the hardware gave a finite reading this cycle. Real-time thread, or between
  /// cycles.
  [[nodiscard]] const Vector6d& sensorWrench() const noexcept { return sensor_wrench_; }
  [[nodiscard]] bool sensorWrenchValid() const noexcept { return sensor_valid_; }
  /// Any thread: the hardware has given a wrist force/torque reading since construction.
  [[nodiscard]] bool sensorSeen() const noexcept {
    return sensor_seen_.load(std::memory_order_relaxed);
  }
  /// In FAULT on a frozen sensor stream: the hold's gravity is that of a pose the arm may have
  /// left, so the hardware's own hold (brakes) is asked for as well (CycleController::wantsHold).
  [[nodiscard]] bool holdRequested() const noexcept {
    return state_frozen_ &&
           diagnostics_.state.load(std::memory_order_relaxed) == WrapperState::kFault;
  }
  /// The stamp [s] of the command in force (what CommandGate::noteCycle() is told after a cycle).
  [[nodiscard]] double stampInForce() const noexcept {
    return std::visit([](const auto& bus) noexcept { return bus.stamp_s; }, active_);
  }
  /// Benchmark protocol, the law's cost alone: measureOnly() runs the measure stage at `state`
  /// (false on a bad state), stepPluginOnly() the plugin step on its input and the command in
  /// force, without shaping or any other state change.
  bool measureOnly(const JointState& state) noexcept { return measure(state); }
  comply_status stepPluginOnly(comply_output& output) noexcept;
  /// Between cycles (ControlLoop's warm_ahead_s): the model update at `last_state` again, into
  /// the model data it already holds for that state (the same numbers), and a read of the plugin
  /// input and the buses, so that the next cycle finds them cached. Never calls the plugin (a law
  /// may keep state between steps). Real-time.
  void warm(const JointState& last_state) noexcept;

 private:
  // Stages, one file each (cycle_*.cpp).
  bool measure(const JointState& state) noexcept;
  bool guardMotion() noexcept;
  /// The energy rule of guardMotion(): the law's command of the last cycle as the watch's input.
  bool guardEnergy() noexcept;
  bool guardSaturation() noexcept;  // cycle_guard.cpp
  void takeCommands() noexcept;
  /// A queued command that sets a group the running chunk drives ends the chunk (its reference
  /// at this cycle stays, at rest unless the command sets a velocity).
  void takeCommand(const CommandBus& command) noexcept;
  void playChunk() noexcept;  // cycle_commands.cpp
  void watchdog() noexcept;
  void guardGains() noexcept;
  void applyForce() noexcept;  // cycle_force.cpp
  [[nodiscard]] const CommandBus& guardedBus() const noexcept {
    return gains_.enabled() ? gains_.lawBus() : active_;
  }
  bool runLaw() noexcept;
  void compensate() noexcept;
  bool shape() noexcept;
  void scaleIntoLimits() noexcept;  // effort_saturation: scale
  CycleStatus write(std::span<double> torque) noexcept;
  CycleStatus hold(std::span<double> torque) noexcept;
  /// Keeps the gravity (+ payload) of the state just evaluated as FAULT's holding base; called
  /// only after a successful model update, which a failed one may leave half-written.
  void keepHoldingGravity() noexcept;
  void observe() noexcept;  // cycle_measure.cpp: the momentum observer's update
  void senseWrench(const JointState& state) noexcept;  // cycle_wrench.cpp
  void tare() noexcept;                                // cycle_wrench.cpp
  /// Whether `state` repeats the last one bit for bit for frozen_state_timeout_s while the torque
  /// moved kFrozenStateTorqueChangeNm: a stale sensor stream.
  bool stateFrozen(const JointState& state) noexcept;
  /// With the driver's sample counter: whether it has stood still for frozen_state_timeout_s.
  bool sequenceStale(const JointState& state) noexcept;

  void advanceClock(double period_s) noexcept;
  void enterFault(const char* prefix, const char* detail) noexcept;
  [[nodiscard]] MeasuredPose currentPose() const noexcept;
  void publishInForce() noexcept;

  std::shared_ptr<const ResolvedController> resolved_;
  const CycleParameters& parameters_;
  int dof_ = 0;
  model::Data data_;
  std::unique_ptr<plugin::PluginInstance> plugin_;
  model::Quantity quantities_ = model::Quantity::kNone;
  TorqueShaper shaper_;
  Diagnostics diagnostics_;

  SpscQueue<IntakeMessage> intake_{kIntakeCapacity};
  TripleBuffer<MeasuredPose> measured_;
  TripleBuffer<CommandBus> in_force_;

  // Cycle state: real-time thread only (or the lifecycle, between cycles).
  CommandBus active_;
  GainGuard gains_;
  MomentumObserver observer_;
  ForceAxes force_;
  CommandBus force_bus_;       // the law's command when the force stage acts (Cartesian)
  bool force_active_ = false;  // the force stage wrote force_bus_ this cycle
  ChunkPlayer chunks_;
  bool in_force_changed_ = false;  // active_ changed since the gain stage last saw it
  bool torque_clipped_ = false;    // the last cycle's torque was rate or effort limited
  JointVector overspeed_s_;        // per joint: how long it has been over its speed limit
  JointVector saturated_s_;        // per joint: how long it has sat at its effort limit
  EnergyWatch energy_watch_;       // the guard's energy rule (energy_watch.hpp)
  CommandBus energy_bus_;          // the law's command the energy rule saw last
  bool reset_pending_ = false;
  // The wrist sensor (cycle_wrench.cpp): this cycle's reading less the tool's weight, then less
  // the tare, which is kept in the TCP frame (the sensor turns with the tool).
  Vector6d sensor_untared_ = Vector6d::Zero();
  Vector6d sensor_wrench_ = Vector6d::Zero();
  Vector6d tare_in_tcp_ = Vector6d::Zero();
  bool sensor_valid_ = false;
  bool sensor_filtered_ = false;  // the low-pass has a reading to start from
  std::atomic<bool> sensor_seen_{false};
  JointState state_;
  bool state_usable_ = false;  // this cycle's state passed measure(), so input_ is current
  comply_input input_{};
  comply_output output_{};
  JointVector torque_;
  JointVector law_torque_;  // this cycle's law output, before compensation
  JointVector scratch_;
  JointVector hold_gravity_;  // gravity (+ payload) at the last usable state: FAULT's holding base
  // Frozen-state detection: cycles the state has repeated, since when, the torque then.
  int repeated_cycles_ = 0;
  double repeated_since_s_ = 0.0;
  JointVector torque_when_repeated_;
  bool state_frozen_ = false;  // the hold then damps nothing: its velocity is stale
  // The driver's sample counter (JointState::sequence): its last value and since when.
  bool sequence_seen_ = false;
  std::uint64_t last_sequence_ = 0;
  double sequence_since_s_ = 0.0;
  double period_s_ = 0.001;
  double time_s_ = 0.0;
  double last_command_time_s_ = 0.0;
  bool watchdog_expired_ = false;
};

}  // namespace comply::pipeline
