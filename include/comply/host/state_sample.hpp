#pragma once
// One control cycle as the hosts report it (the state topic, the recording), taken on the control
// thread right after the cycle: fixed size, so filling and copying it never allocates.

#include <Eigen/Geometry>
#include <vector>

#include "comply/core/state.hpp"
#include "comply/hardware/control_loop.hpp"
#include "comply/model/data.hpp"
#include "comply/pipeline/command_gate.hpp"
#include "comply/pipeline/resolved_controller.hpp"
#include "comply/pipeline/wrapper.hpp"
#include "comply/transport/messages.hpp"

namespace comply::host {

struct StateSample {
  std::uint64_t cycle = 0;
  transport::Stamp wall;  ///< the host's clock at the cycle (simulated time under `comply sim`)
  pipeline::WrapperState state = pipeline::WrapperState::kInactive;
  JointState joints;
  JointVector torque;
  Eigen::Vector3d tcp_position = Eigen::Vector3d::Zero();
  Eigen::Quaterniond tcp_orientation = Eigen::Quaterniond::Identity();
  Vector6d tcp_twist = Vector6d::Zero();
  Vector6d contact_wrench = Vector6d::Zero();  ///< base frame
  transport::WrenchSource contact_wrench_source = transport::WrenchSource::kNone;
  Vector6d contact_wrench_tcp = Vector6d::Zero();   ///< the same in the TCP frame
  Vector6d contact_wrench_task = Vector6d::Zero();  ///< ... in the task frame in force
  /// [Hz] the estimate's first-order bandwidth (observer K_O / 2 pi, sensor filter_hz); 0: raw.
  double contact_wrench_bandwidth_hz = 0.0;
  pipeline::PassivitySnapshot passivity;  ///< the energy tank's account after the cycle
  bool walls = false;            ///< walls or boxes configured or commanded (virtual_walls.hpp)
  double wall_distance_m = 0.0;  ///< measured TCP to the nearest wall; < 0 past one
  Eigen::Vector3d wall_force = Eigen::Vector3d::Zero();     ///< the barrier's [N], base frame
  Eigen::Vector3d workspace_min = Eigen::Vector3d::Zero();  ///< the commanded box [m]; 0: none
  Eigen::Vector3d workspace_max = Eigen::Vector3d::Zero();
  bool reflex = false;  ///< the contact reflex is on (contact_reflex.hpp); else the rest is 0
  Eigen::Vector3d reflex_force_threshold = Eigen::Vector3d::Zero();   ///< [N] task x y z
  Eigen::Vector3d reflex_torque_threshold = Eigen::Vector3d::Zero();  ///< [N m]
  bool reflex_tripped = false;                                        ///< until a reset
  transport::ReflexReaction reflex_reaction = transport::ReflexReaction::kNone;
  Vector6d reflex_wrench = Vector6d::Zero();  ///< what tripped it, task frame then
  double contact_speed_limit_m_per_s = 0.0;   ///< along the TCP's motion (contact_speed.hpp)
  double contact_speed_share = 1.0;           ///< of the law's torque let through
  double contact_speed_brake_n = 0.0;         ///< braking against the TCP's motion
  pipeline::CommandId reference;              ///< the command in force: its number and exact stamp
  std::uint32_t reference_fields = 0;
  Eigen::Vector3d reference_position = Eigen::Vector3d::Zero();
  Eigen::Quaterniond reference_orientation = Eigen::Quaterniond::Identity();
  JointVector reference_joint_position;
};

/// Fills StateSamples from a wrapper (the wrist sensor's reading as its cycle compensated it
/// included); the control thread's scratch lives here.
template <typename Command>
class StateSampler {
 public:
  explicit StateSampler(const pipeline::Wrapper<Command>& wrapper);

  /// The cycle `record` reported, the joint state it measured (`measured`) and `stamp`; on the
  /// control thread, after the cycle. No allocation.
  void fill(const hardware::CycleRecord& record, const JointState& measured, transport::Stamp stamp,
            StateSample& sample) noexcept;

 private:
  const pipeline::Wrapper<Command>& wrapper_;
  /// The pose of the measured joints while the controller is inactive (its own model data then
  /// stays where the last active cycle left it).
  model::Data inactive_pose_;
};

/// The state topic's message of `sample` (allocates: off the control thread).
transport::ControllerStateMessage stateMessage(const StateSample& sample,
                                               const pipeline::ResolvedController& resolved);

/// A command gate's outcome as the wire's CommandOutcome.
transport::CommandOutcomeMessage outcomeMessage(const pipeline::CommandOutcome& outcome);
/// A chunk's timing record as a ChunkTiming message, its times on the host's clock (zero for a
/// time not said, or never reached).
transport::ChunkTimingMessage chunkTimingMessage(const pipeline::NotedChunk& noted);
/// Gate outcomes (CommandGate::takeOutcomes()) as the wire's CommandOutcomes, in order.
std::vector<transport::CommandOutcomeMessage> outcomeMessages(
    const std::vector<pipeline::CommandOutcome>& outcomes);

extern template class StateSampler<CartesianCommand>;
extern template class StateSampler<JointCommand>;

}  // namespace comply::host
