#pragma once
// comply.Sim: the in-process simulator (the wrapper and a MuJoCo plant, no network), shaped like
// a Gymnasium environment without needing gymnasium: reset() -> observation, step(command) ->
// (observation, reward, terminated, truncated, info). One step holds the command for
// `steps_per_action` control cycles (50 at 1 kHz: a 20 Hz policy).
//
// With `record`, every cycle, command and outcome of every episode goes to one MCAP file, as
// `comply sim --record` writes it (host/host_recording.hpp). Its clock is simulated time since
// the Sim was made: each episode starts where the one before it stopped, so the file's log times
// never go back, while the commands keep the stamps they were sent with (the episode's own
// simulated time). An episode starts where the cycle index (state.cycle) is 0 again.
//
// With `cameras`, every observation (reset()'s and each step()'s) carries each camera's frame,
// rendered offscreen, as observation["images"][name]; a recording keeps them as PNG compressed
// images, a channel per camera, at the observation's time.

#include <pybind11/pybind11.h>

#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include "comply/core/chunk.hpp"
#include "comply/host/host_recording.hpp"
#include "comply/host/live_view.hpp"
#include "comply/pipeline/command_gate.hpp"
#include "comply/pipeline/resolved_controller.hpp"
#include "comply/sim/sim_cameras.hpp"

namespace comply::python {

namespace py = pybind11;

class Sim {
 public:
  /// `record`: the MCAP file every episode is recorded to (none: not recorded). `cameras`: None
  /// or a dict of name -> keys (py_sim_cameras.hpp). `foxglove`: None, or "[ADDRESS:]PORT" (or
  /// a port number) to serve a live view on (host/live_view.hpp), the episodes paced to real
  /// time while a viewer is connected.
  Sim(const std::string& config, const std::string& robot, int steps_per_action, double max_time_s,
      const std::optional<std::filesystem::path>& record, const py::object& cameras,
      const py::object& foxglove);
  ~Sim();
  Sim(const Sim&) = delete;
  Sim& operator=(const Sim&) = delete;

  /// A fresh plant at the robot's home pose and a freshly activated controller.
  py::dict reset();
  /// The wrist sensor's zero from the next cycle; raises when there is no episode.
  void tare();
  /// `command`: a dict of schema keywords, or a timed chunk (a list of such dicts, each with a
  /// "time" [s] after this step's observation), or None: no new command. Never raises on a
  /// rejected command: info["accepted"] is False and info["reason"] says why.
  /// `relative_to`: the simulated time a chunk's times count from (an earlier observation's
  /// "time"; default this step's), also reported as the chunk's observation; `keep`: the chunk
  /// takes over at its waypoint `keep` (the running chunk plays until then); `steps`: cycles
  /// to run instead of steps_per_action. info["chunks"]: the timing records of the chunks that
  /// took over, were superseded or dropped during the step.
  py::tuple step(const py::object& command, const py::object& relative_to, const py::object& keep,
                 const py::object& steps);
  /// The reference the cycle will execute at observation_time + k dt (k < count) if no new
  /// command arrives (pipeline::Wrapper::predict): a dict of arrays, "time" and the command's
  /// fields; "known" false when a time before the running chunk could not be answered.
  py::dict committed(double observation_time_s, double dt_s, int count);

  [[nodiscard]] int dof() const noexcept;
  [[nodiscard]] bool cartesian() const noexcept;
  [[nodiscard]] double time() const noexcept;
  /// The control period [s]; raises before reset().
  [[nodiscard]] double period() const;

  /// Stops the recording: the file is complete when this returns. Idempotent; the Sim carries
  /// on unrecorded.
  void close();
  /// The recording's counts (written, dropped, bytes, writer_cpu_s, error), or None.
  [[nodiscard]] py::object recordingStats() const;
  /// The live view's URL ("ws://127.0.0.1:8765"), or None without one.
  [[nodiscard]] py::object foxgloveUrl() const;
  /// A viewer is connected to the live view (the episodes keep to real time meanwhile).
  [[nodiscard]] bool foxgloveViewing() const noexcept { return view_ && view_->viewing(); }

 private:
  struct Session;
  /// The recording while it is open, else null.
  [[nodiscard]] host::HostRecording* recording() const noexcept;
  void recordOutcome(const pipeline::CommandOutcome& outcome);
  /// Settles the episode's commands no cycle took (recorded as rejected) before it goes.
  void endEpisode();
  /// Offers `command` (a dict, or a chunk) through the gate at this step's time; its stamp.
  std::optional<std::int64_t> offer(const py::object& command, const py::object& relative_to,
                                    const py::object& keep);
  /// The chunks' timing records since the last step, as dicts on the simulated clock.
  py::list takeChunkTimings();
  /// The simulated time of the last cycle (the wrapper's host clock, so chunk times fall on
  /// cycles).
  [[nodiscard]] double lastCycleTime() const noexcept;
  /// The cameras' frames of the current state into `observation` ("images"), and into the
  /// recording; nothing without cameras.
  void addImages(py::dict& observation);

  std::shared_ptr<const pipeline::ResolvedController> resolved_;
  std::vector<sim::CameraSpec> camera_specs_;
  /// Made with the first episode and kept across resets (their GL contexts are costly to make);
  /// null without cameras.
  std::unique_ptr<sim::SimCameras> cameras_;
  std::unique_ptr<host::HostRecording> recording_;
  bool recording_open_ = false;
  std::unique_ptr<host::LiveView> view_;  // null without foxglove
  std::unique_ptr<Session> session_;
  int steps_per_action_;
  double max_time_s_;
};

}  // namespace comply::python
