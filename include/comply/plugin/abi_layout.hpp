#pragma once
// The structs of abi.h as data: per struct its elements in declaration order with element type,
// count, offset and size taken from the compiler (offsetof/sizeof), so a listing cannot drift from
// the header in anything but a member left out, which tests/plugin/abi_layout_test.cpp catches by
// requiring the elements to tile the struct. Code generators (comply codegen simulink) read this
// instead of parsing C.

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>
#include <type_traits>

#include "comply/plugin/abi.h"
#include "comply/schema/table.hpp"

namespace comply::plugin::abi_layout {

enum class ScalarType { kDouble, kInt32, kUint32, kChar };

struct Element {
  std::string_view name;
  ScalarType type;
  std::size_t count;   ///< array length (1 for a scalar)
  std::size_t offset;  ///< bytes from the start of the struct
  std::size_t size;    ///< bytes
  std::string_view description;
};

struct Struct {
  std::string_view name;  ///< the C type name, also the bus name
  std::size_t size;
  std::size_t alignment;
  std::span<const Element> elements;
  std::string_view description;
};

template <typename T>
constexpr ScalarType scalarTypeOf() {
  if constexpr (std::is_same_v<T, double>) {
    return ScalarType::kDouble;
  } else if constexpr (std::is_same_v<T, int32_t>) {
    return ScalarType::kInt32;
  } else if constexpr (std::is_same_v<T, uint32_t>) {
    return ScalarType::kUint32;
  } else {
    static_assert(std::is_same_v<T, char>, "abi.h holds double, int32_t, uint32_t and char only");
    return ScalarType::kChar;
  }
}

/// Size in bytes and C alignment of a scalar type.
constexpr std::size_t scalarSize(ScalarType type) {
  return type == ScalarType::kDouble ? 8 : type == ScalarType::kChar ? 1 : 4;
}

}  // namespace comply::plugin::abi_layout

// One element of struct S: everything but the name and the description comes from the compiler.
#define COMPLY_ABI_ELEMENT(S, member, description)                                   \
  ::comply::plugin::abi_layout::Element {                                            \
#member,                                                                         \
        ::comply::plugin::abi_layout::scalarTypeOf < std::remove_all_extents_t <     \
            decltype(S::member)>>(),                                                 \
        sizeof(S::member) / sizeof(std::remove_all_extents_t <decltype(S::member)>), \
        offsetof(S, member), sizeof(S::member), description                          \
  }

namespace comply::plugin::abi_layout {

inline constexpr std::array kInputElements{
    COMPLY_ABI_ELEMENT(comply_input, dof, "joints in use"),
    COMPLY_ABI_ELEMENT(comply_input, available, "COMPLY_NEED_* computed this cycle"),
    COMPLY_ABI_ELEMENT(comply_input, time_s, "controller time since activation [s]"),
    COMPLY_ABI_ELEMENT(comply_input, period_s, "measured period of this cycle [s]"),
    COMPLY_ABI_ELEMENT(comply_input, position, "q [rad | m]"),
    COMPLY_ABI_ELEMENT(comply_input, velocity, "dq [rad/s | m/s]"),
    COMPLY_ABI_ELEMENT(comply_input, effort, "measured torque [N m | N]"),
    COMPLY_ABI_ELEMENT(comply_input, tcp_position, "base frame [m]"),
    COMPLY_ABI_ELEMENT(comply_input, tcp_orientation, "base frame, x y z w"),
    COMPLY_ABI_ELEMENT(comply_input, jacobian, "6 x dof, column-major, linear rows first"),
    COMPLY_ABI_ELEMENT(comply_input, mass_matrix,
                       "dof x dof, column-major, leading dimension COMPLY_MAX_DOF"),
    COMPLY_ABI_ELEMENT(comply_input, gravity, "g(q) [N m]"),
    COMPLY_ABI_ELEMENT(comply_input, coriolis, "C(q, dq) dq [N m]"),
};

// The command buses after their header: the schema table's fields in its order (its descriptions
// included), so that the bus objects and the schema cannot drift apart.
#define COMPLY_ABI_JOINT_FIELD(name, group, kind, type, unit, constraint, role, init, description) \
  COMPLY_ABI_ELEMENT(comply_joint_command, name, description),
#define COMPLY_ABI_CARTESIAN_FIELD(name, group, kind, type, unit, constraint, role, init, \
                                   description)                                           \
  COMPLY_ABI_ELEMENT(comply_cartesian_command, name, description),

inline constexpr std::array kJointCommandElements{
    COMPLY_ABI_ELEMENT(comply_joint_command, stamp_s, "sender time [s]"),
    COMPLY_ABI_ELEMENT(comply_joint_command, fields, "COMPLY_FIELD_* present"),
    COMPLY_ABI_ELEMENT(comply_joint_command, dof, "joints in use"),
    COMPLY_JOINT_COMMAND_FIELDS(COMPLY_ABI_JOINT_FIELD)};

inline constexpr std::array kCartesianCommandElements{
    COMPLY_ABI_ELEMENT(comply_cartesian_command, stamp_s, "sender time [s]"),
    COMPLY_ABI_ELEMENT(comply_cartesian_command, fields, "COMPLY_FIELD_* present"),
    COMPLY_ABI_ELEMENT(comply_cartesian_command, dof, "joints in use"),
    COMPLY_CARTESIAN_COMMAND_FIELDS(COMPLY_ABI_CARTESIAN_FIELD)};

#undef COMPLY_ABI_JOINT_FIELD
#undef COMPLY_ABI_CARTESIAN_FIELD

inline constexpr std::array kOutputElements{
    COMPLY_ABI_ELEMENT(comply_output, torque, "joint torque of the law [N m | N]"),
    COMPLY_ABI_ELEMENT(comply_output, message, "optional reason on error, NUL-terminated"),
};

// The structs that cross the plugin boundary by value, in the order code generators emit them.
inline constexpr std::array<Struct, 4> kStructs{{
    {"comply_input", sizeof(comply_input), alignof(comply_input), kInputElements,
     "what the wrapper hands the law each cycle: measured state and model quantities"},
    {"comply_joint_command", sizeof(comply_joint_command), alignof(comply_joint_command),
     kJointCommandElements, "joint impedance command (complete: the wrapper merges updates)"},
    {"comply_cartesian_command", sizeof(comply_cartesian_command),
     alignof(comply_cartesian_command), kCartesianCommandElements,
     "Cartesian impedance command (complete: the wrapper merges updates)"},
    {"comply_output", sizeof(comply_output), alignof(comply_output), kOutputElements,
     "the law's torque and an optional error message"},
}};

}  // namespace comply::plugin::abi_layout
