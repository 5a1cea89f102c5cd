#pragma once
// The wall of the wall_contact scenario: a rigid box whose face stands across base x, 10 mm in
// front of the probe's ball (examples/sim/probe_tool.xml) with the arm at home. The reference
// lies 20 mm behind the face, so the tool presses on it. Scene fragment and the geometry the
// metrics read.

#include <Eigen/Geometry>
#include <string>

namespace comply::experiments::passivity {

// The probe (examples/sim/probe_tool.xml): its ball's centre 0.1 m along the TCP's z.
inline constexpr double kProbeLengthM = 0.10;
inline constexpr double kProbeRadiusM = 0.01;
inline constexpr double kWallGapM = 0.010;     ///< ball to face with the arm at home
inline constexpr double kPressDepthM = 0.020;  ///< reference behind the face

class Wall {
 public:
  /// The wall in front of the probe of a TCP at `home_tcp`.
  explicit Wall(const Eigen::Isometry3d& home_tcp);

  /// Where the TCP reference goes: kPressDepthM past the point where the ball meets the face.
  [[nodiscard]] Eigen::Vector3d pressingReference() const;
  /// The ball's distance from the face [m] (< 0: it presses in) for the TCP at `tcp`.
  [[nodiscard]] double gap(const Eigen::Isometry3d& tcp) const;
  /// The wall as an MJCF object fragment; it ends below the flange, so only the probe meets it.
  [[nodiscard]] std::string fragment() const;

 private:
  Eigen::Vector3d home_tcp_;
  Eigen::Vector3d home_ball_;
  double face_x_ = 0.0;
};

}  // namespace comply::experiments::passivity
