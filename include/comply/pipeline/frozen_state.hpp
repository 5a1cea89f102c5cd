#pragma once
// Stage "measure", its first check: a stale sensor stream. A driver that keeps resending its last
// sample makes the law act on a state the arm has left; the cycle must stop trusting it.
//
//   with a sample counter (JointState::sequence_valid): stale once the counter has stood still
//     for frozen_state_timeout_s, however the torque moves (a new sample is fresh however alike
//     it is: an arm at rest, or pressing on a wall, repeats its encoders);
//   without one: stale once the state repeats bit for bit for frozen_state_timeout_s while the
//     torque moved kFrozenStateTorqueChangeNm, or while its own velocity should have carried a
//     joint kFrozenStateMotionRad. A simulator or an arm at rest repeats its state only while the
//     torque repeats too; a driver that resends its last sample does not.
//
// Real-time: check() allocates nothing, takes no lock, never throws.

#include <cstdint>

#include "comply/core/capacity.hpp"
#include "comply/core/state.hpp"

namespace comply::pipeline {

/// How far the output torque must move [N m, any joint] while the joint state stays bit-identical
/// for frozen_state_timeout_s before the state counts as frozen.
inline constexpr double kFrozenStateTorqueChangeNm = 1.0;
/// How far [rad | m] the reported velocity must carry a joint over frozen_state_timeout_s for
/// an unchanged position to betray a stale stream (a thousand times an FR3 encoder's resolution).
inline constexpr double kFrozenStateMotionRad = 1e-4;

class FrozenStateDetector {
 public:
  /// `timeout_s` <= 0: off.
  explicit FrozenStateDetector(double timeout_s) noexcept : timeout_s_(timeout_s) {}

  /// Forgets what it has seen (activation).
  void reset() noexcept;
  /// Whether `state` is stale, given the last cycle's state and the torque the last cycle wrote
  /// (computed from that state), at controller time `time_s`.
  bool check(const JointState& state, const JointState& last_state, const JointVector& last_torque,
             double time_s) noexcept;
  /// The last check() found the stream stale: its velocity is stale too.
  [[nodiscard]] bool frozen() const noexcept { return frozen_; }

 private:
  bool repeatsTooLong(const JointState& state, const JointState& last_state,
                      const JointVector& last_torque, double time_s) noexcept;
  bool sequenceStale(const JointState& state, double time_s) noexcept;

  double timeout_s_ = 0.0;
  bool frozen_ = false;
  // Without a sample counter: cycles the state has repeated, since when, the torque then.
  int repeated_cycles_ = 0;
  double repeated_since_s_ = 0.0;
  JointVector torque_when_repeated_;
  // With one: its last value and since when.
  bool sequence_seen_ = false;
  std::uint64_t last_sequence_ = 0;
  double sequence_since_s_ = 0.0;
};

}  // namespace comply::pipeline
