#include "passivity/wall.hpp"

#include <iomanip>
#include <sstream>

namespace comply::experiments::passivity {
namespace {

constexpr double kThicknessM = 0.04;
constexpr double kHalfWidthM = 0.15;  // along base y
// The face reaches from 0.10 m below the ball to 0.03 m above it, 0.07 m short of the flange.
constexpr double kBelowBallM = 0.10;
constexpr double kAboveBallM = 0.03;

Eigen::Vector3d ballOf(const Eigen::Isometry3d& tcp) {
  return tcp * Eigen::Vector3d(0.0, 0.0, kProbeLengthM);
}

}  // namespace

Wall::Wall(const Eigen::Isometry3d& home_tcp)
    : home_tcp_(home_tcp.translation()),
      home_ball_(ballOf(home_tcp)),
      face_x_(home_ball_.x() + kProbeRadiusM + kWallGapM) {}

Eigen::Vector3d Wall::pressingReference() const {
  return home_tcp_ + (kWallGapM + kPressDepthM) * Eigen::Vector3d::UnitX();
}

double Wall::gap(const Eigen::Isometry3d& tcp) const {
  return face_x_ - (ballOf(tcp).x() + kProbeRadiusM);
}

std::string Wall::fragment() const {
  const double centre_z = home_ball_.z() + 0.5 * (kAboveBallM - kBelowBallM);
  std::ostringstream xml;
  xml << std::setprecision(9) << "<mujocoinclude>\n  <geom name=\"wall\" type=\"box\" size=\""
      << 0.5 * kThicknessM << " " << kHalfWidthM << " " << 0.5 * (kAboveBallM + kBelowBallM)
      << "\" pos=\"" << face_x_ + 0.5 * kThicknessM << " " << home_ball_.y() << " " << centre_z
      << "\" rgba=\"0.45 0.55 0.7 1\" friction=\"0.2 0.005 0.0001\" solref=\"0.005 1\"/>\n"
      << "</mujocoinclude>\n";
  return xml.str();
}

}  // namespace comply::experiments::passivity
