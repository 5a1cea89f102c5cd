#pragma once
// Stage "gains": what stands between the gains a command asks for and the gains the control law
// sees, so that it holds for every law, generated C included, without the law knowing. Each
// cycle a change of gains goes through two limits in turn:
//
//   ramps  every stiffness, damping and damping-ratio entry moves toward the command at most at
//          its configured rate, the task frame at most at its angular rate (gain_ramps.hpp).
//   tank   the energy tank pays for what the stiffness and frame part of that step injects into
//          the springs; what it cannot pay is held back this cycle and offered again the next
//          (energy_tank.hpp). Damping injects nothing and is only ramped.
//
// A new command's motion fields and feedforward pass at once; only its gains are held. With
// nothing to hold back, the law reads the command bit for bit. Real-time: no allocation, no
// lock, no exception.

#include <Eigen/Geometry>

#include "comply/core/capacity.hpp"
#include "comply/core/state.hpp"
#include "comply/model/data.hpp"
#include "comply/pipeline/command_bus_variant.hpp"
#include "comply/pipeline/config.hpp"
#include "comply/pipeline/diagnostics.hpp"
#include "comply/pipeline/energy_tank.hpp"

namespace comply::pipeline {

class GainGuard {
 public:
  GainGuard(const GainRampConfig& ramps, const PassivityConfig& passivity);

  /// Whether the stage runs at all: off, the law reads the command in force itself.
  [[nodiscard]] bool enabled() const noexcept { return ramps_.enabled || passivity_.enabled; }
  /// The model quantities the stage needs on top of the law's.
  [[nodiscard]] model::Quantity quantities(bool cartesian) const noexcept;

  /// On activation: the gains in force are the command's, the tanks hold their initial energy.
  void reset(const CommandBus& command, const model::Data& data, const JointState& state,
             Diagnostics& diagnostics) noexcept;
  /// A new command in force (`command`): its motion fields and feedforward pass at once; its
  /// gains become the target the ramps and the tank move toward.
  void takeCommand(const CommandBus& command) noexcept;
  /// One cycle at the measured state (`data` holds the pose and, with ratios, M and J).
  /// `torque_clipped`: the last cycle's torque, which moved the arm to `state`, was rate or effort
  /// limited, so the law's damping did not all reach the arm.
  void update(const CommandBus& command, const model::Data& data, const JointState& state,
              double period_s, bool torque_clipped, Diagnostics& diagnostics) noexcept;

  /// The bus the law reads.
  [[nodiscard]] const CommandBus& lawBus() const noexcept { return law_; }

 private:
  /// Every stiffness entry of a bus, for the fraction of a change in force: the two task blocks
  /// and the nullspace (Cartesian) or the joints.
  using StiffnessStack = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 18 + kMaxDof, 1>;

  /// Move the gains in force toward `target`; true once they are the target's.
  bool updateCartesian(const comply_cartesian_command& target, const model::Data& data,
                       const JointState& state, double period_s) noexcept;
  bool updateJoint(const comply_joint_command& target, const JointState& state,
                   double period_s) noexcept;
  static StiffnessStack stiffnessOf(const CommandBus& bus) noexcept;
  [[nodiscard]] double gainFraction() const noexcept;
  void publish(Diagnostics& diagnostics) const noexcept;

  GainRampConfig ramps_;
  PassivityConfig passivity_;
  CommandBus law_;
  bool pending_ = false;   ///< the gains in force are not yet the command's
  double fraction_ = 1.0;  ///< gainFraction() as of the last change
  EnergyTank tank_;

  // The commanded stiffness and task frame, and how far the gains in force were from them when
  // they were commanded.
  StiffnessStack target_stiffness_;
  double from_distance_ = 0.0;
  Eigen::Quaterniond target_frame_ = Eigen::Quaterniond::Identity();
  double from_angle_ = 0.0;  ///< [rad]
};

}  // namespace comply::pipeline
