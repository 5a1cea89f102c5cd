#include "comply/pipeline/frozen_state.hpp"

#include <cstring>

namespace comply::pipeline {
namespace {

/// Bit for bit: a NaN effort (a robot without torque sensing) repeats as well as a number.
bool sameBits(const JointVector& a, const JointVector& b) noexcept {
  return a.size() == b.size() &&
         std::memcmp(a.data(), b.data(), static_cast<std::size_t>(a.size()) * sizeof(double)) == 0;
}

}  // namespace

void FrozenStateDetector::reset() noexcept {
  repeated_cycles_ = 0;
  frozen_ = false;
  sequence_seen_ = false;
}

bool FrozenStateDetector::check(const JointState& state, const JointState& last_state,
                                const JointVector& last_torque, double time_s) noexcept {
  return state.sequence_valid ? sequenceStale(state, time_s)
                              : repeatsTooLong(state, last_state, last_torque, time_s);
}

bool FrozenStateDetector::repeatsTooLong(const JointState& state, const JointState& last_state,
                                         const JointVector& last_torque, double time_s) noexcept {
  const bool repeated = sameBits(state.position, last_state.position) &&
                        sameBits(state.velocity, last_state.velocity) &&
                        sameBits(state.effort, last_state.effort);
  if (!repeated || timeout_s_ <= 0.0) {
    repeated_cycles_ = 0;
    frozen_ = false;
    return false;
  }
  if (repeated_cycles_++ == 0) {
    repeated_since_s_ = time_s;
    torque_when_repeated_ = last_torque;
  }
  if (frozen_) {
    return true;
  }
  if (time_s - repeated_since_s_ < timeout_s_) {
    return false;
  }
  // Stale either way: the torque moved and the state did not answer, or the state reports a
  // velocity under which its own position would have moved, and it did not (an arm pushed by
  // hand while its stream repeats a moving sample: the law's torque need not change for that).
  const double unmoved_s = time_s - repeated_since_s_;
  frozen_ =
      (last_torque - torque_when_repeated_).cwiseAbs().maxCoeff() > kFrozenStateTorqueChangeNm ||
      state.velocity.cwiseAbs().maxCoeff() * unmoved_s > kFrozenStateMotionRad;
  return frozen_;
}

bool FrozenStateDetector::sequenceStale(const JointState& state, double time_s) noexcept {
  if (timeout_s_ <= 0.0 || !sequence_seen_ || state.sequence != last_sequence_) {
    last_sequence_ = state.sequence;
    sequence_seen_ = true;
    sequence_since_s_ = time_s;
    frozen_ = false;
    return false;
  }
  frozen_ = time_s - sequence_since_s_ >= timeout_s_;
  return frozen_;
}

}  // namespace comply::pipeline
