#pragma once
// Stage "measure", the wrist sensor: the hardware's force/torque reading (JointState::wrench, the
// wrench on the tool at the TCP, base frame, or TCP frame with wrench_in_tcp) as the law's side
// uses it.
//
//   tool     the declared payload (compensation.payload) is the tool beyond the sensor: its weight
//            at its centre of mass, m g and r x m g about the TCP, comes off every cycle, turned
//            with the tool, so a turning tool reads no change of weight;
//   filter   wrench_sensor.filter_hz: a first-order low-pass on what is left, started from the
//            first reading (a cycle without one holds it);
//   tare     a request (Wrapper::tare) takes what remains, at rest and without contact that is the
//            sensor's own offset, as the zero. The offset is fixed in the sensor, which turns with
//            the TCP: it is kept in the TCP frame and turned into the base frame every cycle.
//
// What is left is the environment's wrench (plus the tool's inertial force while it accelerates,
// which admittance gives back: virtual_arm.cpp).
//
// Real-time: sense() and tare() allocate nothing, take no lock, never throw.

#include <atomic>

#include "comply/core/capacity.hpp"
#include "comply/core/state.hpp"
#include "comply/model/data.hpp"
#include "comply/pipeline/resolved_controller.hpp"

namespace comply::pipeline {

class WristSensor {
 public:
  explicit WristSensor(const ResolvedController& resolved) noexcept;

  /// The low-pass starts again from the next reading (activation); the tare stays.
  void reset() noexcept { filtered_ = false; }
  /// No reading this cycle until sense() has read one (a tare needs this cycle's reading).
  void invalidate() noexcept { valid_ = false; }
  /// This cycle's reading from `state`, the tool's weight and the tare taken off at the pose in
  /// `data` (the model updated at `state`).
  void sense(const JointState& state, const model::Data& data, double period_s) noexcept;
  /// What the sensor reads now, less the tool's weight, becomes its zero (no reading this cycle:
  /// the zero in force stays).
  void tare(const model::Data& data) noexcept;

  /// At the TCP, base frame, force first [N, N m]; valid() when this cycle gave a finite reading.
  [[nodiscard]] const Vector6d& wrench() const noexcept { return wrench_; }
  [[nodiscard]] bool valid() const noexcept { return valid_; }
  /// Any thread: the hardware has given a reading since construction.
  [[nodiscard]] bool seen() const noexcept { return seen_.load(std::memory_order_relaxed); }

 private:
  const ResolvedController& resolved_;
  /// The declared tool's weight beyond the sensor [N, base frame]; zero when none is declared or
  /// it is not on the sensor. From the configuration, once.
  Eigen::Vector3d tool_weight_n_ = Eigen::Vector3d::Zero();
  Vector6d untared_ = Vector6d::Zero();  // this cycle's reading less the tool's weight
  Vector6d wrench_ = Vector6d::Zero();   // ... less the tare
  Vector6d tare_in_tcp_ = Vector6d::Zero();
  bool valid_ = false;
  bool filtered_ = false;  // the low-pass has a reading to start from
  std::atomic<bool> seen_{false};
};

}  // namespace comply::pipeline
