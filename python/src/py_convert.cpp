// Conversions between Python values and comply's (see py_convert.hpp).

#include "py_convert.hpp"

#include <pybind11/stl.h>

#include "comply/core/input_error.hpp"
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

template <typename Command>
Command fromKwargs(const py::dict& kwargs, int dof, const std::optional<Command>& base) {
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

CartesianCommand cartesianFromKwargs(const py::dict& kwargs, int dof,
                                     const std::optional<CartesianCommand>& base) {
  return fromKwargs<CartesianCommand>(kwargs, dof, base);
}

JointCommand jointFromKwargs(const py::dict& kwargs, int dof,
                             const std::optional<JointCommand>& base) {
  return fromKwargs<JointCommand>(kwargs, dof, base);
}

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

py::dict toDict(const transport::ControllerStateMessage& s) {
  py::dict d;
  d["stamp"] = s.header.stamp.seconds();
  d["state"] = std::string(toString(s.state));
  d["cycle"] = s.cycle;
  d["joint_names"] = s.joint_names;
  d["position"] = array(s.position);
  d["velocity"] = array(s.velocity);
  d["effort"] = array(s.effort);
  d["torque_command"] = array(s.torque_command);
  d["tcp_position"] = array(s.tcp_position);
  d["tcp_orientation"] = array(s.tcp_orientation);
  d["tcp_twist"] = array(s.tcp_twist);
  d["reference_stamp"] = s.reference_stamp.seconds();
  d["reference_position"] = array(s.reference_position);
  d["reference_orientation"] = array(s.reference_orientation);
  d["reference_joint_position"] = array(s.reference_joint_position);
  d["contact_wrench"] = array(s.contact_wrench);
  d["contact_wrench_source"] = std::string(toString(s.contact_wrench_source));
  d["contact_wrench_tcp"] = array(s.contact_wrench_tcp);
  d["contact_wrench_task"] = array(s.contact_wrench_task);
  d["contact_wrench_bandwidth"] = s.contact_wrench_bandwidth_hz;
  addPassivity({.enabled = s.passivity,
                .tank_energy_j = s.tank_energy_j,
                .nullspace_tank_energy_j = s.nullspace_tank_energy_j,
                .injected_j = s.energy_injected_j,
                .dissipated_j = s.energy_dissipated_j,
                .refused_j = s.energy_refused_j,
                .gain_fraction = s.gain_fraction},
               d);
  return d;
}

py::dict toDict(const transport::CommandOutcomeMessage& o) {
  py::dict d;
  d["stamp"] = o.stamp.nanoseconds();
  d["applied"] = o.outcome == transport::Outcome::kApplied;
  d["reason"] = std::string(toString(o.reason));
  d["cycle"] = o.cycle;
  d["message"] = o.message;
  d["sender"] = transport::toHex(o.sender);
  // Send (the stamp) to the end of the cycle that applied it; one clock only on one machine.
  d["latency_s"] = o.outcome == transport::Outcome::kApplied
                       ? py::object(py::float_(1e-9 * static_cast<double>(o.applied.nanoseconds() -
                                                                          o.stamp.nanoseconds())))
                       : py::object(py::none());
  return d;
}

py::dict toDict(const transport::DiagnosticsMessage& m) {
  py::dict d;
  d["stamp"] = stampDict(m.header.stamp);
  d["state"] = std::string(toString(m.state));
  d["cycles"] = m.cycles;
  d["overruns"] = m.overruns;
  d["commands_received"] = m.commands_received;
  d["commands_applied"] = m.commands_applied;
  d["commands_rejected"] = m.commands_rejected;
  py::dict rejections;
  for (std::size_t i = 0; i < m.rejections.size(); ++i) {
    rejections[py::str(std::string(toString(static_cast<transport::Reason>(i))))] = m.rejections[i];
  }
  d["rejections"] = rejections;
  d["watchdog_timeouts"] = m.watchdog_timeouts;
  d["faults"] = m.faults;
  d["rate_limit_hits"] = m.rate_limit_hits;
  d["effort_limit_hits"] = m.effort_limit_hits;
  d["period"] = m.period_s;
  d["last_fault"] = m.last_fault;
  d["last_rejection"] = m.last_rejection;
  d["publisher"] = m.publisher;
  d["records_dropped"] = m.records_dropped;
  d["recording"] = m.recording;
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

}  // namespace comply::python
