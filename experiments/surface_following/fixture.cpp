#include "surface_following/fixture.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <fstream>
#include <iomanip>
#include <sstream>

namespace comply::experiments::surface_following {
namespace {

double faceSlope(double x) {
  const double u = (x - kPathStartX) / kPathLengthX;
  if (u <= 0.0 || u >= 1.0) {
    return 0.0;
  }
  return kBulge * M_PI / kPathLengthX * std::sin(2.0 * M_PI * u);
}

}  // namespace

double faceY(double x) {
  const double u = std::clamp((x - kPathStartX) / kPathLengthX, 0.0, 1.0);
  return kBulge * std::sin(M_PI * u) * std::sin(M_PI * u);
}

Eigen::Vector3d outwardNormal(double x) {
  return Eigen::Vector3d(-faceSlope(x), 1.0, 0.0).normalized();
}

Eigen::Vector3d nominalTip(double x) {
  return Eigen::Vector3d(x, faceY(x), kTipZ) + kTipRadius * outwardNormal(x);
}

std::vector<Eigen::Vector3d> nominalTipPoints(double fraction) {
  std::vector<Eigen::Vector3d> points;
  const int count = 2000;
  for (int i = 0; i <= count; ++i) {
    points.push_back(nominalTip(kPathStartX + fraction * kPathLengthX * i / count));
  }
  return points;
}

std::string fixtureFragment(double dy, double yaw) {
  const Eigen::Vector2d pivot(kPathStartX + 0.5 * kPathLengthX, 0.0);
  const Eigen::Rotation2Dd turn(yaw);
  const auto place = [&](const Eigen::Vector2d& point) {
    return Eigen::Vector2d(turn * (point - pivot) + pivot + Eigen::Vector2d(0.0, dy));
  };
  std::ostringstream xml;
  xml << std::setprecision(9) << "<mujocoinclude>\n  <body name=\"fixture\" pos=\"0 0 " << kTipZ
      << "\">\n";
  const int segments = 90;
  const double begin = kPathStartX - 0.04;
  const double end = kPathStartX + kPathLengthX + 0.04;
  const double thickness = 0.04;
  for (int i = 0; i < segments; ++i) {
    const double xa = begin + (end - begin) * i / segments;
    const double xb = begin + (end - begin) * (i + 1) / segments;
    const Eigen::Vector2d a = place({xa, faceY(xa)});
    const Eigen::Vector2d b = place({xb, faceY(xb)});
    const Eigen::Vector2d along = (b - a).normalized();
    const Eigen::Vector2d inward(along.y(), -along.x());  // material side (-y for yaw 0)
    const Eigen::Vector2d centre = 0.5 * (a + b) + 0.5 * thickness * inward;
    const double angle = std::atan2(along.y(), along.x());
    xml << "    <geom type=\"box\" size=\"" << 0.5 * (b - a).norm() + 5e-4 << " " << 0.5 * thickness
        << " 0.025\" pos=\"" << centre.x() << " " << centre.y() << " 0\" quat=\""
        << std::cos(0.5 * angle) << " 0 0 " << std::sin(0.5 * angle)
        << "\" rgba=\"0.45 0.55 0.7 1\" friction=\"0.2 0.005 0.0001\" solref=\"0.005 1\"/>\n";
  }
  xml << "  </body>\n</mujocoinclude>\n";
  return xml.str();
}

void writeFixtureCsv(const std::filesystem::path& file) {
  std::ofstream fixture(file);
  fixture << "x,face_y,face_y_displaced\n";
  const Eigen::Vector2d pivot(kPathStartX + 0.5 * kPathLengthX, 0.0);
  for (int i = 0; i <= 200; ++i) {
    const double x = kPathStartX - 0.04 + (kPathLengthX + 0.08) * i / 200.0;
    const Eigen::Vector2d moved =
        Eigen::Rotation2Dd(kDisplacementYawRad) * (Eigen::Vector2d(x, faceY(x)) - pivot) + pivot +
        Eigen::Vector2d(0.0, kDisplacementY);
    fixture << x << ',' << faceY(x) << ',' << moved.y() << '\n';
  }
}

}  // namespace comply::experiments::surface_following
