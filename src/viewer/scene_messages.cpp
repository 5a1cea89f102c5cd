// The 3D panel's transforms and markers (see scene_messages.hpp).

#include "comply/viewer/scene_messages.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <nlohmann/json.hpp>

namespace comply::viewer {
namespace {

using nlohmann::json;

json timeJson(std::int64_t time_ns) {
  const std::int64_t sec = time_ns >= 0 ? time_ns / 1'000'000'000 : 0;
  return {{"sec", sec}, {"nsec", time_ns >= 0 ? time_ns % 1'000'000'000 : 0}};
}

json vectorJson(const Eigen::Vector3d& v) {
  return {{"x", v.x()}, {"y", v.y()}, {"z", v.z()}};
}

json quaternionJson(const Eigen::Quaterniond& q) {
  return {{"x", q.x()}, {"y", q.y()}, {"z", q.z()}, {"w", q.w()}};
}

json poseJson(const Eigen::Vector3d& position, const Eigen::Quaterniond& orientation) {
  return {{"position", vectorJson(position)}, {"orientation", quaternionJson(orientation)}};
}

json colorJson(double r, double g, double b, double a) {
  return {{"r", r}, {"g", g}, {"b", b}, {"a", a}};
}

json transformJson(std::int64_t time_ns, const std::string& parent, const std::string& child,
                   const Eigen::Vector3d& translation, const Eigen::Quaterniond& rotation) {
  return {{"timestamp", timeJson(time_ns)},
          {"parent_frame_id", parent},
          {"child_frame_id", child},
          {"translation", vectorJson(translation)},
          {"rotation", quaternionJson(rotation)}};
}

json entityJson(std::int64_t time_ns, const std::string& frame_id, std::string_view id) {
  json entity = {
      {"timestamp", timeJson(time_ns)}, {"frame_id", frame_id},  {"id", id},
      {"lifetime", timeJson(0)},        {"frame_locked", false}, {"metadata", json::array()}};
  for (const char* kind :
       {"arrows", "cubes", "spheres", "cylinders", "lines", "triangles", "texts", "models"}) {
    entity[kind] = json::array();
  }
  return entity;
}

json stiffnessEntity(std::int64_t time_ns, const ArmMarkers& markers) {
  json entity = entityJson(time_ns, markers.frame_id, kStiffnessEntity);
  if (markers.stiffness) {
    const StiffnessEllipsoid ellipsoid =
        stiffnessEllipsoid(markers.stiffness_task, markers.task_frame);
    entity["spheres"].push_back({{"pose", poseJson(markers.tcp_position, ellipsoid.orientation)},
                                 {"size", vectorJson(ellipsoid.lengths_m)},
                                 {"color", colorJson(0.2, 0.55, 1.0, 0.35)}});
  }
  return entity;
}

json forceEntity(std::int64_t time_ns, const ArmMarkers& markers) {
  json entity = entityJson(time_ns, markers.frame_id, kContactForceEntity);
  const double force_n = markers.contact_force.norm();
  if (force_n >= kForceArrowMinimumN) {
    const double length = std::min(force_n * kForceArrowMPerN, kForceArrowMaximumM);
    const Eigen::Quaterniond along =
        Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitX(), markers.contact_force);
    entity["arrows"].push_back({{"pose", poseJson(markers.tcp_position, along)},
                                {"shaft_length", 0.8 * length},
                                {"shaft_diameter", 0.008},
                                {"head_length", 0.2 * length},
                                {"head_diameter", 0.02},
                                {"color", colorJson(1.0, 0.3, 0.1, 0.9)}});
  }
  return entity;
}

json pathEntity(std::int64_t time_ns, const ArmMarkers& markers) {
  json entity = entityJson(time_ns, markers.frame_id, kChunkPathEntity);
  if (markers.path.size() >= 2) {
    json points = json::array();
    for (const Eigen::Vector3d& point : markers.path) {
      points.push_back(vectorJson(point));
    }
    entity["lines"].push_back(
        {{"type", 0},  // LINE_STRIP
         {"pose", poseJson(Eigen::Vector3d::Zero(), Eigen::Quaterniond::Identity())},
         {"thickness", 0.004},
         {"scale_invariant", false},
         {"points", std::move(points)},
         {"color", colorJson(0.1, 0.8, 0.3, 1.0)},
         {"colors", json::array()},
         {"indices", json::array()}});
  }
  return entity;
}

json objectSchema(json properties) {
  return {{"type", "object"}, {"properties", std::move(properties)}};
}

json numbersSchema(std::initializer_list<const char*> names) {
  json properties = json::object();
  for (const char* name : names) {
    properties[name] = {{"type", "number"}};
  }
  return objectSchema(std::move(properties));
}

json timeSchema() {
  return objectSchema({{"sec", {{"type", "integer"}}}, {"nsec", {{"type", "integer"}}}});
}

json poseSchema() {
  return objectSchema({{"position", numbersSchema({"x", "y", "z"})},
                       {"orientation", numbersSchema({"x", "y", "z", "w"})}});
}

json arrayOf(json items) {
  return {{"type", "array"}, {"items", std::move(items)}};
}

}  // namespace

StiffnessEllipsoid stiffnessEllipsoid(const Eigen::Matrix3d& stiffness_task,
                                      const Eigen::Quaterniond& task_frame) {
  const Eigen::Matrix3d symmetric = 0.5 * (stiffness_task + stiffness_task.transpose());
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(symmetric);
  Eigen::Matrix3d axes = solver.eigenvectors();
  if (axes.determinant() < 0.0) {
    axes.col(2) *= -1.0;  // a rotation, not a reflection
  }
  StiffnessEllipsoid ellipsoid;
  ellipsoid.orientation = (task_frame.normalized() * Eigen::Quaterniond(axes)).normalized();
  for (int i = 0; i < 3; ++i) {
    ellipsoid.lengths_m[i] = std::max(solver.eigenvalues()[i] * kStiffnessEllipsoidMPerNPerM,
                                      kStiffnessEllipsoidMinimumM);
  }
  return ellipsoid;
}

std::string frameTransformsJson(std::int64_t time_ns, const std::vector<LinkTransform>& links,
                                const std::vector<ExtraFrame>& extra) {
  json transforms = json::array();
  for (const LinkTransform& link : links) {
    transforms.push_back(transformJson(time_ns, link.parent, link.child,
                                       link.parent_to_child.translation(),
                                       Eigen::Quaterniond(link.parent_to_child.linear())));
  }
  for (const ExtraFrame& frame : extra) {
    transforms.push_back(
        transformJson(time_ns, frame.parent, frame.child, frame.translation, frame.rotation));
  }
  return json{{"transforms", std::move(transforms)}}.dump();
}

std::string sceneUpdateJson(std::int64_t time_ns, const ArmMarkers& markers) {
  return json{{"deletions", json::array()},
              {"entities",
               {stiffnessEntity(time_ns, markers), forceEntity(time_ns, markers),
                pathEntity(time_ns, markers)}}}
      .dump();
}

std::string frameTransformsSchema() {
  const json transform = objectSchema({{"timestamp", timeSchema()},
                                       {"parent_frame_id", {{"type", "string"}}},
                                       {"child_frame_id", {{"type", "string"}}},
                                       {"translation", numbersSchema({"x", "y", "z"})},
                                       {"rotation", numbersSchema({"x", "y", "z", "w"})}});
  json schema = objectSchema({{"transforms", arrayOf(transform)}});
  schema["title"] = "foxglove.FrameTransforms";
  return schema.dump();
}

std::string sceneUpdateSchema() {
  const json color = numbersSchema({"r", "g", "b", "a"});
  const json sphere = objectSchema(
      {{"pose", poseSchema()}, {"size", numbersSchema({"x", "y", "z"})}, {"color", color}});
  json arrow = objectSchema({{"pose", poseSchema()}, {"color", color}});
  for (const char* size : {"shaft_length", "shaft_diameter", "head_length", "head_diameter"}) {
    arrow["properties"][size] = {{"type", "number"}};
  }
  const json line = objectSchema({{"type", {{"type", "integer"}}},
                                  {"pose", poseSchema()},
                                  {"thickness", {{"type", "number"}}},
                                  {"scale_invariant", {{"type", "boolean"}}},
                                  {"points", arrayOf(numbersSchema({"x", "y", "z"}))},
                                  {"color", color},
                                  {"colors", arrayOf(color)},
                                  {"indices", arrayOf({{"type", "integer"}})}});
  json entity = objectSchema({{"timestamp", timeSchema()},
                              {"frame_id", {{"type", "string"}}},
                              {"id", {{"type", "string"}}},
                              {"lifetime", timeSchema()},
                              {"frame_locked", {{"type", "boolean"}}},
                              {"metadata", arrayOf(json::object())},
                              {"arrows", arrayOf(arrow)},
                              {"spheres", arrayOf(sphere)},
                              {"lines", arrayOf(line)}});
  for (const char* kind : {"cubes", "cylinders", "triangles", "texts", "models"}) {
    entity["properties"][kind] = arrayOf(json::object());
  }
  json schema = objectSchema(
      {{"deletions", arrayOf(json::object())}, {"entities", arrayOf(std::move(entity))}});
  schema["title"] = "foxglove.SceneUpdate";
  return schema.dump();
}

std::vector<std::uint8_t> stringMessageCdr(std::string_view text) {
  // Encapsulation (CDR, little-endian), the string's length with its terminating NUL, its bytes.
  std::vector<std::uint8_t> bytes{0x00, 0x01, 0x00, 0x00};
  const auto length = static_cast<std::uint32_t>(text.size() + 1);
  for (int i = 0; i < 4; ++i) {
    bytes.push_back(static_cast<std::uint8_t>(length >> (8 * i)));
  }
  bytes.insert(bytes.end(), text.begin(), text.end());
  bytes.push_back(0);
  return bytes;
}

}  // namespace comply::viewer
