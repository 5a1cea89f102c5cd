#pragma once
// The connector-mating hardware: a capsule peg on the FR3's flange and a round socket with a 45 deg
// entry chamfer, its axis tilted about base x. Scene fragments for the simulator and the geometry
// the command and the evaluation share.

#include <Eigen/Core>
#include <string>

namespace comply::experiments::connector_mating {

// Peg and socket [m]. The socket's entrance centre is fixed; its axis is tilted about base x.
inline constexpr double kPegRadius = 0.006;
inline constexpr double kPegTip = 0.13;  // peg tip (capsule end) along TCP z, clear of the wrist
inline constexpr double kHoleRadius = 0.00625;  // 0.25 mm radial clearance
inline constexpr double kHoleDepth = 0.020;
inline constexpr double kChamfer = 0.006;

/// Centre of the socket's entrance, base frame.
Eigen::Vector3d socketEntrance();

/// Unit axis into the socket tilted by `tilt` [rad], base frame.
Eigen::Vector3d socketAxis(double tilt);

/// The peg as a tool fragment (MJCF, attached to the TCP).
std::string pegFragment();

/// A ring of 16 walls around a round hole with a 45 deg entry chamfer, and the seat at the
/// bottom; the whole socket tilted by `tilt` [rad] about x.
std::string socketFragment(double tilt);

}  // namespace comply::experiments::connector_mating
