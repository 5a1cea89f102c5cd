#pragma once
// The surface-following fixture: a rigid D-shaped block whose curved face runs along base x, its
// material on the -y side, the probe pressing from +y. The face is a sin^2 bulge; the simulated
// fixture approximates it with boxes tangent to it.

#include <Eigen/Core>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

namespace comply::experiments::surface_following {

// Fixture and probe geometry [m], base frame.
inline constexpr double kPathStartX = 0.35;
inline constexpr double kPathLengthX = 0.18;
inline constexpr double kBulge = 0.03;  // max lateral deviation of the face
inline constexpr double kTipZ = 0.25;   // height of the probe ball's centre
// The probe ball's centre lies this far below the TCP (examples/sim/probe_tool.xml).
inline constexpr double kProbeLength = 0.10;
inline constexpr double kTipRadius = 0.01;
// The probe's mass and centre of mass along the TCP's z (examples/sim/probe_tool.xml: a 50 g rod
// to 90 mm, a 10 g ball at 100 mm).
inline constexpr double kProbeMassKg = 0.06;
inline constexpr double kProbeComM = (0.05 * 0.045 + 0.01 * 0.1) / 0.06;
// The displaced run: the fixture moved 8 mm towards the probe and turned 2 deg about z.
inline constexpr double kDisplacementY = 0.008;
inline constexpr double kDisplacementYawRad = 2.0 * M_PI / 180.0;

/// The face's y at `x`.
double faceY(double x);
/// Unit normal of the face pointing out of the material, towards the probe (horizontal).
Eigen::Vector3d outwardNormal(double x);
/// Where the probe ball's centre should be: the face, one ball radius out.
Eigen::Vector3d nominalTip(double x);
/// nominalTip() densely along the first `fraction` of the face.
std::vector<Eigen::Vector3d> nominalTipPoints(double fraction);

/// The fixture as an MJCF fragment of boxes tangent to the face, displaced by `dy` and turned by
/// `yaw` about the path's middle.
std::string fixtureFragment(double dy, double yaw);

/// The face, nominal and displaced, for the plot script: columns x, face_y, face_y_displaced.
void writeFixtureCsv(const std::filesystem::path& file);

}  // namespace comply::experiments::surface_following
