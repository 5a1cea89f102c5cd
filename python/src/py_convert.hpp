#pragma once
// Python values to and from comply's: keyword arguments to a command (through the schema's JSON
// reader, so the keywords are the schema's field names and every check applies), messages and
// observations to dicts of numpy arrays.

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "comply/core/chunk.hpp"
#include "comply/core/commands.hpp"
#include "comply/pipeline/chunk_timing.hpp"
#include "comply/pipeline/command_gate.hpp"
#include "comply/pipeline/diagnostics.hpp"
#include "comply/record/recorder.hpp"
#include "comply/transport/messages.hpp"

namespace comply::python {

namespace py = pybind11;

/// {name: value} with numpy arrays and sequences flattened to lists of numbers, strings kept.
nlohmann::json kwargsToJson(const py::dict& kwargs);

/// A command from schema keywords (shorthand allowed: a 3x3 block as 1 or 3 numbers); `fields`
/// are the groups of the keywords given. Raises ValueError naming the keyword.
/// `base`: what the keywords a given group leaves out keep (the reference in force, say), so
/// position=... alone keeps the orientation in force; without it, Command::zero(dof).
template <typename Command>
Command commandFromKwargs(const py::dict& kwargs, int dof,
                          const std::optional<Command>& base = std::nullopt);

/// A timed chunk from Python: a list of dicts, each a waypoint's schema keywords plus "time" [s]
/// relative to `time_origin_s`, or {"chunk": that list}. Each waypoint builds on the one before
/// (`base` for the first), so a key given once holds for the rest. Raises ValueError naming
/// "chunk[k].<key>".
template <typename Command>
Chunk<Command> chunkFromPython(const py::handle& chunk, int dof, double time_origin_s,
                               const std::optional<Command>& base = std::nullopt);
/// Whether `value` is a chunk (a list, or a dict with "chunk") rather than one command.
bool isChunk(const py::handle& value);

/// The takeover of keep=m (a Python int or None): waypoint m's time, NaN for None; raises
/// ValueError for an m the chunk has no waypoint for.
template <typename Command>
double takeoverOfKeep(const Chunk<Command>& chunk, const py::object& keep) {
  if (keep.is_none()) {
    return std::numeric_limits<double>::quiet_NaN();
  }
  const int m = keep.cast<int>();
  const auto count = static_cast<int>(chunk.waypoints.size());
  if (m < 0 || m >= count) {
    throw py::value_error("keep=" + std::to_string(m) + ": a chunk of " + std::to_string(count) +
                          " waypoints takes over at one of them (0 to " +
                          std::to_string(count - 1) + ")");
  }
  return chunk.waypoints[static_cast<std::size_t>(m)].time_s;
}

/// Commands as one dict of arrays, a row per command and a key per schema field ("position"
/// (n, 3), "stiffness_translational" (n, 3, 3), quaternions x y z w, "damping_mode" a list of
/// names), for predicted references (ChunkPlayer::predict).
py::dict toArrays(const std::vector<CartesianCommand>& commands);
py::dict toArrays(const std::vector<JointCommand>& commands);
/// A chunk's timing record (comply_msgs/ChunkTiming): times [s] on the host's clock, NaN where
/// the record has none.
py::dict toDict(const transport::ChunkTimingMessage& timing);
/// The same from the cycle's record (`noted`) on a clock that reads `cycle_host_s` [s] in its
/// cycle, exactly (Sim.step()'s info, on the simulated clock).
py::dict toDict(const pipeline::NotedChunk& noted, double cycle_host_s);

py::array_t<double> array(const double* values, std::size_t size);
template <typename Container>
py::array_t<double> array(const Container& values) {
  return array(values.data(), static_cast<std::size_t>(values.size()));
}

/// The committed reference as Sim.committed() and Client.committed() give it: toArrays() of one
/// command per time, "time" [s] (the times, a row each) and "known" (false when a time before the
/// running chunk could no longer be answered: those rows' position NaN).
template <typename Command>
py::dict committedDict(const std::vector<Command>& commands, const std::vector<double>& times_s,
                       bool known) {
  py::dict d = toArrays(commands);
  d["time"] = array(times_s);
  d["known"] = known;
  return d;
}

/// The energy tank's account under ControllerState's names (tank_energy [J], ..., gain_fraction):
/// the Client's state and the Sim's observation carry the same keys.
void addPassivity(const pipeline::PassivitySnapshot& passivity, py::dict& d);

py::dict toDict(const transport::ControllerStateMessage& state);
py::dict toDict(const transport::CommandOutcomeMessage& outcome);
py::dict toDict(const transport::DiagnosticsMessage& diagnostics);
/// A recording's counts as Sim.recording_stats() and Client.recording_stats() give them.
py::dict toDict(const record::RecorderStats& stats);

}  // namespace comply::python
