#pragma once
// The live view's 3D part: the robot description (latched), the links' and the task frame's
// transforms and the markers, at the scene rate, from the view thread's newest cycle.

#include <chrono>
#include <mutex>
#include <string>
#include <vector>

#include "comply/host/live_view.hpp"
#include "comply/viewer/robot_frames.hpp"
#include "comply/viewer/scene_messages.hpp"

namespace comply::host {

class LiveView::Scene {
 public:
  Scene(viewer::FoxgloveServer& server, const pipeline::ResolvedController& resolved,
        const std::string& name, double rate_hz);

  /// The view thread: publishes `cycle`'s transforms and markers when the scene rate allows.
  void publish(const ViewedCycle& cycle);
  /// Any thread: the chunk whose waypoints are drawn from now on (until its last has passed).
  void setPath(const CartesianChunk& chunk);

 private:
  void publishTransforms(const ViewedCycle& cycle, std::int64_t time_ns);
  void publishMarkers(const ViewedCycle& cycle, std::int64_t time_ns);

  viewer::FoxgloveServer& server_;
  std::string base_frame_;
  std::string name_;
  viewer::RobotFrames frames_;
  viewer::ChannelId description_channel_ = 0;
  viewer::ChannelId transforms_channel_ = 0;
  viewer::ChannelId markers_channel_ = 0;
  std::chrono::steady_clock::duration period_;
  std::chrono::steady_clock::time_point next_;
  std::vector<double> positions_;
  std::mutex path_mutex_;
  std::vector<Eigen::Vector3d> path_;
  double path_end_s_ = 0.0;  // the chunk's last waypoint, on the host's clock
  viewer::ArmMarkers markers_;
};

}  // namespace comply::host
