// The `comply._comply` extension: Client, Sim and the task-frame builders (python/comply re-exports
// them). numpy arrays in and out; keywords are the command schema's field names.

#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

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

}  // namespace

PYBIND11_MODULE(_comply, m) {
  m.doc() = "comply: live compliant control over DDS, and an in-process simulator";

  py::class_<Client>(m, "Client")
      .def(py::init<const std::string&, int, const std::string&, double>(),
           py::arg("name") = "comply", py::arg("domain") = 0, py::arg("network") = "loopback",
           py::arg("timeout") = 10.0)
      .def("send_cartesian", &Client::sendCartesian,
           "Send a Cartesian command by schema keywords; returns its stamp [ns]. Waits while "
           "the host is behind; RuntimeError when it acknowledged nothing for 0.1 s")
      .def("send_joint", &Client::sendJoint,
           "Send a joint command; returns its stamp [ns]. Waits and raises as send_cartesian")
      .def("state", &Client::state, py::arg("timeout") = 1.0)
      .def("diagnostics", &Client::diagnostics, py::arg("timeout") = 1.0)
      .def("outcome", &Client::outcome, py::arg("stamp"), py::arg("timeout") = 1.0)
      .def("wait_until", &Client::waitUntil, py::arg("predicate"), py::arg("timeout") = 10.0)
      .def("activate", [](Client& c) { c.request(comply::transport::RequestType::kActivate); })
      .def("deactivate", [](Client& c) { c.request(comply::transport::RequestType::kDeactivate); })
      .def("reset", [](Client& c) { c.request(comply::transport::RequestType::kReset); })
      .def_property_readonly("dof", &Client::dof)
      .def_property_readonly("cartesian", &Client::cartesian);

  py::class_<Sim>(m, "Sim")
      .def(py::init<const std::string&, const std::string&, int, double>(), py::arg("config"),
           py::arg("robot") = "", py::arg("steps_per_action") = 50, py::arg("max_time") = 0.0)
      .def("reset", &Sim::reset)
      .def("step", &Sim::step, py::arg("command") = py::none())
      .def_property_readonly("dof", &Sim::dof)
      .def_property_readonly("cartesian", &Sim::cartesian)
      .def_property_readonly("time", &Sim::time);

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
