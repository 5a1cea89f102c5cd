#pragma once
// The MJCF text of a simulated scene: a robot's URDF as MuJoCo imports it, plus a floor, lights,
// an optional tool attached to the TCP and optional objects in the world.
//
// Tools and objects are MJCF fragments: a file whose root element is <mujocoinclude>, holding
// what may stand inside a <body> (geoms, sites, child bodies), e.g.
//
//   <mujocoinclude>
//     <geom name="probe" type="capsule" fromto="0 0 0 0 0 0.1" size="0.01" rgba="0.2 0.4 0.8 1"/>
//   </mujocoinclude>
//
// A tool fragment is placed in the TCP body, in TCP coordinates; an object fragment in the world
// body, in world (= robot base) coordinates.

#include <mujoco/mujoco.h>

#include <filesystem>
#include <string>
#include <vector>

#include "comply/model/robot_description.hpp"

namespace comply::sim {

struct SceneOptions {
  std::filesystem::path tool;                  ///< fragment attached to the TCP; empty: none
  std::vector<std::filesystem::path> objects;  ///< fragments added to the world
  int offscreen_width = 1280;                  ///< largest picture that can be rendered [px]
  int offscreen_height = 960;
};

/// The robot's URDF as MuJoCo MJCF: MuJoCo converts it (fixed frames kept as bodies, inertias
/// from <inertial> only), then the scene is added around it. Throws SimError naming the file on
/// an unreadable URDF or fragment, a fragment that is not <mujocoinclude>, or a URDF MuJoCo
/// rejects.
std::string buildSceneXml(const model::RobotDescription& robot, const SceneOptions& options);

/// Loads MJCF text into a model. Throws SimError with MuJoCo's message, prefixed by `what`.
mjModel* loadModelFromXml(const std::string& xml, const std::string& what);

}  // namespace comply::sim
