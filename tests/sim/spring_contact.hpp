#pragma once
// A probe on the simulated FR3's TCP driven into a spring as stiff as a hand (ISO/TS 15066 Annex A:
// 75 N/mm), for the contact-speed stage (contact_speed.hpp). contact_speed_test.cpp runs a few of
// these, contact_speed_sweep_test.cpp (label long) the sweep docs/safety.md shows.
//
// The spring: a 0.1 kg plate on a slide joint along the approach direction u, the joint's
// stiffness 75000 N/m (and 2 N s/m, 0.2 % of critical with the arm: it only lets the plate's own
// ringing settle). The force a run reports is the spring's, k q with q the slide's compression:
// what a hand behind the plate takes. Probe and plate meet through a MuJoCo contact whose time
// constant is two substeps (16 substeps per 1 ms cycle), about 6.5e6 N/m on the plate's mass, ~90
// times the spring's, so the series compliance lowers the peak by ~0.6 %, the plate's own mass by
// ~1.6 % more (F = v mu sqrt(k / (mu + m_plate))): the plant is the clamped hand of the stage's
// default within ~2 %, on the soft side.
//
// The probe: a 1 cm ball 5 cm out along the TCP's z axis, driven along that axis, so the
// contact's line of action passes through the TCP: the force is a pure force at the TCP and meets
// the mass mu(u) the stage computes. Its 10 g are declared as the payload.
//
// The reference: streamed every cycle from the start TCP along u at the commanded speed (position
// and twist) until it reaches the plate's face, then held kPastSurfaceM beyond it, at rest: the
// law's stiffness, kStiffnessNPerM, times that is the quasi-static part of the force, 10 N, well
// under the hands' 140 N, and no twist drives the law's damping into the spring. So what passes
// the limit is the impact's. A reference that runs on through the contact (SpringReference::
// through) pushes with the law's damping times its speed as well: the stage does not bound that
// (contact_speed.hpp), and the sweep measures it apart. The motion governor's own TCP bound is
// raised to 2 m/s and the reference's jump bound to 0.5 m, so that runs without the stage are
// limited by the joints alone and a governed TCP may lag its reference.

#include <Eigen/Geometry>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "comply/pipeline/config.hpp"

namespace comply::testing {

inline constexpr double kHandStiffnessNPerM = 75e3;
inline constexpr double kHandsQuasiStaticLimitN = 140.0;
inline constexpr double kStiffnessNPerM = 2000.0;
inline constexpr double kPastSurfaceM = 0.005;
inline constexpr double kThroughSurfaceM = 0.02;  ///< a reference that runs on (40 N quasi-static)

/// A start pose of the FR3 (joint positions, robot.yaml order).
struct ArmPose {
  std::string name;
  std::vector<double> joints;
};

/// Three poses with different masses along their tool axes: home, turned to the side, and with the
/// tool tilted 34 degrees forward.
const std::vector<ArmPose>& springPoses();

/// The plant's TCP at a pose and the approach direction (its z axis), from MuJoCo.
struct SpringScene {
  ArmPose pose;
  Eigen::Vector3d tcp = Eigen::Vector3d::Zero();
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();
  double axis_mass_kg = 0.0;     ///< mu along the axis at the start (the stage's, the probe's in)
  std::filesystem::path folder;  ///< where the scene's fragments are written
};
SpringScene springScene(const ArmPose& pose, const std::filesystem::path& folder);

/// The controller every run uses: config/sim's, with the stage on (hands, quasi-static: the
/// defaults) when `governed`, the probe's mass declared, and the bounds above raised.
pipeline::WrapperConfig springConfig(bool governed);

/// What one run measured.
struct SpringRun {
  double commanded_m_per_s = 0.0;
  bool touched = false;
  bool faulted = false;
  double contact_speed_m_per_s = 0.0;  ///< the TCP's along u over the cycle before the first touch
  double fastest_m_per_s = 0.0;        ///< the TCP's along u, fastest before the first touch
  double peak_force_n = 0.0;           ///< the spring's, largest over the run
  double settled_force_n = 0.0;        ///< the spring's at the end: the quasi-static part
  double limit_m_per_s = 0.0;          ///< the stage's v_max along u at the first touch (0: off)
  double mass_kg = 0.0;                ///< the stage's mu(u) + payload at the first touch
  double slowest_limit_m_per_s = 0.0;  ///< the stage's least v_max over the approach (0: off)
  std::uint64_t stage_cycles = 0;      ///< cycles the stage acted (diagnostics)
  std::uint64_t rate_limit_hits = 0;   ///< joint-cycles the torque-rate limit clipped
  int brake_onsets = 0;                ///< times the stage's brake switched on
};

/// How the reference meets the plate.
struct SpringReference {
  double past_surface_m = kPastSurfaceM;  ///< where it ends, beyond the plate's face
  bool through = false;                   ///< at speed until there (else: at rest from the face on)
};

/// Drives the probe at `scene` into the spring at `speed_m_per_s` with `config`.
SpringRun driveIntoSpring(const SpringScene& scene, const pipeline::WrapperConfig& config,
                          double speed_m_per_s, const SpringReference& reference = {});

}  // namespace comply::testing
