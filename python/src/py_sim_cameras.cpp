// comply.Sim's cameras (see py_sim_cameras.hpp).

#include "py_sim_cameras.hpp"

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <cstring>
#include <set>
#include <string>

#include "comply/sim/sim_error.hpp"

namespace comply::python {
namespace {

std::vector<double> numbers(const py::handle& value, std::size_t count, const std::string& what) {
  std::vector<double> out;
  try {
    out = py::cast<std::vector<double>>(value);
  } catch (const py::cast_error&) {
    throw py::value_error(what + " must be " + std::to_string(count) + " numbers");
  }
  if (out.size() != count) {
    throw py::value_error(what + " must be " + std::to_string(count) + " numbers, not " +
                          std::to_string(out.size()));
  }
  return out;
}

/// One camera's keys into `spec` (its name already set).
void readKeys(const py::dict& keys, sim::CameraSpec& spec) {
  static const std::set<std::string> kScene = {"lookat", "distance", "azimuth", "elevation"};
  static const std::set<std::string> kTcp = {"position", "orientation"};
  static const std::set<std::string> kCommon = {"width", "height",  "fovy",
                                                "mount", "shadows", "reflections"};
  const std::string which = "camera '" + spec.name + "'";
  if (keys.contains("mount")) {
    const auto mount = keys["mount"].cast<std::string>();
    if (mount != "scene" && mount != "tcp") {
      throw py::value_error(which + ": mount must be 'scene' or 'tcp', not '" + mount + "'");
    }
    spec.mount = mount == "tcp" ? sim::CameraMount::kTcp : sim::CameraMount::kScene;
  }
  Eigen::Vector3d position = spec.tcp_from_camera.translation();
  Eigen::Quaterniond orientation(spec.tcp_from_camera.linear());
  for (const auto& [key_handle, value] : keys) {
    const auto key = key_handle.cast<std::string>();
    const std::string what = which + ": " + key;
    const bool scene_key = kScene.contains(key);
    const bool tcp_key = kTcp.contains(key);
    if (!scene_key && !tcp_key && !kCommon.contains(key)) {
      throw py::value_error(which + ": unknown key '" + key +
                            "' (width, height, fovy, mount, shadows, reflections; lookat, "
                            "distance, azimuth, elevation "
                            "for mount 'scene'; position, orientation for mount 'tcp')");
    }
    if ((scene_key && spec.mount != sim::CameraMount::kScene) ||
        (tcp_key && spec.mount != sim::CameraMount::kTcp)) {
      throw py::value_error(what + " is not a key of a camera with mount '" +
                            (spec.mount == sim::CameraMount::kTcp ? "tcp" : "scene") + "'");
    }
    if (key == "width") {
      spec.width_px = value.cast<int>();
    } else if (key == "height") {
      spec.height_px = value.cast<int>();
    } else if (key == "shadows") {
      spec.shadows = value.cast<bool>();
    } else if (key == "reflections") {
      spec.reflections = value.cast<bool>();
    } else if (key == "fovy") {
      spec.fovy_deg = value.cast<double>();
    } else if (key == "lookat") {
      const std::vector<double> lookat = numbers(value, 3, what);
      std::copy(lookat.begin(), lookat.end(), spec.view.lookat);
    } else if (key == "distance") {
      spec.view.distance_m = value.cast<double>();
    } else if (key == "azimuth") {
      spec.view.azimuth_deg = value.cast<double>();
    } else if (key == "elevation") {
      spec.view.elevation_deg = value.cast<double>();
    } else if (key == "position") {
      const std::vector<double> p = numbers(value, 3, what);
      position = Eigen::Vector3d(p[0], p[1], p[2]);
    } else if (key == "orientation") {
      const std::vector<double> q = numbers(value, 4, what + " (x y z w)");
      orientation = Eigen::Quaterniond(q[3], q[0], q[1], q[2]);
      if (!(std::abs(orientation.norm() - 1.0) < 1e-3)) {
        throw py::value_error(what + " is not a unit quaternion (x y z w)");
      }
    }
  }
  spec.tcp_from_camera.linear() = orientation.normalized().toRotationMatrix();
  spec.tcp_from_camera.translation() = position;
}

}  // namespace

std::vector<sim::CameraSpec> cameraSpecs(const py::object& cameras) {
  std::vector<sim::CameraSpec> specs;
  if (cameras.is_none()) {
    return specs;
  }
  if (!py::isinstance<py::dict>(cameras)) {
    throw py::value_error("cameras must be a dict of name -> the camera's keys");
  }
  for (const auto& [name, keys] : cameras.cast<py::dict>()) {
    sim::CameraSpec spec;
    spec.name = name.cast<std::string>();
    if (!py::isinstance<py::dict>(keys)) {
      throw py::value_error("camera '" + spec.name + "' must be a dict of its keys");
    }
    readKeys(keys.cast<py::dict>(), spec);
    specs.push_back(std::move(spec));
  }
  try {
    sim::checkCameraSpecs(specs);
  } catch (const sim::SimError& error) {
    throw py::value_error(error.what());
  }
  return specs;
}

py::dict imagesDict(const std::vector<sim::CameraSpec>& specs,
                    const std::vector<sim::Image>& images) {
  py::dict out;
  for (std::size_t i = 0; i < specs.size(); ++i) {
    const sim::Image& image = images[i];
    py::array_t<std::uint8_t> pixels({image.height, image.width, 3});
    std::memcpy(pixels.mutable_data(), image.rgb.data(), image.rgb.size());
    out[py::str(specs[i].name)] = std::move(pixels);
  }
  return out;
}

}  // namespace comply::python
