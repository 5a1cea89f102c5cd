#pragma once
// What a Foxglove 3D panel is sent besides the arm's URDF: its links' transforms
// (foxglove.FrameTransforms), and markers (foxglove.SceneUpdate) for the compliance the law
// holds: the translational stiffness as an ellipsoid at the TCP, its axes the stiffness's
// principal axes, each as long as the stiffness along it (kStiffnessEllipsoidMPerNPerM); the
// contact force as an arrow from the TCP (kForceArrowMPerN); the chunk playing as a path through
// its waypoints. Both in JSON, the encoding Foxglove reads with the schemas below.

#include <Eigen/Geometry>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "comply/viewer/robot_frames.hpp"

namespace comply::viewer {

/// An ellipsoid axis's length [m] per N/m of stiffness along it: 1000 N/m draws 20 cm, so that
/// a task's usual stiffnesses (a few hundred to a few thousand N/m) stand out of the hand.
inline constexpr double kStiffnessEllipsoidMPerNPerM = 2e-4;
/// Axes shorter than this are drawn this long [m], so that a soft axis still shows.
inline constexpr double kStiffnessEllipsoidMinimumM = 0.004;
/// The force arrow's length [m] per N: 10 N draws 10 cm (up to kForceArrowMaximumM).
inline constexpr double kForceArrowMPerN = 0.01;
inline constexpr double kForceArrowMaximumM = 0.5;
/// A contact force below this [N] draws no arrow.
inline constexpr double kForceArrowMinimumN = 0.5;

/// The stiffness ellipsoid of `stiffness_task` (N/m, task frame axes; symmetric) with the task
/// frame `task_frame` (its orientation in the base frame): orientation in the base frame (a
/// right-handed rotation to the principal axes) and the lengths along them [m].
struct StiffnessEllipsoid {
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();
  Eigen::Vector3d lengths_m = Eigen::Vector3d::Zero();
};
StiffnessEllipsoid stiffnessEllipsoid(const Eigen::Matrix3d& stiffness_task,
                                      const Eigen::Quaterniond& task_frame);

/// What the markers show, in the base frame `frame_id`.
struct ArmMarkers {
  std::string frame_id;
  Eigen::Vector3d tcp_position = Eigen::Vector3d::Zero();
  bool stiffness = false;  ///< Cartesian control: draw the ellipsoid
  Eigen::Matrix3d stiffness_task = Eigen::Matrix3d::Zero();
  Eigen::Quaterniond task_frame = Eigen::Quaterniond::Identity();
  Eigen::Vector3d contact_force = Eigen::Vector3d::Zero();  ///< [N] on the tool
  std::vector<Eigen::Vector3d> path;                        ///< the chunk's waypoints [m]
};

/// The markers' entity ids, one each, replaced by every update.
inline constexpr std::string_view kStiffnessEntity = "stiffness";
inline constexpr std::string_view kContactForceEntity = "contact_force";
inline constexpr std::string_view kChunkPathEntity = "chunk_path";

/// A frame placed in its parent besides the URDF's links (the task frame, the reference).
struct ExtraFrame {
  std::string parent;
  std::string child;
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();
  Eigen::Quaterniond rotation = Eigen::Quaterniond::Identity();
};

std::string frameTransformsJson(std::int64_t time_ns, const std::vector<LinkTransform>& links,
                                const std::vector<ExtraFrame>& extra);
std::string sceneUpdateJson(std::int64_t time_ns, const ArmMarkers& markers);

/// The JSON schemas of the two messages, as their channels advertise them.
std::string frameTransformsSchema();
std::string sceneUpdateSchema();

/// A std_msgs/msg/String in CDR: how a ROS 2 robot_description travels, and what Foxglove's URDF
/// layer reads from a topic.
std::vector<std::uint8_t> stringMessageCdr(std::string_view text);
inline constexpr std::string_view kStringSchemaName = "std_msgs/msg/String";
inline constexpr std::string_view kStringDefinition = "string data\n";

}  // namespace comply::viewer
