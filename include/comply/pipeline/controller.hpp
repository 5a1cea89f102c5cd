#pragma once
// The control cycle. Two functions are the whole cycle, each a table of contents over stages that
// are objects of their own (their state and reset()), run from files of their own:
//
// cycle(): one cycle for the drives (cycle/cycle.cpp)
//   law state    admittance modes run the law on their virtual arm, the others on the measured
//                state                                           (output/virtual_arm.*)
//   update()     the law's cycle below, at that state
//   output       the torque as it is, split for a drive's PD, or the virtual arm's step and the
//                positions and velocities the drives follow      (output/output_stage.*)
//
// update(): the law's cycle, torque out (cycle/cycle.cpp)
//   measure      state check (finite; not frozen: frozen_state.*), model update, the momentum
//                observer, the wrist sensor's reading (wrist_sensor.*), plugin input, publish the
//                measured pose                                   -> FAULT on a bad state
//   guard        overspeed, a joint past its limit, an oscillation whose energy grows while the
//                command holds still (stability_guard.*)         -> FAULT
//   commands     take every command the intake queued, merged by field mask; a timed chunk
//                starts, and the running one writes its reference at this cycle's time
//   watchdog     no command for command_timeout_s: hold (stop the motion) or re-anchor
//   sensor       the wrist sensor's reading at rest after activation near zero, and in agreement
//                with the momentum observer (sensor_check.*)    -> FAULT
//   reflex       the contact wrench above the thresholds of the command in force: hold, retreat
//                (latched until a reset) or FAULT (contact_reflex.hpp; off: one branch)
//   gains        ramps and the energy tank between the commanded gains and the law's (optional)
//   force        force along the task axes a command selects, the contact-force limit
//                (force_axes.hpp; Cartesian laws)
//   walls        the law's reference kept inside the walls and boxes (virtual_walls.hpp;
//                Cartesian laws; off without walls)
//   law          plugin step, finite check                       -> FAULT on failure
//   compensate   gravity, payload, friction, soft joint limits
//   govern       the law's torque scaled (direction kept) so no joint passes its share of its
//                URDF speed, nor the TCP its speeds; braking past them (motion_governor.*)
//   contact      the TCP no faster along its motion than a contact may take; braking past
//                it (contact_speed.*; Cartesian laws; off by default)
//   barrier      a TCP approaching a wall braked through J^T (virtual_walls.*)
//   shape        low-pass, finite check, torque-rate limit, effort limit (torque_shaper.*); a
//                joint held at its effort limit too long         -> FAULT (stability_guard.*)
//   write        torque out; in FAULT the controlled stop's torque instead (safe_hold.*); a
//                reset holds the measured pose (commands.cpp)
//
// activate() seeds the command in force from the measured state and resets every stage, in one
// list (controller.cpp).
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

#include "comply/core/actuator_command.hpp"
#include "comply/core/spsc_queue.hpp"
#include "comply/core/state.hpp"
#include "comply/core/triple_buffer.hpp"
#include "comply/model/data.hpp"
#include "comply/model/update.hpp"
#include "comply/pipeline/chunk_player.hpp"
#include "comply/pipeline/command_bus_variant.hpp"
#include "comply/pipeline/command_watchdog.hpp"
#include "comply/pipeline/contact_reflex.hpp"
#include "comply/pipeline/contact_speed.hpp"
#include "comply/pipeline/cycle_status.hpp"
#include "comply/pipeline/diagnostics.hpp"
#include "comply/pipeline/force_axes.hpp"
#include "comply/pipeline/frozen_state.hpp"
#include "comply/pipeline/gain_guard.hpp"
#include "comply/pipeline/momentum_observer.hpp"
#include "comply/pipeline/motion_governor.hpp"
#include "comply/pipeline/output_stage.hpp"
#include "comply/pipeline/resolved_controller.hpp"
#include "comply/pipeline/safe_hold.hpp"
#include "comply/pipeline/sensor_check.hpp"
#include "comply/pipeline/stability_guard.hpp"
#include "comply/pipeline/torque_shaper.hpp"
#include "comply/pipeline/virtual_walls.hpp"
#include "comply/pipeline/wrist_sensor.hpp"
#include "comply/plugin/loader.hpp"

namespace comply::pipeline {

/// One entry of the intake queue.
struct IntakeMessage {
  /// kDropChunk: the chunk numbered id.sequence is dropped if it still waits for its first
  /// waypoint (its sender left).
  enum class Type : std::uint8_t { kCommand, kReset, kChunk, kTare, kDropChunk };
  Type type = Type::kCommand;
  CommandBus command;   ///< kCommand: a validated command with its field mask
  int chunk_slot = -1;  ///< kChunk: the ChunkPlayer slot the intake loaded it into
  CommandId id;         ///< kCommand, kChunk, kDropChunk: which command it is; kReset: its number
};

/// What became of a reset request (IntakeMessage kReset, numbered by its id.sequence), decided by
/// the cycle that took it.
struct ResetResult {
  enum class End : std::uint8_t {
    kNoFault,        ///< there was no fault to leave (the intake cleared the stamp floor)
    kLeftFault,      ///< the controller left FAULT, holding the measured pose
    kStateUnusable,  ///< in FAULT with a measured state it cannot hold: the fault stays
    kInactive,       ///< taken at activation, which starts afresh anyway
    kLeftReflex,     ///< the contact reflex's hold ended (its latch), holding the measured pose
    kRobotStopped,   ///< in FAULT while the robot itself is stopped (JointState::robot_stop)
  };
  std::uint64_t number = 0;
  End end = End::kNoFault;
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
  /// pose (gains and task frame stay), runs the plugin's activate() and a trial step, resets every
  /// stage and starts the cycle (an admittance's virtual arm at `state`). Throws
  /// std::runtime_error on a bad state, plugin::PluginError if the law refuses; the controller
  /// then stays inactive.
  void activate(const JointState& state);
  /// update() outputs nothing until the next activate().
  void deactivate() noexcept;

  // ---- real-time: no allocation, no locks, no exceptions --------------------------------------
  /// One control cycle for the drives at measured `state`, in output.mode; true when `command`
  /// holds a command to write (false: inactive).
  bool cycle(const JointState& state, double period_s, ActuatorCommand& command) noexcept;
  /// The law's cycle at `state` (measured, or an admittance's virtual arm); writes dof() torques
  /// [N m] to `torque` unless inactive: the cycle of output.mode torque.
  CycleStatus update(const JointState& state, double period_s, std::span<double> torque) noexcept;

  // ---- intake side (one producer at a time: the wrapper serialises its senders) ---------------
  /// Queues a message for the next cycle; false when the queue is full.
  bool enqueue(const IntakeMessage& message) noexcept { return intake_.push(message); }
  /// The timed chunks' slots: the intake loads a validated chunk here and then enqueues a
  /// kChunk message naming its slot.
  [[nodiscard]] ChunkPlayer& chunks() noexcept { return chunks_; }
  [[nodiscard]] const ChunkPlayer& chunks() const noexcept { return chunks_; }
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
  /// Which command is in force (the last the cycle took, or the chunk playing): what the command
  /// gate is told after a cycle (CommandGate::noteCycle) and what state and recordings report.
  [[nodiscard]] const CommandId& idInForce() const noexcept { return id_in_force_; }
  /// One non-real-time thread: what became of the next reset request the cycle decided; false
  /// when none is waiting.
  bool takeResetResult(ResetResult& result) noexcept {
    const ResetResult* front = reset_results_.front();
    if (front == nullptr) {
      return false;
    }
    result = *front;
    reset_results_.pop();
    return true;
  }
  /// The controller's clock at the last cycle [s since activation]; the real-time thread's (an
  /// observer's after the cycle), as the chunk timing records that cycle wrote.
  [[nodiscard]] double time() const noexcept { return time_s_; }
  /// What the law reads: the command in force with the gains the gain stage let through (the
  /// command in force itself when the stage is off), and force axes turned into reference and
  /// feedforward by the force stage, and the reference kept inside the walls (walls stage).
  /// Real-time thread, or between cycles.
  [[nodiscard]] const CommandBus& lawBus() const noexcept {
    return walls_active_ ? walls_bus_ : forcedBus();
  }
  /// The walls stage (virtual_walls.hpp): the distance to the nearest wall and the barrier's
  /// force of the last cycle.
  [[nodiscard]] const VirtualWalls& walls() const noexcept { return walls_; }
  /// The reflex stage (contact_reflex.hpp): its thresholds in force, whether and on what it
  /// tripped. Real-time thread, or between cycles.
  [[nodiscard]] const ContactReflex& reflex() const noexcept { return reflex_; }
  /// The largest contact force [N] and torque [N m] the contact reflex lets through now (its
  /// thresholds in force: the file's, or a command's for its phase); false when the reflex is off.
  /// Control thread.
  bool contactAllowance(double& force_n, double& torque_n_m) const noexcept;
  /// The contact-speed stage (contact_speed.hpp): the speed limit along the TCP's motion, the
  /// mass that set it, the share of the law let through and the braking of the last cycle.
  [[nodiscard]] const ContactSpeed& contactSpeed() const noexcept { return contact_speed_; }
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
  /// The wrist force/torque sensor's reading as the law's side sees it (wrist_sensor.hpp): the
  /// declared tool's weight and the tare taken off; at the TCP, base frame, force first [N, N m].
  /// Valid when the hardware gave a finite reading this cycle. Real-time thread, or between
  /// cycles.
  [[nodiscard]] const Vector6d& sensorWrench() const noexcept { return wrist_.wrench(); }
  [[nodiscard]] bool sensorWrenchValid() const noexcept { return wrist_.valid(); }
  /// Any thread: the hardware has given a wrist force/torque reading since construction.
  [[nodiscard]] bool sensorSeen() const noexcept { return wrist_.seen(); }
  /// The output stage (output.mode; the virtual arm of an admittance mode).
  [[nodiscard]] const OutputStage& output() const noexcept { return output_stage_; }
  /// In FAULT once the controlled stop has brought the arm to rest, or at once on a frozen or
  /// unusable state (the hold's gravity is that of a pose the arm may have left): the hardware's
  /// own hold (brakes) is asked for as well (CycleController::wantsHold). Not in admittance,
  /// whose position drives stop the arm themselves and whose law state is the virtual arm's.
  [[nodiscard]] bool holdRequested() const noexcept {
    const bool stopped = safe_hold_.atRest() && !isAdmittance(parameters_.output.mode);
    return (frozen_.frozen() || !state_usable_ || stopped) &&
           diagnostics_.state.load(std::memory_order_relaxed) == WrapperState::kFault;
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
  // Stages of update(), one file each (cycle/*.cpp).
  bool measure(const JointState& state) noexcept;  // measure.cpp
  void observe() noexcept;
  bool guardMotion() noexcept;  // guard.cpp
  bool guardSaturation() noexcept;
  void takeCommands() noexcept;  // commands.cpp
  /// A queued command that sets a group the running chunk drives ends the chunk (its reference
  /// at this cycle stays, at rest unless the command sets a velocity).
  void takeCommand(const IntakeMessage& message) noexcept;
  void takeChunk(const IntakeMessage& message) noexcept;
  void playChunk() noexcept;
  void watchdog() noexcept;
  bool takeReset(std::uint64_t number) noexcept;
  bool dropWaitingChunk(std::uint64_t sequence) noexcept;
  void resumeAfterReset() noexcept;
  bool checkSensor() noexcept;   // sensor.cpp
  bool checkContact() noexcept;  // reflex.cpp
  void retreatFromContact() noexcept;
  void rearmReflex() noexcept;
  void guardGains() noexcept;  // gains.cpp
  void applyForce() noexcept;  // force.cpp
  [[nodiscard]] const CommandBus& guardedBus() const noexcept {
    return gains_.enabled() ? gains_.lawBus() : active_;
  }
  [[nodiscard]] const CommandBus& forcedBus() const noexcept {
    return force_active_ ? force_bus_ : guardedBus();
  }
  void limitToWalls() noexcept;  // walls.cpp
  void brakeAtWalls() noexcept;
  bool runLaw() noexcept;      // law.cpp
  void compensate() noexcept;  // torque.cpp
  void govern() noexcept;
  void limitContactSpeed() noexcept;  // contact_speed.cpp
  bool shape() noexcept;
  void scaleIntoLimits() noexcept;  // effort_saturation: scale
  CycleStatus write(std::span<double> torque) noexcept;
  CycleStatus hold(std::span<double> torque) noexcept;

  void resetStages() noexcept;  // controller.cpp: activation's list of resets
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
  Diagnostics diagnostics_;

  SpscQueue<IntakeMessage> intake_{kIntakeCapacity};
  TripleBuffer<MeasuredPose> measured_;
  TripleBuffer<CommandBus> in_force_;

  // The stages, in cycle order: real-time thread only (or the lifecycle, between cycles).
  FrozenStateDetector frozen_;  // measure
  MomentumObserver observer_;   // measure
  WristSensor wrist_;           // measure
  StabilityGuard guard_;        // guard (motion, energy; saturation after shaping)
  CommandBus active_;           // commands: the command in force
  CommandId id_in_force_;       //   and which command it is
  CommandId waiting_chunk_id_;  //   the chunk waiting for its takeover time, if any
  ChunkPlayer chunks_;          //   the timed chunks
  CommandWatchdog watchdog_;    // watchdog
  SensorCheck sensor_check_;    // sensor
  ContactReflex reflex_;        // reflex
  double reflex_trip_s_ = 0.0;  //   when it tripped (controller clock)
  GainGuard gains_;             // gains
  ForceAxes force_;             // force
  CommandBus force_bus_;        //   the law's command when the force stage acts (Cartesian)
  bool force_active_ = false;   //   the force stage wrote force_bus_ this cycle
  VirtualWalls walls_;          // walls (reference) and barrier
  CommandBus walls_bus_;        //   the law's command when the walls stage runs (Cartesian)
  bool walls_active_ = false;   //   the walls stage wrote walls_bus_ this cycle
  MotionGovernor governor_;     // govern
  ContactSpeed contact_speed_;  // contact
  TorqueShaper shaper_;         // shape
  SafeHold safe_hold_;          // hold (FAULT)
  OutputStage output_stage_;    // output

  // The cycle's own state.
  JointState state_;
  bool state_usable_ = false;      // this cycle's state passed measure(), so input_ is current
  bool robot_stopped_ = false;     // this cycle's state says the robot stopped itself
  bool in_force_changed_ = false;  // active_ changed since the gain stage last saw it
  bool reset_pending_ = false;
  std::uint64_t reset_number_ = 0;            // the pending reset's number
  SpscQueue<ResetResult> reset_results_{16};  // to one non-real-time reader
  bool torque_clipped_ = false;  // the last cycle's torque was rate or effort limited or governed
  bool governed_ = false;        // the governor acted this cycle
  bool walled_ = false;          // the barrier acted this cycle
  bool slowed_ = false;          // the contact-speed stage acted this cycle
  comply_input input_{};
  comply_output law_output_{};  // the plugin's output this cycle
  JointVector torque_;
  JointVector law_torque_;  // this cycle's law output, before compensation
  JointVector scratch_;
  Vector6d tcp_twist_ = Vector6d::Zero();  // J dq at this cycle's state (Cartesian laws)
  double period_s_ = 0.001;
  double time_s_ = 0.0;
};

}  // namespace comply::pipeline
