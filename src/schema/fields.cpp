// The tables of schema/table.hpp as data, for documentation and messages.

#include <limits>
#include <type_traits>

#include "comply/core/enum_names.hpp"
#include "comply/schema/generic_json.hpp"
#include "field_kinds.hpp"

namespace comply::schema {
namespace {

template <typename T>
std::vector<EnumValue> enumValues() {
  std::vector<EnumValue> values;
  if constexpr (std::is_enum_v<T>) {
    for (const auto& [enumerator, name] : generic::EnumNames<T>::kNames) {
      values.push_back({name, static_cast<int>(enumerator)});
    }
  }
  return values;
}

#define COMPLY_SCHEMA_FIELD_INFO(name, group, kind, type, unit, constraint, role, init, doc) \
  FieldInfo{#name,                                                                           \
            CommandField::group,                                                             \
            FieldKind::kind,                                                                 \
            #type,                                                                           \
            unit,                                                                            \
            Constraint::constraint,                                                          \
            Role::role,                                                                      \
            doc,                                                                             \
            enumValues<type>()},

#define COMPLY_SCHEMA_GROUP_INFO(enumerator, name, doc) \
  GroupInfo{CommandField::enumerator, name, doc},

constexpr EnumNames<Constraint, 6> kConstraintNames{
    {{Constraint::kNone, "none"},
     {Constraint::kNonNegative, "non_negative"},
     {Constraint::kSymmetricPsd, "symmetric_psd"},
     {Constraint::kUnitQuaternion, "unit_quaternion"},
     {Constraint::kSelection, "selection"},
     {Constraint::kThreshold, "threshold"}}};

constexpr EnumNames<Role, 5> kRoleNames{{{Role::kNone, "none"},
                                         {Role::kSeedTcpPosition, "seed_tcp_position"},
                                         {Role::kSeedTcpOrientation, "seed_tcp_orientation"},
                                         {Role::kSeedJointPosition, "seed_joint_position"},
                                         {Role::kZeroOnStop, "zero_on_stop"}}};

}  // namespace

std::span<const FieldInfo> fields(CommandKind kind) {
  static const std::vector<FieldInfo> cartesian{
      COMPLY_CARTESIAN_COMMAND_FIELDS(COMPLY_SCHEMA_FIELD_INFO)};
  static const std::vector<FieldInfo> joint{COMPLY_JOINT_COMMAND_FIELDS(COMPLY_SCHEMA_FIELD_INFO)};
  return kind == CommandKind::kCartesian ? cartesian : joint;
}

std::span<const GroupInfo> groups() {
  static const std::vector<GroupInfo> list{COMPLY_COMMAND_FIELD_GROUPS(COMPLY_SCHEMA_GROUP_INFO)};
  return list;
}

std::string_view toString(CommandKind kind) {
  return kind == CommandKind::kCartesian ? "cartesian" : "joint";
}

std::string_view toString(FieldKind kind) {
  return static_cast<std::size_t>(kind) < std::size(kFieldKinds) ? spellingOf(kind).name
                                                                 : "unknown";
}

std::string_view toString(Constraint constraint) {
  return nameIn(kConstraintNames, constraint);
}

double gainLimit(std::string_view unit) noexcept {
  // The vendors' Cartesian impedance controllers stop near 5e3 N/m and 3e2 N m/rad, joint
  // impedance near 5e3 N m/rad; damping ratios beyond a few are already sluggish.
  struct Limit {
    std::string_view unit;
    double limit;
  };
  constexpr Limit kLimits[] = {
      {"N/m", 1e6},       {"N m/rad", 1e5},           {"N m/rad | N/m", 1e6}, {"N s/m", 1e5},
      {"N m s/rad", 1e4}, {"N m s/rad | N s/m", 1e5}, {"1", 100.0},
  };
  for (const Limit& entry : kLimits) {
    if (entry.unit == unit) {
      return entry.limit;
    }
  }
  return std::numeric_limits<double>::infinity();
}

double valueLimit(std::string_view unit) noexcept {
  // Arms' own limits: TCP 1-3 m/s and 2.5 rad/s, joints up to 5.3 rad/s and 20 rad/s^2, Cartesian
  // accelerations near 10 m/s^2, joint torques up to 330 N m, payloads near 300 N.
  struct Limit {
    std::string_view unit;
    double limit;
  };
  constexpr Limit kLimits[] = {
      {"m/s, rad/s", 100.0},    {"rad/s | m/s", 100.0}, {"m/s^2, rad/s^2", 1e3},
      {"rad/s^2 | m/s^2", 1e3}, {"N, N m", 1e4},        {"N m", 1e4},
      {"N m | N", 1e4},
  };
  for (const Limit& entry : kLimits) {
    if (entry.unit == unit) {
      return entry.limit;
    }
  }
  return std::numeric_limits<double>::infinity();
}

std::string_view toString(Role role) {
  return nameIn(kRoleNames, role);
}

}  // namespace comply::schema
