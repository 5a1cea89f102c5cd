#pragma once
// A robot simulated in MuJoCo behind the same read/write interface a real arm's driver offers.
//
//   SimulatedRobot robot(model::loadRobotDescription("fr3"), PlantOptions{});
//   loop: robot.read(state); wrapper.update(state, period, torque); robot.write(torque);
//         robot.step();
//
// The plant is the robot's URDF (the same file the controller's model comes from) plus what the
// URDF cannot say: joint viscous damping, rotor armature and Coulomb friction from robot.yaml
// (`joint_dynamics`), so that a controller's friction and gravity compensation have real work to
// do. Effort is applied as a generalised joint force clamped to the URDF effort limit, held over
// the physics substeps of one control period. Deterministic: the same options (and seed) give the
// same trajectory, bit for bit.

#include <mujoco/mujoco.h>

#include <Eigen/Geometry>
#include <cstdint>
#include <memory>
#include <random>
#include <span>
#include <string>
#include <vector>

#include "comply/core/actuator_command.hpp"
#include "comply/core/commands.hpp"
#include "comply/hardware/hardware_interface.hpp"
#include "comply/model/robot_description.hpp"
#include "comply/sim/scene_xml.hpp"

namespace comply::sim {

struct PlantOptions {
  double control_period_s = 0.001;  ///< one read/write cycle [s]
  int substeps = 1;                 ///< physics steps per control period (timestep = period / n)
  bool joint_dynamics = true;       ///< damping, armature, frictionloss from robot.yaml
  /// Multiplies robot.yaml's Coulomb friction (frictionloss); 0 removes it while keeping damping
  /// and armature, which the plant's stability at 1 kHz relies on. For ablations.
  double friction_scale = 1.0;
  /// The effort read back is what a joint-torque sensor between gear and link measures (FR3,
  /// iiwa and Rizon have one): the drive's torque less the joint's friction, damping and rotor
  /// inertia, averaged over the period. False: the drive's torque itself.
  bool link_side_torque = false;
  std::string tip_frame;  ///< TCP body for pose and tool wrench; default robot.tcp_frame
  /// What the drives take (core/actuator_command.hpp): torque motors (the default); drives with
  /// an onboard PD (joint_pd, which take a torque as well: kp = kd = 0); or a position or a
  /// velocity servo, a position-controlled arm as UR, xArm or Kinova in position mode are.
  OutputMode actuation = OutputMode::kTorque;
  /// position, velocity: the servo's bandwidth [Hz]. Each joint runs a PID with a triple pole
  /// there for its own inertia at home, on top of the plant's own gravity and Coriolis torque
  /// (the vendor's model), every physics substep.
  double servo_bandwidth_hz = 20.0;
  /// The wrist sensor's offset, fixed in the sensor (TCP frame), force first [N, N m]: what a
  /// tare removes.
  Vector6d wrench_sensor_offset = Vector6d::Zero();
  SceneOptions scene;
  /// Measurement noise (Gaussian, standard deviation) drawn from a generator seeded with `seed`.
  double position_noise_rad = 0.0;
  double velocity_noise_rad_per_s = 0.0;
  std::uint64_t seed = 0;
};

class SimulatedRobot final : public hardware::HardwareInterface {
 public:
  /// Builds and loads the scene, starts at the robot's home pose at rest. Throws SimError (scene,
  /// MuJoCo) or model::ModelError (URDF) with a clear message.
  SimulatedRobot(const model::RobotDescription& robot, const PlantOptions& options);
  ~SimulatedRobot() override;
  SimulatedRobot(const SimulatedRobot&) = delete;
  SimulatedRobot& operator=(const SimulatedRobot&) = delete;

  [[nodiscard]] int dof() const noexcept override { return static_cast<int>(qpos_address_.size()); }
  /// Position, velocity (plus noise, if configured) and the effort applied in the last period.
  bool read(JointState& state) noexcept override;
  /// The sample counter a driver has: the control periods stepped when read() took its sample
  /// (one per step(), whatever the arm does), so a stream that stops is told from an arm at rest.
  bool readSequence(std::uint64_t& sequence) noexcept override {
    sequence = read_sequence_;
    return true;
  }
  /// Applies `torque` [N m | N] from the next step() on, clamped to the URDF effort limit.
  /// Refuses (returns false, keeps the previous torque) a wrong size or a non-finite entry, and
  /// any torque on position or velocity servos.
  bool write(std::span<const double> torque) noexcept override;
  [[nodiscard]] bool accepts(OutputMode mode) const noexcept override;
  /// A command in the plant's actuation (PlantOptions::actuation); the drives follow it every
  /// physics substep until the next one. Refuses another mode, a wrong size or a non-finite
  /// entry.
  bool writeCommand(const ActuatorCommand& command) noexcept override;

  /// A brake: the controlled joints stay where they are when hold() is first called, at rest,
  /// their drives carrying gravity (the applied effort reads so), until the next write().
  bool hold() noexcept override;
  /// Advances one control period (`substeps` physics steps). No heap allocation.
  void step() noexcept;
  /// Puts the robot at `position` (rad | m, `joints` order) at rest, held by its drives (the
  /// applied effort is the gravity torque of that pose until the next write()). The simulated
  /// time is kept. Throws std::invalid_argument on a wrong size.
  void setJointPositions(std::span<const double> position);

  [[nodiscard]] double simTime() const noexcept { return data_->time; }
  [[nodiscard]] double controlPeriod() const noexcept { return control_period_s_; }
  /// TCP pose in the robot's base frame, from the simulator (not from the controller's model).
  [[nodiscard]] Eigen::Isometry3d tcpPose() const noexcept;
  /// Sum of the contact wrenches the environment exerts on the tool (the TCP body and everything
  /// attached below it): force [N] and torque about the TCP origin [N m], base frame.
  [[nodiscard]] Vector6d toolContactWrench() const noexcept;
  /// A wrist force/torque sensor between the TCP body and its parent, as a real one reads: the
  /// wrench the tool subtree takes from its parent (MuJoCo's interaction force, cfrc_int), turned
  /// into the wrench on the tool from everything else, plus the sensor's offset
  /// (PlantOptions::wrench_sensor_offset). At rest without contact that is the tool's weight and
  /// the offset; the contact and the applied wrench (setExternalWrench) add to it, and while the
  /// tool accelerates its inertial force -m a does. The controller takes the declared tool's
  /// weight and a tare off. Base frame, about the TCP, force first. Real-time.
  bool readWrench(Vector6d& wrench) noexcept override;
  /// A wrench the environment exerts on the tool at the TCP from the next step() on: base frame,
  /// force first, torque about the TCP origin [N, N m] (a push by hand, a known load; the tests'
  /// ground truth for the external-wrench estimate). Zero removes it. Not a contact: it is not in
  /// toolContactWrench(), but the wrist sensor (readWrench) feels it.
  void setExternalWrench(const Vector6d& wrench) noexcept { external_wrench_ = wrench; }
  /// Effort the plant applied in the last period [N m | N], after clamping.
  [[nodiscard]] std::span<const double> appliedEffort() const noexcept { return applied_; }
  [[nodiscard]] std::span<const double> effortLimit() const noexcept { return effort_limit_; }

  [[nodiscard]] const mjModel& mujocoModel() const noexcept { return *model_; }
  [[nodiscard]] const mjData& mujocoData() const noexcept { return *data_; }
  /// For scene objects a task moves (e.g. a displaced fixture); call forward() after edits.
  [[nodiscard]] mjModel& mutableMujocoModel() noexcept { return *model_; }
  void forward() noexcept;

 private:
  void configureServos(const PlantOptions& options);
  void pinHeldJoints() noexcept;
  void applyExternalWrench() noexcept;
  /// link_side_torque: adds this substep's joint-torque sensor reading to link_torque_.
  void senseLinkTorque() noexcept;
  /// The drives' torque for this substep (joint_pd, position, velocity), into applied_.
  void driveJoints(double since_write_s) noexcept;

  struct MujocoDeleter {
    void operator()(mjModel* model) const noexcept { mj_deleteModel(model); }
    void operator()(mjData* data) const noexcept { mj_deleteData(data); }
  };

  std::unique_ptr<mjModel, MujocoDeleter> model_;
  std::unique_ptr<mjData, MujocoDeleter> data_;
  double control_period_s_ = 0.001;
  int substeps_ = 1;
  std::vector<int> qpos_address_;
  std::vector<int> dof_address_;
  std::vector<double> effort_limit_;
  std::vector<double> applied_;
  /// link_side_torque: the joint-torque sensors' reading summed over this period's substeps, and
  /// the joints' friction forces of one substep (by MuJoCo dof).
  bool link_side_torque_ = false;
  bool link_torque_sensed_ = false;  ///< a step has filled link_torque_
  std::uint64_t steps_ = 0;          ///< control periods stepped
  std::uint64_t read_sequence_ = 0;  ///< steps_ at the last read()
  std::vector<double> link_torque_;
  std::vector<double> dof_friction_;
  bool braked_ = false;
  std::vector<double> held_position_;  ///< per controlled joint, while braked
  std::vector<bool> tool_body_;        ///< per MuJoCo body: part of the tool (TCP subtree)
  int base_body_ = 0;
  int tip_body_ = 0;
  std::mt19937_64 noise_generator_;
  std::normal_distribution<double> unit_normal_{0.0, 1.0};
  double position_noise_rad_ = 0.0;
  double velocity_noise_rad_per_s_ = 0.0;
  Vector6d external_wrench_ = Vector6d::Zero();
  Vector6d wrench_sensor_offset_ = Vector6d::Zero();  ///< TCP frame

  // Drives other than torque motors (PlantOptions::actuation).
  OutputMode actuation_ = OutputMode::kTorque;
  ActuatorCommand drive_command_;  ///< the last command written
  bool drive_commanded_ = false;   ///< a command since the start or the last hold
  double since_write_s_ = 0.0;     ///< time since that command [s]
  std::vector<double> servo_kp_, servo_ki_, servo_kd_;  ///< per joint, from the bandwidth
  std::vector<double> servo_integral_;                  ///< of the position error [rad s]
  std::vector<double> velocity_reference_;              ///< velocity servo: integrated command
};

}  // namespace comply::sim
