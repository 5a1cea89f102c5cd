// The live view's 3D part (see live_view_scene.hpp).

#include "live_view_scene.hpp"

#include <stdexcept>

#include "comply/core/text_file.hpp"
#include "comply/schema/schema.hpp"

namespace comply::host {
namespace {

/// A robot's URDF text: the description's own, else its file's.
std::string urdfText(const model::RobotDescription& robot) {
  if (!robot.urdf_xml.empty()) {
    return robot.urdf_xml;
  }
  TextFile file = readTextFile(robot.urdf_path);
  if (!file.ok()) {
    throw std::runtime_error("the live view cannot show the robot: " + file.error);
  }
  return std::move(file.text);
}

}  // namespace

LiveView::Scene::Scene(viewer::FoxgloveServer& server, const pipeline::ResolvedController& resolved,
                       const std::string& name, double rate_hz)
    : Scene(server, resolved, name, rate_hz, urdfText(resolved.robot)) {}

LiveView::Scene::Scene(viewer::FoxgloveServer& server, const pipeline::ResolvedController& resolved,
                       const std::string& name, double rate_hz, const std::string& urdf)
    : server_(server),
      base_frame_(resolved.robot.base_frame),
      name_(name),
      frames_(urdf, resolved.config.joints),
      rate_(rate_hz),
      positions_(resolved.config.joints.size(), 0.0) {
  description_channel_ = server_.addChannel({.topic = "/robot_description",
                                             .encoding = "cdr",
                                             .schema_name = std::string(viewer::kStringSchemaName),
                                             .schema_encoding = "ros2msg",
                                             .schema = std::string(viewer::kStringDefinition),
                                             .latched = true});
  server_.publish(description_channel_, 0, viewer::stringMessageCdr(urdf));
  transforms_channel_ = server_.addChannel({.topic = "/tf",
                                            .encoding = "json",
                                            .schema_name = "foxglove.FrameTransforms",
                                            .schema_encoding = "jsonschema",
                                            .schema = viewer::frameTransformsSchema()});
  markers_channel_ = server_.addChannel({.topic = "/" + name + "/markers",
                                         .encoding = "json",
                                         .schema_name = "foxglove.SceneUpdate",
                                         .schema_encoding = "jsonschema",
                                         .schema = viewer::sceneUpdateSchema()});
  markers_.frame_id = base_frame_;
}

void LiveView::Scene::publish(const ViewedCycle& cycle) {
  // The scene's rate is kept here, once for both channels (they go out together).
  const auto now = std::chrono::steady_clock::now();
  if (!rate_.allows(now)) {
    return;
  }
  rate_.take(now);
  const std::int64_t time_ns = cycle.state.wall.nanoseconds();
  if (server_.wants(transforms_channel_)) {
    publishTransforms(cycle, time_ns);
  }
  if (server_.wants(markers_channel_)) {
    publishMarkers(cycle, time_ns);
  }
}

void LiveView::Scene::publishTransforms(const ViewedCycle& cycle, std::int64_t time_ns) {
  const JointVector& q = cycle.state.joints.position;
  for (std::size_t i = 0; i < positions_.size() && static_cast<Eigen::Index>(i) < q.size(); ++i) {
    positions_[i] = q[static_cast<Eigen::Index>(i)];
  }
  frames_.update(positions_);
  std::vector<viewer::ExtraFrame> extra;
  extra.push_back(
      {base_frame_, name_ + "/tcp", cycle.state.tcp_position, cycle.state.tcp_orientation});
  if (const auto* bus = std::get_if<comply_cartesian_command>(&cycle.in_force)) {
    // The task frame's axes at the TCP: where the stiffness they carry acts.
    extra.push_back({base_frame_, name_ + "/task_frame", cycle.state.tcp_position,
                     schema::fromXyzw(bus->task_frame).normalized()});
    extra.push_back({base_frame_, name_ + "/reference", cycle.state.reference_position,
                     cycle.state.reference_orientation});
  }
  server_.publish(transforms_channel_, time_ns,
                  viewer::frameTransformsJson(time_ns, frames_.transforms(), extra));
}

void LiveView::Scene::publishMarkers(const ViewedCycle& cycle, std::int64_t time_ns) {
  markers_.tcp_position = cycle.state.tcp_position;
  markers_.contact_force = cycle.state.contact_wrench.head<3>();
  const auto* bus = std::get_if<comply_cartesian_command>(&cycle.in_force);
  markers_.stiffness = bus != nullptr;
  if (bus != nullptr) {
    markers_.stiffness_task = schema::fromRowMajor(bus->stiffness_translational);
    markers_.task_frame = schema::fromXyzw(bus->task_frame).normalized();
  }
  {
    const std::lock_guard lock(path_mutex_);
    if (!path_.empty() && time_ns > path_end_ns_) {
      path_.clear();  // played out
    }
    markers_.path = path_;
  }
  server_.publish(markers_channel_, time_ns, viewer::sceneUpdateJson(time_ns, markers_));
}

void LiveView::Scene::setPath(const CartesianChunk& chunk, transport::Stamp received_at) {
  const std::lock_guard lock(path_mutex_);
  path_.clear();
  for (const auto& waypoint : chunk.waypoints) {
    path_.push_back(waypoint.command.position);
  }
  // The waypoints' times are the wrapper's clock, which need not be the stamps' (Python's Sim
  // stamps an episode from where the last one ended): the span counts from the receipt.
  const double span_s = chunk.waypoints.empty()
                            ? 0.0
                            : chunk.waypoints.back().time_s - chunk.waypoints.front().time_s;
  path_end_ns_ = received_at.nanoseconds() + static_cast<std::int64_t>((span_s + 1.0) * 1e9);
}

}  // namespace comply::host
