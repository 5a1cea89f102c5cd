#include "command_json.hpp"

#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <vector>

namespace comply::app {
namespace {

using nlohmann::json;

const std::map<std::string, CommandField>& fieldGroups() {
  static const std::map<std::string, CommandField> groups{
      {"position", CommandField::kPosition},
      {"velocity", CommandField::kVelocity},
      {"acceleration", CommandField::kAcceleration},
      {"stiffness", CommandField::kStiffness},
      {"damping", CommandField::kDamping},
      {"task_frame", CommandField::kTaskFrame},
      {"wrench_feedforward", CommandField::kWrenchFeedforward},
      {"torque_feedforward", CommandField::kTorqueFeedforward},
      {"nullspace", CommandField::kNullspace},
  };
  return groups;
}

/// Reads keys of one command object and remembers the groups they belong to.
class Reader {
 public:
  Reader(const json& object, std::map<std::string, CommandField> key_groups)
      : object_(object), key_groups_(std::move(key_groups)) {
    if (!object_.is_object()) {
      throw CommandJsonError("a command must be a JSON object");
    }
    for (const auto& [key, value] : object_.items()) {
      if (key != "stamp" && key != "fields" && key_groups_.count(key) == 0) {
        std::string known = "stamp, fields";
        for (const auto& entry : key_groups_) {
          known += ", " + entry.first;
        }
        throw CommandJsonError("unknown command field '" + key + "' (known: " + known + ")");
      }
      if (key_groups_.count(key) != 0) {
        present_ = present_ | key_groups_.at(key);
      }
    }
  }

  /// `count` numbers at `key` into `out`; false when absent.
  bool numbers(const std::string& key, std::size_t count, double* out) const {
    if (!object_.contains(key)) {
      return false;
    }
    const json& value = object_.at(key);
    std::vector<double> flat;
    try {
      if (value.is_array() && !value.empty() && value.front().is_array()) {
        for (const json& row : value) {
          for (const json& entry : row) {
            flat.push_back(entry.get<double>());
          }
        }
      } else {
        flat = value.get<std::vector<double>>();
      }
    } catch (const json::exception&) {
      throw CommandJsonError("'" + key + "' must be a list of numbers");
    }
    if (flat.size() != count) {
      throw CommandJsonError("'" + key + "' has " + std::to_string(flat.size()) +
                             " numbers, expected " + std::to_string(count));
    }
    std::copy(flat.begin(), flat.end(), out);
    return true;
  }

  template <typename Vector>
  void vector(const std::string& key, int count, Vector& out) const {
    std::vector<double> values(static_cast<std::size_t>(count));
    if (numbers(key, values.size(), values.data())) {
      out.resize(count);
      for (int i = 0; i < count; ++i) {
        out[i] = values[static_cast<std::size_t>(i)];
      }
    }
  }

  void block(const std::string& key, Eigen::Matrix3d& out) const {
    std::array<double, 9> values{};
    if (numbers(key, values.size(), values.data())) {
      out = Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(values.data());
    }
  }

  void quaternion(const std::string& key, Eigen::Quaterniond& out) const {
    std::array<double, 4> xyzw{};
    if (numbers(key, xyzw.size(), xyzw.data())) {
      out = Eigen::Quaterniond(xyzw[3], xyzw[0], xyzw[1], xyzw[2]);  // not normalised: validation
    }
  }

  void header(double& stamp, CommandField& fields) const {
    if (object_.contains("stamp")) {
      if (!object_.at("stamp").is_number()) {
        throw CommandJsonError("'stamp' must be a number [s]");
      }
      stamp = object_.at("stamp").get<double>();
    }
    fields = present_;
    if (object_.contains("fields")) {
      fields = CommandField::kNone;
      const json& list = object_.at("fields");
      if (!list.is_array()) {
        throw CommandJsonError("'fields' must be a list of field group names");
      }
      for (const json& name : list) {
        const auto found =
            name.is_string() ? fieldGroups().find(name.get<std::string>()) : fieldGroups().end();
        if (found == fieldGroups().end()) {
          throw CommandJsonError("'fields' holds an unknown group " + name.dump());
        }
        fields = fields | found->second;
      }
    }
  }

 private:
  const json& object_;
  std::map<std::string, CommandField> key_groups_;
  CommandField present_ = CommandField::kNone;
};

}  // namespace

JointCommand commandFromJson(const json& object, int dof, const JointCommand& base) {
  const Reader reader(object, {{"position", CommandField::kPosition},
                               {"velocity", CommandField::kVelocity},
                               {"acceleration", CommandField::kAcceleration},
                               {"stiffness", CommandField::kStiffness},
                               {"damping", CommandField::kDamping},
                               {"torque_feedforward", CommandField::kTorqueFeedforward}});
  JointCommand command = base;
  reader.header(command.stamp_s, command.fields);
  reader.vector("position", dof, command.position);
  reader.vector("velocity", dof, command.velocity);
  reader.vector("acceleration", dof, command.acceleration);
  reader.vector("stiffness", dof, command.stiffness);
  reader.vector("damping", dof, command.damping);
  reader.vector("torque_feedforward", dof, command.torque_feedforward);
  return command;
}

CartesianCommand commandFromJson(const json& object, int dof, const CartesianCommand& base) {
  const Reader reader(object, {{"position", CommandField::kPosition},
                               {"orientation", CommandField::kPosition},
                               {"twist", CommandField::kVelocity},
                               {"acceleration", CommandField::kAcceleration},
                               {"stiffness_translational", CommandField::kStiffness},
                               {"stiffness_rotational", CommandField::kStiffness},
                               {"damping_translational", CommandField::kDamping},
                               {"damping_rotational", CommandField::kDamping},
                               {"damping_mode", CommandField::kDamping},
                               {"damping_ratio", CommandField::kDamping},
                               {"task_frame", CommandField::kTaskFrame},
                               {"wrench_feedforward", CommandField::kWrenchFeedforward},
                               {"torque_feedforward", CommandField::kTorqueFeedforward},
                               {"nullspace_position", CommandField::kNullspace},
                               {"nullspace_stiffness", CommandField::kNullspace},
                               {"nullspace_damping", CommandField::kNullspace}});
  CartesianCommand command = base;
  reader.header(command.stamp_s, command.fields);
  reader.vector("position", 3, command.position);
  reader.quaternion("orientation", command.orientation);
  reader.vector("twist", 6, command.twist);
  reader.vector("acceleration", 6, command.acceleration);
  reader.block("stiffness_translational", command.stiffness_translational);
  reader.block("stiffness_rotational", command.stiffness_rotational);
  reader.block("damping_translational", command.damping_translational);
  reader.block("damping_rotational", command.damping_rotational);
  if (object.contains("damping_mode")) {
    const json& mode = object.at("damping_mode");
    if (mode == "absolute") {
      command.damping_mode = DampingMode::kAbsolute;
    } else if (mode == "ratio") {
      command.damping_mode = DampingMode::kRatio;
    } else {
      throw CommandJsonError("'damping_mode' must be \"absolute\" or \"ratio\"");
    }
  }
  reader.vector("damping_ratio", 6, command.damping_ratio);
  reader.quaternion("task_frame", command.task_frame);
  reader.vector("wrench_feedforward", 6, command.wrench_feedforward);
  reader.vector("torque_feedforward", dof, command.torque_feedforward);
  reader.vector("nullspace_position", dof, command.nullspace_position);
  reader.vector("nullspace_stiffness", dof, command.nullspace_stiffness);
  reader.vector("nullspace_damping", dof, command.nullspace_damping);
  return command;
}

}  // namespace comply::app
