#pragma once
// comply.Sim's cameras (py_sim.hpp): their specs from Python's dict, and the frames of a step as
// numpy arrays and as the recording's compressed images.

#include <pybind11/pybind11.h>

#include <vector>

#include "comply/sim/sim_cameras.hpp"

namespace comply::python {

namespace py = pybind11;

/// `cameras`: None, or a dict of name -> dict of the camera's keys (docs/simulation.md's
/// "Cameras"): width, height, fovy, shadows, reflections, mount ("scene" or "tcp"); a scene
/// camera's lookat, distance, azimuth, elevation; a TCP camera's position and orientation (x y z w)
/// in the TCP frame. Raises ValueError naming the camera and the key that is wrong or unknown.
std::vector<sim::CameraSpec> cameraSpecs(const py::object& cameras);

/// The frames as a dict of name -> uint8 array (height, width, 3), rows top to bottom.
py::dict imagesDict(const std::vector<sim::CameraSpec>& specs,
                    const std::vector<sim::Image>& images);

}  // namespace comply::python
