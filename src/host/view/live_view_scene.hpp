#pragma once
// The live view's 3D part: the robot description (latched), the links' and the task frame's
// transforms and the markers, at the scene rate, from the view thread's newest cycle.

#include <chrono>
#include <mutex>
#include <string>
#include <vector>

#include "comply/host/live_view.hpp"
#include "comply/viewer/rate_limit.hpp"
#include "comply/viewer/robot_frames.hpp"
#include "comply/viewer/scene_messages.hpp"

namespace comply::host {

class LiveView::Scene {
 public:
  Scene(viewer::FoxgloveServer& server, const pipeline::ResolvedController& resolved,
        const std::string& name, double rate_hz);

  /// The view thread: publishes `cycle`'s transforms and markers when the scene rate allows.
  void publish(const ViewedCycle& cycle);
  /// Any thread: the chunk whose waypoints are drawn from now on, received at `received_at` (on
  /// the clock of the cycles' stamps), until a second after its span has passed.
  void setPath(const CartesianChunk& chunk, transport::Stamp received_at);

 private:
  /// `urdf`: the robot's URDF text, read once for the frames and the robot description.
  Scene(viewer::FoxgloveServer& server, const pipeline::ResolvedController& resolved,
        const std::string& name, double rate_hz, const std::string& urdf);
  void publishTransforms(const ViewedCycle& cycle, std::int64_t time_ns);
  void publishMarkers(const ViewedCycle& cycle, std::int64_t time_ns);

  viewer::FoxgloveServer& server_;
  std::string base_frame_;
  std::string name_;
  viewer::RobotFrames frames_;
  viewer::ChannelId description_channel_ = 0;
  viewer::ChannelId transforms_channel_ = 0;
  viewer::ChannelId markers_channel_ = 0;
  viewer::RateLimit rate_;
  std::vector<double> positions_;
  std::mutex path_mutex_;
  std::vector<Eigen::Vector3d> path_;
  std::int64_t path_end_ns_ = 0;  // on the clock of the cycles' stamps
  viewer::ArmMarkers markers_;
};

}  // namespace comply::host
