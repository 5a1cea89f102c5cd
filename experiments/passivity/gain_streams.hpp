#pragma once
// The command streams of the passivity experiment, as a policy would send them at its own rate.
//
//   PumpStream        an adversarial gain schedule: the reference held at a fixed target, and
//                     with every command the gains chosen from the sign of e . v (e = TCP - target,
//                     v the TCP velocity): compliant while the tool moves away from the target,
//                     stiff while it returns. Each switch to stiff comes at a large error, so
//                     without a guard every swing pumps energy into the arm.
//   SmoothTaskStream  a task as one would send it: the reference out and back along a smooth line,
//                     the stiffness stepped once, damping ratio 1.

#include <Eigen/Geometry>
#include <optional>

#include "comply/core/commands.hpp"
#include "comply/task/command_source.hpp"

namespace comply::experiments::passivity {

/// What the adversarial schedule switches.
enum class PumpedGain {
  kStiffness,  ///< translational K = 100 N/m (away) or 3000 N/m (returning), all axes
  /// K = diag(100, 3000, 3000) in the task frame; the frame turns 90 deg about z so that the
  /// stiff axis lies along base x (the motion) while the tool returns, the soft one while it
  /// moves away
  kTaskFrame,
};

class PumpStream final : public task::CartesianSource {
 public:
  /// The reference: `target` with `orientation`, sent with the first command; later commands
  /// carry gains only (a policy streaming gains), so the reference stays in force. The rotational
  /// stiffness is `controller`'s (the controller file's initial command).
  PumpStream(PumpedGain pumped, const Eigen::Vector3d& target,
             const Eigen::Quaterniond& orientation, const CartesianCommand& controller);

  /// Always a command. The velocity is the measured TCP's displacement since the last call
  /// divided by the time between them: what a policy at this rate can know.
  std::optional<CartesianCommand> next(double t_s, const MeasuredPose& measured) override;

  /// The gains while the tool moves away (`returning` false) or returns; the run starts with the
  /// former, as the controller's initial gains.
  [[nodiscard]] CartesianCommand gains(bool returning) const;

 private:
  PumpedGain pumped_;
  Eigen::Vector3d target_;
  Eigen::Quaterniond orientation_;
  CartesianCommand controller_;
  bool first_ = true;
  double previous_t_s_ = 0.0;
  Eigen::Vector3d previous_tcp_ = Eigen::Vector3d::Zero();
};

class SmoothTaskStream final : public task::CartesianSource {
 public:
  /// From `start` along base x to `start` + kStrokeM and back in kMotionS, with the orientation
  /// held; the stiffness steps from kStiffnessBefore to kStiffnessAfter at the far end. The
  /// rotational stiffness is `controller`'s (the controller file's initial command).
  SmoothTaskStream(const Eigen::Vector3d& start, const Eigen::Quaterniond& orientation,
                   const CartesianCommand& controller);

  static constexpr double kStrokeM = 0.10;
  static constexpr double kMotionS = 2.0;
  static constexpr double kHoldS = 1.0;  ///< after the motion, the reference at the start
  static constexpr double kStiffnessBefore = 500.0;  ///< N/m
  static constexpr double kStiffnessAfter = 2000.0;  ///< N/m, from kMotionS / 2 on

  std::optional<CartesianCommand> next(double t_s, const MeasuredPose& measured) override;
  [[nodiscard]] double motionEndTime() const override { return kMotionS; }

  /// The gains at `t_s`: translational stiffness as above, the controller's rotational stiffness,
  /// damping ratio 1.
  [[nodiscard]] CartesianCommand gains(double t_s) const;
  /// Where the reference is at `t_s`.
  [[nodiscard]] Eigen::Vector3d reference(double t_s) const;

 private:
  Eigen::Vector3d start_;
  Eigen::Quaterniond orientation_;
  CartesianCommand controller_;
};

/// Copies the gain fields (stiffness, damping, task frame) of `from` into `to`.
void copyGains(const CartesianCommand& from, CartesianCommand& to);

}  // namespace comply::experiments::passivity
