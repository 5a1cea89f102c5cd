#pragma once
// The stability guard's energy rule: an oscillation whose energy keeps growing while the command
// in force holds still. This is what a loop that generates energy looks like (a law with too
// little damping for the control period and the drives' delay, a plugin with a sign error): the
// other rules (overspeed, past a limit, saturation) see it only once it is large.
//
// Per window of window_s:
//   kinetic  the peak of  1/2 sum_i m_i dq_i^2  (m_i each joint's lightest inertia: a weighting
//            that needs no mass matrix in the cycle; only its growth counts)
//   input    whether the command the law acts on (the whole bus: reference, rates, feedforward,
//            gains, task frame, nullspace) changed at all
//   swing    sign reversals of the velocity of the joint that held most of the peak (a reversal
//            counts once the speed exceeds a tenth of that joint's previous peak: not noise)
// A window grows when its kinetic peak is at least kStepGrowth x the previous one, the command held
// still through it, and its dominant joint swung at least twice. A run of at least kMinRunWindows
// growing windows whose kinetic peak rose `growth` times from where the run started, above
// floor_j, is a FAULT, at the end of the first window where all three hold (the run has
// kMinRunWindows windows, its energy has grown `growth` times, and is above floor_j).
//
// Only a command that holds still makes the arm's energy the loop's own: a stream of commands
// (a policy at 10 Hz and up, a chunk playing, the force stage acting) feeds energy in at will, and
// a rule that judged it by how the stream varies tripped on the soak's random stream of valid
// poses. While a stream flows, the rule waits; the other rules stand.
// A push or a commanded step (the arm rises for a window or two, then settles), a decaying
// oscillation or an arm moved faster by hand (no swing) never makes a run.
//
// Limits (docs/safety.md): a growth slower than kStepGrowth per window is left to the other rules;
// an arm shaken by hand with ever larger swings looks the same as a loop that generates energy.
//
// Real-time: update() allocates nothing, takes no lock, never throws.

#include <span>

#include "comply/core/capacity.hpp"

namespace comply::pipeline {

class EnergyWatch {
 public:
  struct Options {
    double window_s = 0.25;  ///< 0: off
    double growth = 4.0;     ///< kinetic peak over a run of growing windows [-]
    double floor_j = 0.05;   ///< the kinetic peak must exceed this [J]
  };
  /// A window must rise at least this much over the one before to continue a run: the peaks of
  /// a steady oscillation and of noise do not.
  static constexpr double kStepGrowth = 1.1;
  /// A run must be this long: an admittance arm pushed by a hand swings up within a window too.
  static constexpr int kMinRunWindows = 3;

  /// `inertia` each joint's weight [kg m^2 | kg]; entries <= 0 count as 1.
  void configure(const Options& options, std::span<const double> inertia) noexcept;
  /// Forgets every window (activation, reset).
  void reset() noexcept;
  [[nodiscard]] bool enabled() const noexcept { return options_.window_s > 0.0; }

  /// One cycle: the measured joint velocities, whether the command the law acts on changed since
  /// the last cycle, and the period. True when a run reached `growth`: the loop is generating
  /// energy.
  bool update(std::span<const double> velocity, bool command_changed, double period_s) noexcept;

  /// The run that tripped: its start and end kinetic peaks [J], its length [s] and the joint.
  struct Run {
    double from_j = 0.0;
    double to_j = 0.0;
    double duration_s = 0.0;
    int joint = 0;
  };
  [[nodiscard]] const Run& run() const noexcept { return tripped_; }

 private:
  void closeWindow() noexcept;
  void startWindow() noexcept;  // clears what one window gathers
  bool tripped() const noexcept;

  Options options_;
  int dof_ = 0;
  JointVector inertia_;
  // The window being filled.
  double elapsed_s_ = 0.0;
  double kinetic_peak_j_ = 0.0;
  bool input_changed_ = false;  // the command changed in this window
  JointVector joint_peak_j_;    // each joint's share at its own peak
  JointVector reversals_;       // sign reversals this window
  JointVector last_sign_;       // -1, 0 (not yet), +1
  JointVector swing_speed_;     // previous window's peak speed per joint: the reversal scale
  JointVector speed_peak_;      // this window's peak speed per joint
  // The windows closed.
  bool have_previous_ = false;
  double previous_kinetic_j_ = 0.0;
  double run_from_j_ = 0.0;  // kinetic peak of the window before the run (0: no run)
  double run_to_j_ = 0.0;
  int run_windows_ = 0;
  int run_joint_ = 0;
  Run tripped_;
};

}  // namespace comply::pipeline
