// The `initial:` block of a controller file, read with the command reader (see json.hpp).

#include <nlohmann/json.hpp>

#include "comply/core/input_error.hpp"
#include "comply/schema/json.hpp"

namespace comply::schema {
namespace {

/// The role of `key` in a kind's table; nullopt when the table has no such field.
std::optional<Role> roleOf(CommandKind kind, const std::string& key) {
  for (const FieldInfo& field : fields(kind)) {
    if (field.name == key) {
      return field.role;
    }
  }
  return std::nullopt;
}

/// A group a command sets for a phase of its task, whose value at the start the controller file
/// gives elsewhere: the reflex's thresholds (reflex.*) and the workspace box (boxes:).
bool isPhaseGroup(CommandField group) {
  return group == CommandField::kReflex || group == CommandField::kWorkspace;
}

/// The phase group `key` belongs to (the Cartesian table holds every one), or kNone.
CommandField phaseGroupOf(const std::string& key) {
  for (const FieldInfo& field : fields(CommandKind::kCartesian)) {
    if (field.name == key) {
      return isPhaseGroup(field.group) ? field.group : CommandField::kNone;
    }
  }
  return CommandField::kNone;
}

std::string initialKeys() {
  std::string known;
  for (const CommandKind kind : {CommandKind::kJoint, CommandKind::kCartesian}) {
    for (const FieldInfo& field : fields(kind)) {
      const bool listed = known.find(" " + std::string(field.name) + ",") != std::string::npos;
      if (field.role == Role::kNone && !isPhaseGroup(field.group) && !listed) {
        known += " " + std::string(field.name) + ",";
      }
    }
  }
  return known.substr(1, known.size() - 2);
}

template <typename Command>
Command readKind(const nlohmann::json& object, int dof, const Command& base,
                 const std::string& source, const std::string& key_prefix) {
  ReadOptions<Command> options;
  options.allow_shorthand = true;
  options.base = base;
  options.source = source;
  options.key_prefix = key_prefix;
  Command command = fromJson(object, dof, options).command;
  command.fields = CommandField::kAll;
  CheckOptions check;
  check.quaternion_tolerance = 1e-6;
  const CheckResult result = checkFields(command, dof, check);
  if (!result.ok()) {
    throw InputError(InputErrc::kOutOfRange, source, key_prefix + result.field, result.message);
  }
  return command;
}

}  // namespace

InitialCommands defaultInitialCommands(int dof) {
  InitialCommands initial{JointCommand::zero(dof), CartesianCommand::zero(dof)};
  initial.joint.stiffness.setConstant(dof, 100.0);
  initial.joint.damping.setConstant(dof, 10.0);
  CartesianCommand& cartesian = initial.cartesian;
  cartesian.stiffness_translational = 500.0 * Eigen::Matrix3d::Identity();
  cartesian.stiffness_rotational = 30.0 * Eigen::Matrix3d::Identity();
  cartesian.damping_translational = 45.0 * Eigen::Matrix3d::Identity();
  cartesian.damping_rotational = 3.0 * Eigen::Matrix3d::Identity();
  cartesian.damping_mode = DampingMode::kRatio;
  cartesian.damping_ratio.setOnes();
  cartesian.nullspace_stiffness.setConstant(dof, 2.0);
  cartesian.nullspace_damping.setConstant(dof, 0.5);
  return initial;
}

InitialCommands readInitialCommands(const nlohmann::json& object, int dof,
                                    const std::string& source, const std::string& key_prefix) {
  InitialCommands initial = defaultInitialCommands(dof);
  if (object.is_null()) {
    return initial;
  }
  const std::string block =
      key_prefix.empty() ? key_prefix : key_prefix.substr(0, key_prefix.size() - 1);
  if (!object.is_object()) {
    throw InputError(InputErrc::kWrongType, source, block, "must be a mapping");
  }
  nlohmann::json joint = nlohmann::json::object();
  nlohmann::json cartesian = nlohmann::json::object();
  for (const auto& [key, value] : object.items()) {
    // One place for the file's own value; a command sets it per phase.
    const CommandField phase_group = phaseGroupOf(key);
    if (phase_group == CommandField::kReflex) {
      throw InputError(InputErrc::kInvalidValue, source, key_prefix + key,
                       "is set by the options reflex.force_n and reflex.torque_nm (a command sets "
                       "it for a phase of its task)");
    }
    if (phase_group == CommandField::kWorkspace) {
      throw InputError(InputErrc::kInvalidValue, source, key_prefix + key,
                       "is set by boxes: in the controller file (a command sets a box for a "
                       "phase of its task)");
    }
    const std::optional<Role> joint_role = roleOf(CommandKind::kJoint, key);
    const std::optional<Role> cartesian_role = roleOf(CommandKind::kCartesian, key);
    if (joint_role == Role::kNone) {
      joint[key] = value;
    }
    if (cartesian_role == Role::kNone) {
      cartesian[key] = value;
    }
    if (joint_role != Role::kNone && cartesian_role != Role::kNone) {
      const bool known = joint_role.has_value() || cartesian_role.has_value();
      throw InputError(known ? InputErrc::kInvalidValue : InputErrc::kUnknownKey, source,
                       key_prefix + key,
                       known ? "is set from the measured state when the controller starts"
                             : "is not a known option (known: " + initialKeys() + ")");
    }
  }
  initial.joint = readKind(joint, dof, initial.joint, source, key_prefix);
  initial.cartesian = readKind(cartesian, dof, initial.cartesian, source, key_prefix);
  return initial;
}

}  // namespace comply::schema
