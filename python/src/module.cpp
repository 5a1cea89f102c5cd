// The `comply._comply` extension: Client, Sim and the task-frame builders (python/comply re-exports
// them). numpy arrays in and out; keywords are the command schema's field names.

#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "comply/export/lerobot_dataset.hpp"
#include "comply/record/mcap_writer.hpp"
#include "comply/task/frames.hpp"
#include "py_client.hpp"
#include "py_sim.hpp"

namespace py = pybind11;
using comply::python::Client;
using comply::python::Sim;

namespace {

/// A rotation matrix as the x y z w quaternion a command's task_frame takes.
Eigen::Vector4d quaternionOf(const Eigen::Matrix3d& rotation) {
  return Eigen::Quaterniond(rotation).normalized().coeffs();
}

constexpr const char* kClientDoc =
    "Client(name='comply', domain=0, network='loopback', timeout=10.0, record=None, "
    "security=None): a connection to the `comply run` host `name` on DDS `domain`.\n\n"
    "security='keystore/enclaves/comply/client' turns DDS Security on with that enclave of a "
    "keystore (scripts/create-keystore.sh, SROS2's layout): the host must run with "
    "--security and a keystore of the same CA. A process's participants on one domain are all "
    "secure or all not.\n\n"
    "Constructing it and reading state() and diagnostics() never takes the host's command "
    "topics (its discovery probe is a request, REQUEST_PROBE): a dashboard locks no sender out. "
    "The first command or chunk sent makes it the publisher; close() (or leaving a `with` "
    "block) deletes its DDS participant, and the host lets another sender in at once.\n\n"
    "Threads: every method may be called from any thread, also at once (a policy reading the "
    "state on one thread and sending on another): commands from several threads leave in the "
    "order of their stamps, and a state or outcome taken by one thread's call is seen by the "
    "others'. Blocking calls release the GIL.\n\n"
    "record='path.mcap' records what the client sends (commands, requests and the discovery "
    "probe, logged at their stamps) and every state and diagnostics message it takes (logged "
    "when taken) on /<name>/cartesian_command, /<name>/joint_command, /<name>/cartesian_chunk, "
    "/<name>/joint_chunk, /<name>/request, /<name>/state and /<name>/diagnostics; "
    "comply.read_recording() reads it. close() finishes the file (also on destruction). The "
    "file's folder must exist (OSError naming it otherwise). Should the disk fall behind, "
    "records are dropped and counted (recording_stats()), never the commands held up.";

constexpr const char* kSimDoc =
    "Sim(config, robot='', steps_per_action=50, max_time=0.0, record=None, cameras=None, "
    "foxglove=None): the "
    "controller on an "
    "in-process MuJoCo plant, shaped like a Gymnasium environment.\n\n"
    "record='path.mcap' records every cycle, command and outcome of every episode to one file, "
    "as `comply sim --record` does (/comply/cycle, /comply/cartesian_command or "
    "/comply/joint_command, /comply/outcome). An episode begins where the cycle index "
    "(state.cycle) is 0 again. The file's clock is simulated time since the Sim was made: each "
    "episode starts where the one before it stopped, so log times never go back; commands keep "
    "the stamps they were sent with (the episode's time). close() finishes the file (also on "
    "destruction); the Sim carries on unrecorded. The file's folder must exist (OSError naming "
    "it otherwise). Nothing is dropped: a step waits for a busy disk.\n\n"
    "cameras={'front': {'width': 128, 'height': 96, 'lookat': [0.4, 0, 0.3], 'distance': 1.2, "
    "'azimuth': 180, 'elevation': -25}, 'wrist': {'mount': 'tcp'}}: every observation carries "
    "observation['images'][name], a uint8 array (height, width, 3) rendered offscreen (EGL) from "
    "the state it reports. Keys: width, height (even), fovy [deg], shadows and reflections (off by "
    "default: costly on a CPU renderer), mount 'scene' (lookat [m], "
    "distance [m], azimuth, elevation [deg], as MuJoCo's free camera) or 'tcp' (position [m] and "
    "orientation x y z w of the camera in the TCP frame: x right, y down, z the view). A "
    "recording keeps the frames as sensor_msgs/CompressedImage (PNG) on /comply/camera/<name>; "
    "`comply export --lerobot` makes videos of them (docs/simulation.md).\n\n"
    "foxglove='8765' (or '0.0.0.0:8765', or a port number) serves a live view to Foxglove or "
    "Lichtblick, as `comply sim --foxglove` does (foxglove_url says where); while a viewer is "
    "connected the episodes keep to real time (docs/live-view.md).";

constexpr const char* kCloseDoc =
    "Stop the recording and finish its file; idempotent (a no-op without record=)";
constexpr const char* kClientCloseDoc =
    "Disconnect: delete the client's DDS participant (its writers with it, so the host releases "
    "the command topics at once, without waiting out command_timeout_s) and finish the "
    "recording, if any. Idempotent; afterwards every call but recording_stats() raises "
    "RuntimeError";
// A request's stamp names its outcome: outcome(stamp) says whether the host carried it out or
// refused it (other_publisher: another process holds the command topics).
#define COMPLY_REQUEST_RETURNS \
  "; returns its stamp [ns], whose outcome() says carried out or refused"
constexpr const char* kStatsDoc =
    "The recording's counts: dict(written, dropped, bytes, writer_cpu_s, error), or None "
    "without record=";

void translateRecordingErrors() {
  // A recording that cannot be created is the file system's answer, as open() gives it.
  py::register_exception_translator([](std::exception_ptr raised) {
    try {
      if (raised) {
        std::rethrow_exception(raised);
      }
    } catch (const comply::record::McapError& error) {
      PyErr_SetString(PyExc_OSError, error.what());
    }
  });
}

void bindClient(py::module_& m) {
  py::class_<Client>(m, "Client", kClientDoc)
      .def(py::init<const std::string&, int, const std::string&, double,
                    const std::optional<std::filesystem::path>&,
                    const std::optional<std::filesystem::path>&>(),
           py::arg("name") = "comply", py::arg("domain") = 0, py::arg("network") = "loopback",
           py::arg("timeout") = 10.0, py::kw_only(), py::arg("record") = py::none(),
           py::arg("security") = py::none())
      .def("send_cartesian", &Client::sendCartesian,
           "Send a Cartesian command by schema keywords; returns its stamp [ns]. Waits while "
           "the host is behind; RuntimeError when it acknowledged nothing for 0.1 s")
      .def("send_joint", &Client::sendJoint,
           "Send a joint command; returns its stamp [ns]. Waits and raises as send_cartesian")
      .def("send_chunk", &Client::sendChunk, py::arg("chunk"), py::arg("relative_to") = py::none(),
           py::arg("keep") = py::none(),
           "Send a timed chunk: a list of dicts, each with a 'time' [s] and schema keywords (a "
           "key given once holds for the waypoints after it). Times are relative to "
           "`relative_to` [s on the host's clock, e.g. the 'stamp' of the state the policy "
           "acted on], or to the host's clock now as clock() estimates it; that time travels as "
           "the chunk's observation. `keep`=m: the chunk takes over at its waypoint m, the "
           "running chunk plays until then. Returns the stamp [ns]. ValueError for a time a "
           "stamp cannot carry (not finite, or past 2038) or an m outside 0..n-1; the host "
           "answers every other refusal in outcome(), whose 'chunk' holds the timing record")
      .def("clock", &Client::clock,
           "The host's clock from the commands' round trips: dict(offset [s, host minus this "
           "machine], one_way_latency [s], round_trip [s], samples), or None")
      .def("state", &Client::state, py::arg("timeout") = 1.0)
      .def("diagnostics", &Client::diagnostics, py::arg("timeout") = 1.0,
           "The newest diagnostics (dict, with 'age' [s]) if taken within the last `timeout` s "
           "or within the next; None when none came (the host is gone or stalled: it publishes "
           "them at least once a second) or their writer is gone")
      .def("outcome", &Client::outcome, py::arg("stamp"), py::arg("timeout") = 1.0)
      .def("committed", &Client::committed, py::arg("observation_time"), py::arg("dt"),
           py::arg("n"), py::arg("timeout") = 1.0,
           "The reference the arm will execute at observation_time + k*dt (k < n; the host's "
           "clock, a state's 'stamp') if no new command arrives, from the host's own chunk "
           "player: the dict Sim.committed() returns ('time', 'position', ..., 'known'). One "
           "request on /<name>/committed_request, answered on /<name>/committed. ValueError when "
           "the host refuses it (dt not > 0, n over 64: its words), TimeoutError when no answer "
           "comes within `timeout` [s]")
      .def("wait_until", &Client::waitUntil, py::arg("predicate"), py::arg("timeout") = 10.0)
      .def(
          "activate",
          [](Client& c) { return c.request(comply::transport::RequestType::kActivate); },
          "Ask the host to activate" COMPLY_REQUEST_RETURNS)
      .def(
          "deactivate",
          [](Client& c) { return c.request(comply::transport::RequestType::kDeactivate); },
          "Ask the host to deactivate" COMPLY_REQUEST_RETURNS)
      .def(
          "reset", [](Client& c) { return c.request(comply::transport::RequestType::kReset); },
          "Ask the host to reset (leave FAULT, clear the stamp floor)" COMPLY_REQUEST_RETURNS)
      .def(
          "tare", [](Client& c) { return c.request(comply::transport::RequestType::kTare); },
          "Take the wrist force/torque sensor's reading (less the declared tool's weight) as its "
          "zero, from the host's next cycle" COMPLY_REQUEST_RETURNS)
      .def("close", &Client::close, kClientCloseDoc)
      .def(
          "__enter__", [](Client& c) -> Client& { return c; }, py::return_value_policy::reference)
      .def("__exit__", [](Client& c, const py::args& /*exception*/) { c.close(); })
      .def("recording_stats", &Client::recordingStats, kStatsDoc)
      .def_property_readonly("dof", &Client::dof)
      .def_property_readonly("cartesian", &Client::cartesian);
}

void bindSim(py::module_& m) {
  py::class_<Sim>(m, "Sim", kSimDoc)
      .def(py::init<const std::string&, const std::string&, int, double,
                    const std::optional<std::filesystem::path>&, const py::object&,
                    const py::object&>(),
           py::arg("config"), py::arg("robot") = "", py::arg("steps_per_action") = 50,
           py::arg("max_time") = 0.0, py::kw_only(), py::arg("record") = py::none(),
           py::arg("cameras") = py::none(), py::arg("foxglove") = py::none())
      .def_property_readonly("foxglove_url", &Sim::foxgloveUrl,
                             "The live view's URL (foxglove=), or None")
      .def_property_readonly("foxglove_viewing", &Sim::foxgloveViewing,
                             "A viewer is connected to the live view: steps keep to real time")
      .def("reset", &Sim::reset)
      .def("tare", &Sim::tare,
           "Take the wrist force/torque sensor's reading (less the declared tool's weight) as its "
           "zero, from the next cycle")
      .def("step", &Sim::step, py::arg("command") = py::none(), py::kw_only(),
           py::arg("relative_to") = py::none(), py::arg("keep") = py::none(),
           py::arg("steps") = py::none(),
           "Hold `command` (a dict of schema keywords, or a timed chunk: a list of such dicts "
           "each with a 'time' [s] after this observation, or after `relative_to`, see "
           "docs/chunks.md) for steps_per_action cycles (or `steps`); `keep`=m: the chunk takes "
           "over at its waypoint m, the running chunk plays until then (docs/policies.md). "
           "Returns (observation, reward, terminated, truncated, info); info['chunks'] holds "
           "the timing records of the chunks that took over, were superseded or dropped")
      .def("committed", &Sim::committed, py::arg("observation_time"), py::arg("dt"), py::arg("n"),
           "The reference the arm will execute at observation_time + k*dt (k < n) if no new "
           "command arrives, from the host's own chunk player: a dict of arrays ('time', "
           "'position', ... one row per time); 'known' is False when a time before the running "
           "chunk could no longer be answered (those rows' position NaN)")
      .def("close", &Sim::close, kCloseDoc)
      .def("recording_stats", &Sim::recordingStats, kStatsDoc)
      .def_property_readonly("dof", &Sim::dof)
      .def_property_readonly("cartesian", &Sim::cartesian)
      .def_property_readonly("time", &Sim::time)
      .def_property_readonly("period", &Sim::period, "The control period [s]");
}

void bindTaskFrames(py::module_& m) {
  m.def(
      "frenet_frame",
      [](const Eigen::Vector3d& velocity, const Eigen::Vector3d& acceleration,
         std::optional<Eigen::Vector3d> previous_normal) -> std::optional<Eigen::Vector4d> {
        const auto frame = comply::task::frenetFrame(velocity, acceleration, previous_normal);
        return frame ? std::optional(quaternionOf(*frame)) : std::nullopt;
      },
      py::arg("velocity"), py::arg("acceleration"), py::arg("previous_normal") = py::none(),
      "Frenet-Serret frame of a curve as a task_frame quaternion (x y z w), or None");
  m.def(
      "darboux_frame",
      [](const Eigen::Vector3d& tangent,
         const Eigen::Vector3d& normal) -> std::optional<Eigen::Vector4d> {
        const auto frame = comply::task::darbouxFrame(tangent, normal);
        return frame ? std::optional(quaternionOf(*frame)) : std::nullopt;
      },
      py::arg("tangent"), py::arg("surface_normal"),
      "Darboux frame of a curve on a surface as a task_frame quaternion (x y z w), or None");
}

void bindExport(py::module_& m) {
  m.def(
      "export_lerobot",
      [](const std::filesystem::path& folder, const std::vector<std::filesystem::path>& recordings,
         double fps, const std::string& task, const std::string& robot_type) {
        comply::exporter::LeRobotSummary summary;
        {
          const py::gil_scoped_release release;
          summary =
              comply::exporter::writeLeRobotDataset(folder, recordings, {fps, task, robot_type});
        }
        py::dict d;
        d["episodes"] = summary.episodes;
        d["frames"] = summary.frames;
        d["files"] = summary.files;
        return d;
      },
      py::arg("folder"), py::arg("recordings"), py::kw_only(), py::arg("fps") = 30.0,
      py::arg("task") = "comply recording", py::arg("robot_type") = "",
      "Recordings (MCAP, in episode order; a Sim's file holds an episode per reset) as a LeRobot "
      "v3.0 dataset in `folder`, as `comply export --lerobot` writes it (docs/datasets.md). "
      "Returns {'episodes', 'frames', 'files'}; raises RuntimeError naming the recording at "
      "fault, ValueError for an fps that is not positive or no recording");
}

}  // namespace

PYBIND11_MODULE(_comply, m) {
  m.doc() = "comply: live compliant control over DDS, and an in-process simulator";
  translateRecordingErrors();
  bindClient(m);
  bindSim(m);
  bindTaskFrames(m);
  bindExport(m);
}
