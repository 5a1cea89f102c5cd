#include "comply/sim/scene_xml.hpp"

#include <unistd.h>

#include <array>
#include <fstream>
#include <sstream>
#include <string_view>

#include "comply/core/temporary_file.hpp"
#include "comply/core/text_file.hpp"
#include "comply/core/xml_tags.hpp"
#include "comply/sim/sim_error.hpp"

namespace comply::sim {
namespace {

std::string readText(const std::filesystem::path& file, const std::string& what) {
  TextFile text = readTextFile(file);
  if (!text.ok()) {
    throw SimError(what + ": " + text.error);
  }
  return std::move(text.text);
}

/// MuJoCo 2.2 loads models from files only; a file it cannot have is a simulation error.
class ModelFile {
 public:
  ModelFile(const std::string& text, const char* suffix) try : file_(text, "scene", suffix) {
  } catch (const std::runtime_error& error) {
    throw SimError(error.what());
  }
  [[nodiscard]] const std::filesystem::path& path() const { return file_.path(); }

 private:
  TemporaryFile file_;
};

/// `xml` without <!-- --> comments, so that tags mentioned in comments are never matched.
std::string withoutComments(const std::string& xml) {
  std::string out;
  out.reserve(xml.size());
  std::size_t at = 0;
  while (at < xml.size()) {
    const std::size_t open = xml.find("<!--", at);
    if (open == std::string::npos) {
      out.append(xml, at);
      break;
    }
    out.append(xml, at, open - at);
    const std::size_t close = xml.find("-->", open + 4);
    at = close == std::string::npos ? xml.size() : close + 3;
  }
  return out;
}

/// The URDF with our <mujoco> compiler options in place of any it had: fixed-joint frames stay
/// bodies (the TCP must exist), inertias come from <inertial> only (as in the controller's
/// model), and relative mesh paths resolve against the robot's folder.
std::string urdfForMujoco(const model::RobotDescription& robot) {
  std::string urdf = withoutComments(readText(robot.urdf_path, "URDF"));
  if (const auto mujoco = findOpeningTag(urdf, "mujoco")) {
    std::size_t end = mujoco->end;
    if (!mujoco->selfClosing(urdf)) {
      const std::size_t close = urdf.find("</mujoco>", mujoco->end);
      if (close == std::string::npos) {
        throw SimError("URDF '" + robot.urdf_path.string() + "': unterminated <mujoco> element");
      }
      end = close + 9;
    }
    urdf.erase(mujoco->begin, end - mujoco->begin);
  }
  const auto robot_tag = findOpeningTag(urdf, "robot");
  if (!robot_tag || robot_tag->selfClosing(urdf)) {
    throw SimError("URDF '" + robot.urdf_path.string() + "' has no <robot> element with links");
  }
  urdf.insert(robot_tag->end,
              "<mujoco><compiler fusestatic=\"false\" discardvisual=\"true\" "
              "inertiafromgeom=\"false\" balanceinertia=\"true\" meshdir=\"" +
                  robot.folder.string() + "\"/></mujoco>");
  return urdf;
}

/// The MJCF MuJoCo writes for the robot's URDF.
std::string robotMjcf(const model::RobotDescription& robot) {
  const ModelFile urdf_file(urdfForMujoco(robot), ".urdf");
  std::array<char, 1024> error{};
  mjModel* model =
      mj_loadXML(urdf_file.path().c_str(), nullptr, error.data(), static_cast<int>(error.size()));
  if (model == nullptr) {
    throw SimError("MuJoCo cannot load the URDF of " + robot.name + " ('" +
                   robot.urdf_path.string() + "'): " + error.data());
  }
  const ModelFile mjcf_file("", ".xml");
  const int saved =
      mj_saveLastXML(mjcf_file.path().c_str(), model, error.data(), static_cast<int>(error.size()));
  mj_deleteModel(model);
  if (saved == 0) {
    throw SimError("MuJoCo cannot convert the URDF of " + robot.name + ": " + error.data());
  }
  return readText(mjcf_file.path(), "converted model");
}

/// What stands inside the <mujocoinclude> root of a fragment file.
std::string fragmentBody(const std::filesystem::path& file, const std::string& what) {
  const std::string xml = withoutComments(readText(file, what));
  const auto root = findOpeningTag(xml, "mujocoinclude");
  const std::size_t close = xml.rfind("</mujocoinclude>");
  if (!root || close == std::string::npos || close < root->end) {
    throw SimError(what + " '" + file.string() +
                   "': the root element must be <mujocoinclude> ... </mujocoinclude>");
  }
  return xml.substr(root->end, close - root->end);
}

/// Inserts `content` as the last children of the body named `name`.
void appendToBody(std::string& mjcf, const std::string& name, const std::string& content,
                  const std::string& robot_name) {
  const std::string attribute = "name=\"" + name + "\"";
  for (auto body = findOpeningTag(mjcf, "body"); body;
       body = findOpeningTag(mjcf, "body", body->end)) {
    if (mjcf.substr(body->begin, body->end - body->begin).find(attribute) == std::string::npos) {
      continue;
    }
    if (body->selfClosing(mjcf)) {  // <body .../>: open it up
      mjcf.replace(body->end - 2, 2, ">" + content + "</body>");
      return;
    }
    // The matching </body>: count nested bodies.
    int depth = 1;
    std::size_t cursor = body->end;
    while (depth > 0) {
      const auto next_open = findOpeningTag(mjcf, "body", cursor);
      const std::size_t next_close = mjcf.find("</body>", cursor);
      if (next_close == std::string::npos) {
        break;
      }
      if (next_open && next_open->begin < next_close) {
        depth += next_open->selfClosing(mjcf) ? 0 : 1;
        cursor = next_open->end;
      } else {
        --depth;
        cursor = depth == 0 ? next_close : next_close + 7;
      }
    }
    mjcf.insert(cursor, content);
    return;
  }
  throw SimError("the MuJoCo model of " + robot_name + " has no body '" + name +
                 "' to attach the tool to");
}

void insertAfterTag(std::string& mjcf, std::string_view tag, const std::string& content) {
  const auto opening = findOpeningTag(mjcf, tag);
  if (!opening) {
    throw SimError("converted model has no <" + std::string(tag) + "> element");
  }
  mjcf.insert(opening->end, content);
}

}  // namespace

std::string buildSceneXml(const model::RobotDescription& robot, const SceneOptions& options) {
  std::string mjcf = robotMjcf(robot);

  if (!options.tool.empty()) {
    appendToBody(mjcf, robot.tcp_frame, fragmentBody(options.tool, "tool fragment"), robot.name);
  }
  std::string objects;
  for (const std::filesystem::path& file : options.objects) {
    objects += fragmentBody(file, "object fragment");
  }
  const std::size_t world_end = mjcf.rfind("</worldbody>");
  if (world_end == std::string::npos) {
    throw SimError("converted model of " + robot.name + " has no </worldbody>");
  }
  mjcf.insert(world_end, objects);

  // Floor at z = 0 (the robot base stands on it), a key and a fill light, a checker floor.
  insertAfterTag(mjcf, "worldbody",
                 "<light name=\"comply_key\" directional=\"true\" pos=\"1 -1 3\" "
                 "dir=\"-0.4 0.4 -1\" diffuse=\"0.7 0.7 0.7\" castshadow=\"true\"/>"
                 "<light name=\"comply_fill\" directional=\"true\" pos=\"-1 1 3\" "
                 "dir=\"0.5 -0.3 -1\" diffuse=\"0.3 0.3 0.3\" castshadow=\"false\"/>"
                 "<geom name=\"comply_floor\" type=\"plane\" size=\"3 3 0.1\" "
                 "material=\"comply_floor\"/>");
  insertAfterTag(
      mjcf, "mujoco",
      "<visual><global offwidth=\"" + std::to_string(options.offscreen_width) + "\" offheight=\"" +
          std::to_string(options.offscreen_height) +
          "\"/><quality shadowsize=\"2048\"/><headlight ambient=\"0.35 0.35 0.35\" "
          "diffuse=\"0.3 0.3 0.3\"/></visual>"
          "<asset><texture name=\"comply_sky\" type=\"skybox\" builtin=\"gradient\" "
          "rgb1=\"1 1 1\" rgb2=\"0.86 0.89 0.93\" width=\"256\" height=\"256\"/>"
          "<texture name=\"comply_checker\" type=\"2d\" builtin=\"checker\" "
          "rgb1=\"0.82 0.82 0.8\" rgb2=\"0.72 0.72 0.7\" width=\"256\" height=\"256\"/>"
          "<material name=\"comply_floor\" texture=\"comply_checker\" texrepeat=\"12 12\" "
          "reflectance=\"0.05\"/></asset>");
  return mjcf;
}

mjModel* loadModelFromXml(const std::string& xml, const std::string& what) {
  const ModelFile file(xml, ".xml");
  std::array<char, 1024> error{};
  mjModel* model =
      mj_loadXML(file.path().c_str(), nullptr, error.data(), static_cast<int>(error.size()));
  if (model == nullptr) {
    throw SimError("MuJoCo cannot load " + what + ": " + error.data());
  }
  return model;
}

}  // namespace comply::sim
