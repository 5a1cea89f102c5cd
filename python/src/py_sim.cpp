// comply.Sim (see py_sim.hpp).

#include "py_sim.hpp"

#include <cmath>
#include <optional>
#include <variant>

#include "comply/core/clock.hpp"
#include "comply/host/controller_setup.hpp"
#include "comply/host/state_sample.hpp"
#include "comply/pipeline/command_gate.hpp"
#include "comply/pipeline/wrapper.hpp"
#include "py_convert.hpp"
#include "py_sim_cameras.hpp"
#include "py_sim_session.hpp"

namespace comply::python {
namespace {

/// The gate's outcome on the recording's clock: the Sim's commands are received at the simulated
/// time they are stamped with (the gate itself notes the wall clock).
transport::CommandOutcomeMessage simOutcomeMessage(const pipeline::CommandOutcome& outcome,
                                                   std::int64_t episode_start_ns) {
  transport::CommandOutcomeMessage message = host::outcomeMessage(outcome);
  message.received = transport::Stamp::fromNanoseconds(episode_start_ns + outcome.stamp_ns);
  return message;
}

}  // namespace

Sim::Sim(const std::string& config, const std::string& robot, int steps_per_action,
         double max_time_s, const std::optional<std::filesystem::path>& record,
         const py::object& cameras, const py::object& foxglove)
    : resolved_(pipeline::resolveController(host::simControllerConfig(robot, "", config))),
      camera_specs_(cameraSpecs(cameras)),
      steps_per_action_(steps_per_action),
      max_time_s_(max_time_s) {
  if (steps_per_action < 1) {
    throw py::value_error("steps_per_action must be >= 1");
  }
  if (record) {
    std::vector<std::string> camera_names;
    for (const sim::CameraSpec& spec : camera_specs_) {
      camera_names.push_back(spec.name);
    }
    recording_ = std::make_unique<host::HostRecording>(
        record->string(), resolved_, "comply",
        record::StringMap{{"host", "comply.Sim"},
                          {"clock", "simulated"},
                          {"steps_per_action", std::to_string(steps_per_action)}},
        // Simulated time has no deadline: a step waits for a busy disk, no cycle is lost.
        host::HostRecordingOptions{.when_full = record::WhenFull::kWait,
                                   .cameras = std::move(camera_names)});
    recording_open_ = true;
  }
  if (!foxglove.is_none()) {
    const std::string address = py::isinstance<py::int_>(foxglove)
                                    ? std::to_string(foxglove.cast<int>())
                                    : foxglove.cast<std::string>();
    view_ = std::make_unique<host::LiveView>(host::parseViewAddress(address), resolved_, "comply");
  }
}

Sim::~Sim() {
  close();
}

host::HostRecording* Sim::recording() const noexcept {
  return recording_open_ ? recording_.get() : nullptr;
}

void Sim::close() {
  if (!recording_open_) {
    return;
  }
  if (session_) {
    session_->detachRecording();
  }
  recording_->stop();
  recording_open_ = false;
}

py::object Sim::foxgloveUrl() const {
  return view_ ? py::object(py::str(view_->url())) : py::object(py::none());
}

py::object Sim::recordingStats() const {
  return recording_ ? py::object(toDict(recording_->stats())) : py::object(py::none());
}

void Sim::recordOutcome(const pipeline::CommandOutcome& outcome) {
  host::HostRecording* to = recording();
  if (to == nullptr && !view_) {
    return;
  }
  const transport::CommandOutcomeMessage message = simOutcomeMessage(outcome, session_->start_ns);
  if (to != nullptr) {
    to->outcome(message);
  }
  if (view_) {
    view_->outcome(message);
  }
}

void Sim::endEpisode() {
  if (!session_) {
    return;
  }
  session_->gate.abandonPending("the episode ended before a cycle took the command");
  for (const pipeline::CommandOutcome& outcome : session_->gate.takeOutcomes()) {
    recordOutcome(outcome);
  }
}

int Sim::dof() const noexcept {
  return resolved_->dof;
}

bool Sim::cartesian() const noexcept {
  return resolved_->cartesian();
}

double Sim::time() const noexcept {
  return session_ ? session_->plant.simTime() : 0.0;
}

double Sim::period() const {
  if (!session_) {
    throw std::runtime_error("call reset() before reading the period");
  }
  return session_->plant.controlPeriod();
}

py::dict Sim::reset() {
  std::int64_t start_ns = 0;
  if (session_) {
    endEpisode();
    start_ns = session_->clockNs();
    session_.reset();
  }
  session_ = std::make_unique<Session>(resolved_, start_ns, recording(), view_.get());
  if (!camera_specs_.empty()) {
    const py::gil_scoped_release release;
    if (cameras_) {
      cameras_->attach(session_->plant);
    } else {
      cameras_ = std::make_unique<sim::SimCameras>(session_->plant, camera_specs_);
    }
  }
  py::dict observation = session_->observation();
  addImages(observation);
  return observation;
}

void Sim::addImages(py::dict& observation) {
  if (!cameras_) {
    return;
  }
  const std::vector<sim::Image>* images = nullptr;
  {
    const py::gil_scoped_release release;
    images = &cameras_->render();
  }
  observation["images"] = imagesDict(camera_specs_, *images);
  if (host::HostRecording* to = recording()) {
    const py::gil_scoped_release release;
    const double now_s = session_->plant.simTime();
    transport::CompressedImageMessage message;
    message.header.stamp =
        transport::Stamp::fromNanoseconds(session_->start_ns + stampNanoseconds(now_s));
    message.format = "png";
    for (std::size_t i = 0; i < camera_specs_.size(); ++i) {
      message.header.frame_id = camera_specs_[i].name;
      message.data = sim::encodePng((*images)[i]);
      to->image(i, message);
    }
  }
}

void Sim::tare() {
  if (!session_) {
    throw std::runtime_error("call reset() before tare()");
  }
  const std::string why =
      std::visit([](auto& episode) { return episode->wrapper.tare(); }, session_->episode);
  if (!why.empty()) {
    throw std::runtime_error("tare: " + why);
  }
}

}  // namespace comply::python
