#pragma once
// comply.Sim: the in-process simulator (the wrapper and a MuJoCo plant, no network), shaped like
// a Gymnasium environment without needing gymnasium: reset() -> observation, step(command) ->
// (observation, reward, terminated, truncated, info). One step holds the command for
// `steps_per_action` control cycles (50 at 1 kHz: a 20 Hz policy).

#include <pybind11/pybind11.h>

#include <memory>
#include <optional>
#include <string>

#include "comply/pipeline/resolved_controller.hpp"

namespace comply::python {

namespace py = pybind11;

class Sim {
 public:
  Sim(const std::string& config, const std::string& robot, int steps_per_action, double max_time_s);
  ~Sim();

  /// A fresh plant at the robot's home pose and a freshly activated controller.
  py::dict reset();
  /// `command`: a dict of schema keywords (or None: no new command). Never raises on a rejected
  /// command: info["accepted"] is False and info["reason"] says why.
  py::tuple step(const py::object& command);

  [[nodiscard]] int dof() const noexcept;
  [[nodiscard]] bool cartesian() const noexcept;
  [[nodiscard]] double time() const noexcept;

 private:
  struct Session;
  std::shared_ptr<const pipeline::ResolvedController> resolved_;
  std::unique_ptr<Session> session_;
  int steps_per_action_;
  double max_time_s_;
};

}  // namespace comply::python
