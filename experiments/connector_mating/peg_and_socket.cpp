#include "connector_mating/peg_and_socket.hpp"

#include <Eigen/Geometry>
#include <cmath>
#include <iomanip>
#include <sstream>

namespace comply::experiments::connector_mating {

Eigen::Vector3d socketEntrance() {
  return {0.45, 0.0, 0.20};
}

Eigen::Vector3d socketAxis(double tilt) {
  return Eigen::AngleAxisd(tilt, Eigen::Vector3d::UnitX()) * Eigen::Vector3d(0.0, 0.0, -1.0);
}

std::string pegFragment() {
  std::ostringstream xml;
  xml << "<mujocoinclude>\n  <geom name=\"peg\" type=\"capsule\" fromto=\"0 0 0.005 0 0 "
      << kPegTip - kPegRadius << "\" size=\"" << kPegRadius
      << "\" rgba=\"0.8 0.55 0.15 1\" mass=\"0.05\" friction=\"0.3 0.005 0.0001\"/>\n"
      << "</mujocoinclude>\n";
  return xml.str();
}

// Connectors have such a chamfer: it takes up the few millimetres by which a compliant arm with
// joint friction misses the entrance.
std::string socketFragment(double tilt) {
  const Eigen::Vector3d entrance = socketEntrance();
  std::ostringstream xml;
  xml << std::setprecision(9) << "<mujocoinclude>\n  <body name=\"socket\" pos=\"" << entrance.x()
      << " " << entrance.y() << " " << entrance.z() << "\" quat=\"" << std::cos(0.5 * tilt) << " "
      << std::sin(0.5 * tilt) << " 0 0\">\n";
  const int sides = 16;
  const double wall = 0.01;
  const double half_width = (kHoleRadius + kChamfer + wall) * std::tan(M_PI / sides) + 5e-4;
  const auto box = [&](const Eigen::Vector3d& centre, const Eigen::Quaterniond& rotation,
                       const Eigen::Vector3d& half_size) {
    xml << "    <geom type=\"box\" size=\"" << half_size.transpose() << "\" pos=\""
        << centre.transpose() << "\" quat=\"" << rotation.w() << " " << rotation.x() << " "
        << rotation.y() << " " << rotation.z()
        << "\" rgba=\"0.4 0.45 0.5 1\" friction=\"0.3 0.005 0.0001\" solref=\"0.005 1\"/>\n";
  };
  for (int i = 0; i < sides; ++i) {
    const Eigen::Quaterniond around(
        Eigen::AngleAxisd(2.0 * M_PI * i / sides, Eigen::Vector3d::UnitZ()));
    // Straight wall below the chamfer: inner face at the hole radius.
    const double wall_length = kHoleDepth - kChamfer;
    box(around * Eigen::Vector3d(kHoleRadius + 0.5 * wall, 0.0, -kChamfer - 0.5 * wall_length),
        around, Eigen::Vector3d(0.5 * wall, half_width, 0.5 * wall_length));
    // Chamfer: inner face through (r, -c) and (r + c, 0), thickness outwards and down.
    const Eigen::Quaterniond tilted =
        around * Eigen::AngleAxisd(M_PI / 4.0, Eigen::Vector3d::UnitY());
    const Eigen::Vector3d face_middle(kHoleRadius + 0.5 * kChamfer, 0.0, -0.5 * kChamfer);
    const Eigen::Vector3d outward_down = Eigen::Vector3d(1.0, 0.0, -1.0).normalized();
    box(around * (face_middle + 0.5 * wall * outward_down), tilted,
        Eigen::Vector3d(0.5 * wall, half_width, kChamfer / std::sqrt(2.0)));
  }
  xml << "    <geom type=\"box\" size=\"0.02 0.02 0.005\" pos=\"0 0 " << -kHoleDepth - 0.005
      << "\" rgba=\"0.3 0.35 0.4 1\" solref=\"0.005 1\"/>\n  </body>\n</mujocoinclude>\n";
  return xml.str();
}

}  // namespace comply::experiments::connector_mating
