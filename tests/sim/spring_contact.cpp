#include "spring_contact.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <stdexcept>

#include "comply/pipeline/contact_speed.hpp"
#include "governed_arm.hpp"
#include "sim_support.hpp"

namespace comply::testing {
namespace {

constexpr int kSubsteps = 16;           // 62.5 us: the probe-plate contact's time constant 125 us
constexpr double kProbeOffsetM = 0.05;  // the ball's centre, out along the TCP's z
constexpr double kProbeRadiusM = 0.01;
constexpr double kProbeMassKg = 0.01;
constexpr double kPlateMassKg = 0.1;
constexpr double kPlateHalfThicknessM = 0.005;
constexpr int kCyclesAfterTouch = 300;
constexpr int kMaxCycles = 4000;

/// The gap between the probe and the plate: room to reach the commanded speed first.
double gapFor(double speed_m_per_s) {
  return 0.02 + 0.15 * speed_m_per_s;
}

std::string xyz(const Eigen::Vector3d& v) {
  return std::to_string(v.x()) + " " + std::to_string(v.y()) + " " + std::to_string(v.z());
}

void writeFile(const std::filesystem::path& file, const std::string& text) {
  std::ofstream out(file);
  out << text;
  if (!out) {
    throw std::runtime_error("cannot write " + file.string());
  }
}

std::filesystem::path writeProbe(const std::filesystem::path& folder) {
  const std::filesystem::path file = folder / "probe.xml";
  writeFile(file, "<mujocoinclude>\n  <geom name=\"comply_probe\" type=\"sphere\" pos=\"0 0 " +
                      std::to_string(kProbeOffsetM) + "\" size=\"" + std::to_string(kProbeRadiusM) +
                      "\" mass=\"" + std::to_string(kProbeMassKg) +
                      "\" solref=\"0.000125 1\" rgba=\"0.85 0.2 0.15 1\"/>\n</mujocoinclude>\n");
  return file;
}

/// The plate `gap_m` ahead of the probe along the scene's axis, on its spring.
std::filesystem::path writePlate(const SpringScene& scene, double gap_m) {
  const Eigen::Vector3d centre =
      scene.tcp + (kProbeOffsetM + kProbeRadiusM + gap_m + kPlateHalfThicknessM) * scene.axis;
  const std::filesystem::path file = scene.folder / "spring.xml";
  writeFile(file, "<mujocoinclude>\n  <body name=\"comply_spring_plate\" pos=\"" + xyz(centre) +
                      "\" zaxis=\"" + xyz(scene.axis) +
                      "\">\n    <joint name=\"comply_spring\" type=\"slide\" axis=\"0 0 1\" "
                      "stiffness=\"" +
                      std::to_string(kHandStiffnessNPerM) +
                      "\" damping=\"2\"/>\n    <geom name=\"comply_spring_face\" type=\"box\" "
                      "size=\"0.04 0.04 " +
                      std::to_string(kPlateHalfThicknessM) + "\" mass=\"" +
                      std::to_string(kPlateMassKg) +
                      "\" solref=\"0.000125 1\" rgba=\"0.9 0.75 0.6 1\"/>\n  </body>\n"
                      "</mujocoinclude>\n");
  return file;
}

sim::PlantOptions plantOptions(const std::filesystem::path& folder) {
  sim::PlantOptions options;
  options.substeps = kSubsteps;
  options.scene.tool = writeProbe(folder);
  return options;
}

}  // namespace

const std::vector<ArmPose>& springPoses() {
  static const std::vector<ArmPose> kPoses = {
      {"home", {0.0, -0.785398, 0.0, -2.356194, 0.0, 1.570796, 0.785398}},
      {"side", {1.2, -0.5, 0.3, -2.3, 0.2, 1.9, 0.5}},
      {"tilted", {0.0, -0.6, 0.0, -2.4, 0.0, 2.4, 0.785398}},
  };
  return kPoses;
}

pipeline::WrapperConfig springConfig(bool governed) {
  pipeline::WrapperConfig config = simCartesianConfig("fr3");
  config.contact_speed.enabled = governed;
  config.payload.mass_kg = kProbeMassKg;
  config.governor.tcp_speed_m_per_s = 2.0;
  config.validation.max_position_jump_m = 0.5;
  return config;
}

SpringScene springScene(const ArmPose& pose, const std::filesystem::path& folder) {
  std::filesystem::create_directories(folder);
  SpringScene scene;
  scene.pose = pose;
  scene.folder = folder;
  Arm<> probe(springConfig(false), plantOptions(folder), pose.joints);
  const Eigen::Isometry3d tcp = probe.plant.tcpPose();
  scene.tcp = tcp.translation();
  scene.axis = tcp.linear().col(2);
  const pipeline::Controller& controller = probe.wrapper.controller();
  scene.axis_mass_kg =
      pipeline::reflectedMass(controller.modelData(), JointVector(), controller.dof(), scene.axis) +
      kProbeMassKg;
  return scene;
}

SpringRun driveIntoSpring(const SpringScene& scene, const pipeline::WrapperConfig& config,
                          double speed_m_per_s, const SpringReference& reference) {
  sim::PlantOptions options = plantOptions(scene.folder);
  const double gap_m = gapFor(speed_m_per_s);
  options.scene.objects = {writePlate(scene, gap_m)};
  Arm<> arm(config, options, scene.pose.joints);
  const mjModel& model = arm.plant.mujocoModel();
  const int slide = model.jnt_qposadr[mj_name2id(&model, mjOBJ_JOINT, "comply_spring")];
  const double period = arm.plant.controlPeriod();
  // Along u at the commanded speed (position and twist) until the probe would touch the plate
  // (or, through, until past the face), then held past_surface_m beyond the face, at rest.
  const double end_m = gap_m + reference.past_surface_m;
  const Eigen::Quaterniond orientation = arm.wrapper.measuredPose().tcp_orientation;
  const pipeline::ContactSpeed& stage = arm.wrapper.controller().contactSpeed();
  SpringRun run;
  run.commanded_m_per_s = speed_m_per_s;
  Eigen::Vector3d last_tcp = arm.plant.tcpPose().translation();
  double approach_speed = 0.0;  // along u over the last cycle: at the first touch, the one before
  int touched_at = -1;
  bool braking = false;
  for (int cycle = 0; cycle < kMaxCycles; ++cycle) {
    const double along = speed_m_per_s * cycle * period;
    const bool moving = along < (reference.through ? end_m : gap_m);
    CartesianCommand command = CartesianCommand::zero(arm.wrapper.dof());
    command.stamp_s = 1.0 + cycle * period;
    command.fields = CommandField::kPosition | CommandField::kVelocity | CommandField::kStiffness;
    command.position = arm.start_tcp + (moving ? along : end_m) * scene.axis;
    command.orientation = orientation;
    if (moving) {
      command.twist.head<3>() = speed_m_per_s * scene.axis;
    }
    command.stiffness_translational = kStiffnessNPerM * Eigen::Matrix3d::Identity();
    command.stiffness_rotational = 100.0 * Eigen::Matrix3d::Identity();
    EXPECT_TRUE(arm.wrapper.submit(command).accepted) << cycle;
    arm.cycle();
    const double force_n = kHandStiffnessNPerM * arm.plant.mujocoData().qpos[slide];
    run.peak_force_n = std::max(run.peak_force_n, force_n);
    run.settled_force_n = force_n;
    const Eigen::Vector3d tcp = arm.plant.tcpPose().translation();
    if (stage.enabled() && touched_at < 0 && stage.limit() > 0.0) {
      run.slowest_limit_m_per_s = run.slowest_limit_m_per_s > 0.0
                                      ? std::min(run.slowest_limit_m_per_s, stage.limit())
                                      : stage.limit();
    }
    run.brake_onsets += !braking && stage.brakeForce() > 0.0 ? 1 : 0;
    braking = stage.brakeForce() > 0.0;
    if (touched_at < 0 && arm.plant.toolContactWrench().head<3>().norm() > 0.0) {
      touched_at = cycle;
      run.touched = true;
      run.contact_speed_m_per_s = approach_speed;
      run.limit_m_per_s = stage.limit();
      run.mass_kg = stage.mass();
    }
    approach_speed = (tcp - last_tcp).dot(scene.axis) / period;
    if (touched_at < 0) {
      run.fastest_m_per_s = std::max(run.fastest_m_per_s, approach_speed);
    }
    last_tcp = tcp;
    if (arm.faulted() || (touched_at >= 0 && cycle - touched_at >= kCyclesAfterTouch && !moving)) {
      break;
    }
  }
  const pipeline::DiagnosticsSnapshot diagnostics = arm.wrapper.diagnostics();
  run.faulted = arm.faulted();
  run.stage_cycles = diagnostics.contact_speed_hits;
  run.rate_limit_hits = diagnostics.rate_limit_hits;
  return run;
}

}  // namespace comply::testing
