// Conversions between Python values and comply's (see py_convert.hpp).

#include "py_convert.hpp"

#include <pybind11/stl.h>

#include <algorithm>
#include <array>
#include <type_traits>

#include "comply/core/input_error.hpp"
#include "comply/host/state_sample.hpp"
#include "comply/schema/json.hpp"

namespace comply::python {
namespace {

nlohmann::json valueToJson(const py::handle& value) {
  if (py::isinstance<py::str>(value)) {
    return value.cast<std::string>();
  }
  const auto numbers =
      py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(value);
  if (!numbers) {
    throw py::type_error("expected a number, a sequence of numbers or a numpy array");
  }
  if (numbers.ndim() == 0) {
    return *numbers.data();
  }
  nlohmann::json list = nlohmann::json::array();
  for (py::ssize_t i = 0; i < numbers.size(); ++i) {
    list.push_back(numbers.data()[i]);
  }
  return list;
}

py::dict stampDict(const transport::Stamp& stamp) {
  py::dict d;
  d["sec"] = stamp.sec;
  d["nanosec"] = stamp.nanosec;
  return d;
}

}  // namespace

nlohmann::json kwargsToJson(const py::dict& kwargs) {
  nlohmann::json object = nlohmann::json::object();
  for (const auto& [key, value] : kwargs) {
    object[key.cast<std::string>()] = valueToJson(value);
  }
  return object;
}

bool isChunk(const py::handle& value) {
  return py::isinstance<py::list>(value) || py::isinstance<py::tuple>(value) ||
         (py::isinstance<py::dict>(value) && value.cast<py::dict>().contains("chunk"));
}

template <typename Command>
Chunk<Command> chunkFromPython(const py::handle& chunk, int dof, double time_origin_s,
                               const std::optional<Command>& base) {
  const py::handle list = py::isinstance<py::dict>(chunk) ? chunk.cast<py::dict>()["chunk"] : chunk;
  if (!py::isinstance<py::list>(list) && !py::isinstance<py::tuple>(list)) {
    throw py::type_error("a chunk is a list of dicts, each with a \"time\" and schema keywords");
  }
  nlohmann::json waypoints = nlohmann::json::array();
  for (const py::handle& waypoint : list) {
    if (!py::isinstance<py::dict>(waypoint)) {
      throw py::type_error("each waypoint of a chunk is a dict");
    }
    waypoints.push_back(kwargsToJson(waypoint.cast<py::dict>()));
  }
  schema::ReadOptions<Command> options;
  options.base = base;
  options.allow_shorthand = true;
  options.source = "chunk";
  try {
    return schema::chunkFromJson<Command>(nlohmann::json{{"chunk", waypoints}}, dof, time_origin_s,
                                          options);
  } catch (const InputError& error) {
    throw py::value_error(error.what());
  }
}

template Chunk<CartesianCommand> chunkFromPython(const py::handle&, int, double,
                                                 const std::optional<CartesianCommand>&);
template Chunk<JointCommand> chunkFromPython(const py::handle&, int, double,
                                             const std::optional<JointCommand>&);

template <typename Command>
Command commandFromKwargs(const py::dict& kwargs, int dof, const std::optional<Command>& base) {
  schema::ReadOptions<Command> options;
  options.base = base;
  options.allow_shorthand = true;
  options.source = "keyword arguments";
  try {
    return schema::fromJson<Command>(kwargsToJson(kwargs), dof, options).command;
  } catch (const InputError& error) {
    throw py::value_error(error.what());
  }
}

template CartesianCommand commandFromKwargs(const py::dict&, int,
                                            const std::optional<CartesianCommand>&);
template JointCommand commandFromKwargs(const py::dict&, int, const std::optional<JointCommand>&);

py::array_t<double> array(const double* values, std::size_t size) {
  py::array_t<double> out(static_cast<py::ssize_t>(size));
  std::copy(values, values + size, out.mutable_data());
  return out;
}

void addPassivity(const pipeline::PassivitySnapshot& passivity, py::dict& d) {
  d["passivity"] = passivity.enabled;
  d["tank_energy"] = passivity.tank_energy_j;
  d["nullspace_tank_energy"] = passivity.nullspace_tank_energy_j;
  d["energy_injected"] = passivity.injected_j;
  d["energy_dissipated"] = passivity.dissipated_j;
  d["energy_refused"] = passivity.refused_j;
  d["gain_fraction"] = passivity.gain_fraction;
}

namespace {

/// std::vector<double>, std::array<double, N>: a numpy array.
template <typename T>
concept DoubleArray = requires {
  requires std::is_same_v<typename T::value_type, double>;
};

/// A field of a table's message as Python has it: enums by name, stamps in seconds, a header as
/// {"stamp", "frame_id"}, numbers in arrays as numpy arrays, a GUID as hex.
template <typename T>
py::object fieldObject(const T& value) {
  if constexpr (std::is_enum_v<T>) {
    return py::str(std::string(toString(value)));
  } else if constexpr (std::is_same_v<T, transport::Stamp>) {
    return py::float_(value.seconds());
  } else if constexpr (std::is_same_v<T, transport::Header>) {
    py::dict header;
    header["stamp"] = value.stamp.seconds();
    header["frame_id"] = value.frame_id;
    return header;
  } else if constexpr (std::is_same_v<T, transport::Gid>) {
    return py::str(transport::toHex(value));
  } else if constexpr (std::is_same_v<T, transport::Outcomes>) {
    py::list outcomes;
    for (const auto& outcome : value) {
      outcomes.append(toDict(outcome));
    }
    return outcomes;
  } else if constexpr (DoubleArray<T>) {
    return array(value.data(), value.size());
  } else {
    return py::cast(value);
  }
}

py::dict messageDict(const transport::TableMessage auto& message) {
  py::dict d;
  std::remove_cvref_t<decltype(message)>::visit(
      message, [&](transport::FieldName name, const auto& value) {
        d[py::str(std::string(name.wire))] = fieldObject(value);
      });
  return d;
}

}  // namespace

py::dict toDict(const transport::ControllerStateMessage& s) {
  py::dict d = messageDict(s);
  d["stamp"] = s.header.stamp.seconds();  // the header's stamp, as every state dict has it
  return d;
}

namespace {

/// A chunk timing record's times [s] on the host's clock, NaN where it has none.
struct ChunkTimes {
  double observation, received, takeover, requested_takeover, first_waypoint, last_waypoint;
};

/// The record under the names of Sim.step()'s info["chunks"], its times given apart: the wire's
/// stamps, or a simulated clock that starts at 0 (a time the wire's all-zero "none" would hide).
py::dict chunkDict(const transport::ChunkTimingMessage& timing, const ChunkTimes& times) {
  py::dict d;
  d["sequence"] = timing.sequence;
  d["end"] = std::string(toString(timing.end));
  d["observation"] = times.observation;
  d["received"] = times.received;
  d["takeover"] = times.takeover;
  d["takeover_cycle"] = timing.end == transport::ChunkEnd::kTookOver
                            ? py::object(py::int_(timing.takeover_cycle))
                            : py::object(py::none());
  d["requested_takeover"] = times.requested_takeover;
  d["first_waypoint"] = times.first_waypoint;
  d["last_waypoint"] = times.last_waypoint;
  d["waypoints"] = timing.waypoints;
  d["waypoints_past"] = timing.waypoints_past;
  d["position_jump"] = timing.position_jump;
  d["rotation_jump"] = timing.rotation_jump;
  d["velocity_jump"] = timing.velocity_jump;
  d["angular_velocity_jump"] = timing.angular_velocity_jump;
  d["starved"] = timing.starved;
  d["rest"] = timing.rest_s;
  return d;
}

}  // namespace

py::dict toDict(const transport::ChunkTimingMessage& timing) {
  using transport::secondsOrNaN;
  return chunkDict(timing,
                   {secondsOrNaN(timing.observation), secondsOrNaN(timing.received),
                    secondsOrNaN(timing.takeover), secondsOrNaN(timing.requested_takeover),
                    secondsOrNaN(timing.first_waypoint), secondsOrNaN(timing.last_waypoint)});
}

py::dict toDict(const pipeline::NotedChunk& noted, double cycle_host_s) {
  const pipeline::ChunkTiming& t = noted.timing;
  const double controller_minus_host_s = noted.controller_s - cycle_host_s;
  const auto host = [&](double controller_s) { return controller_s - controller_minus_host_s; };
  return chunkDict(
      host::chunkTimingMessage(noted),
      {host(t.observation_s), host(t.received_s), host(t.takeover_s), host(t.requested_takeover_s),
       host(t.first_waypoint_s), host(t.last_waypoint_s)});
}

py::dict toDict(const transport::CommandOutcomeMessage& o) {
  py::dict d;
  d["stamp"] = o.stamp.nanoseconds();
  // "cartesian" or "joint" (a command), "request" (applied: the host carried it out).
  d["command_kind"] = std::string(toString(o.command_kind));
  d["applied"] = o.outcome == transport::Outcome::kApplied;
  d["reason"] = std::string(toString(o.reason));
  d["cycle"] = o.cycle;
  d["message"] = o.message;
  d["sender"] = transport::toHex(o.sender);
  // Send (the stamp) to the end of the cycle that applied it; one clock only on one machine. A
  // request is carried out by the host, not a cycle.
  const bool by_cycle = o.command_kind != transport::WireCommandKind::kRequest;
  d["latency_s"] = o.outcome == transport::Outcome::kApplied && by_cycle
                       ? py::object(py::float_(1e-9 * static_cast<double>(o.applied.nanoseconds() -
                                                                          o.stamp.nanoseconds())))
                       : py::object(py::none());
  // A chunk's timing record (docs/chunks.md); None for a command or request.
  d["chunk"] = o.chunk.empty() ? py::object(py::none()) : py::object(toDict(o.chunk.front()));
  return d;
}

py::dict toDict(const transport::DiagnosticsMessage& m) {
  py::dict d = messageDict(m);
  d["stamp"] = stampDict(m.header.stamp);
  py::dict rejections;  // by the reason's name, not its number
  for (std::size_t i = 0; i < m.rejections.size(); ++i) {
    rejections[py::str(std::string(toString(static_cast<transport::Reason>(i))))] = m.rejections[i];
  }
  d["rejections"] = rejections;
  return d;
}

py::dict toDict(const record::RecorderStats& stats) {
  py::dict d;
  d["written"] = stats.written;
  d["dropped"] = stats.dropped;
  d["bytes"] = stats.bytes;
  d["writer_cpu_s"] = stats.writer_cpu_s;
  d["error"] = stats.error;
  return d;
}

namespace {

/// One field of every command, stacked: the values' own shape after the row.
struct Stack {
  std::vector<py::ssize_t> shape;
  std::vector<double> values;
};

void append(const Eigen::Quaterniond& value, Stack& to) {
  to.shape = {4};
  to.values.insert(to.values.end(), value.coeffs().data(), value.coeffs().data() + 4);
}
void append(const Eigen::Matrix3d& value, Stack& to) {
  to.shape = {3, 3};
  for (int row = 0; row < 3; ++row) {
    for (int col = 0; col < 3; ++col) {
      to.values.push_back(value(row, col));
    }
  }
}
template <typename Vector>
void append(const Vector& value, Stack& to) {
  to.shape = {static_cast<py::ssize_t>(value.size())};
  to.values.insert(to.values.end(), value.data(), value.data() + value.size());
}

py::array_t<double> arrayOf(const Stack& stack, std::size_t rows) {
  std::vector<py::ssize_t> shape{static_cast<py::ssize_t>(rows)};
  shape.insert(shape.end(), stack.shape.begin(), stack.shape.end());
  py::array_t<double> out(shape);
  std::copy(stack.values.begin(), stack.values.end(), out.mutable_data());
  return out;
}

template <typename Command, typename T>
void stackField(py::dict& d, const char* name, const std::vector<Command>& commands,
                T Command::*member) {
  if constexpr (std::is_same_v<T, DampingMode>) {
    py::list modes;
    for (const Command& command : commands) {
      modes.append(command.*member == DampingMode::kRatio ? "ratio" : "absolute");
    }
    d[name] = modes;
  } else {
    Stack stack;
    for (const Command& command : commands) {
      append(command.*member, stack);
    }
    d[name] = arrayOf(stack, commands.size());
  }
}

#define COMPLY_STACK_FIELD(name, group, kind, type, unit, constraint, role, init, description) \
  stackField(d, #name, commands, &Command::name);

}  // namespace

py::dict toArrays(const std::vector<CartesianCommand>& commands) {
  using Command = CartesianCommand;
  py::dict d;
  COMPLY_CARTESIAN_COMMAND_FIELDS(COMPLY_STACK_FIELD)
  return d;
}

py::dict toArrays(const std::vector<JointCommand>& commands) {
  using Command = JointCommand;
  py::dict d;
  COMPLY_JOINT_COMMAND_FIELDS(COMPLY_STACK_FIELD)
  return d;
}

#undef COMPLY_STACK_FIELD

}  // namespace comply::python
