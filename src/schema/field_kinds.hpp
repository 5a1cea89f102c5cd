#pragma once
// Every field kind and how each output spells it, one row per kind; private to src/schema. A new
// kind is one row here.

#include <cstddef>
#include <iterator>
#include <string_view>

#include "comply/schema/schema.hpp"

namespace comply::schema {

struct FieldKindSpelling {
  FieldKind kind;
  std::string_view name;       ///< toString(FieldKind): describe --format json
  std::string_view size_text;  ///< size and layout as a user writes it (kEnum: "", its values)
  std::string_view msg_type;   ///< the ROS 2 .msg type
  std::string_view idl_type;   ///< rosidl's DDS IDL type (octet and uint8 share the wire)
  std::string_view idl_bound;  ///< the IDL array bound after the member name ("" for none)
};

inline constexpr FieldKindSpelling kFieldKinds[] = {
    {FieldKind::kVector3, "vector3", "3", "float64[3]", "double", "[3]"},
    {FieldKind::kVector6, "vector6", "6", "float64[6]", "double", "[6]"},
    {FieldKind::kJointVector, "joint_vector", "dof", "float64[]", "sequence<double>", ""},
    {FieldKind::kBlock3, "block3x3", "3x3, row-major", "float64[9]", "double", "[9]"},
    {FieldKind::kQuaternion, "quaternion_xyzw", "4, x y z w", "float64[4]", "double", "[4]"},
    {FieldKind::kEnum, "enum", "", "uint8", "octet", ""},
};

constexpr bool listsEveryKindInOrder() {
  for (std::size_t i = 0; i < std::size(kFieldKinds); ++i) {
    if (static_cast<std::size_t>(kFieldKinds[i].kind) != i) {
      return false;
    }
  }
  return std::size(kFieldKinds) == static_cast<std::size_t>(FieldKind::kEnum) + 1;
}
static_assert(listsEveryKindInOrder(), "kFieldKinds: one row per FieldKind, in value order");

/// The row of `kind`.
constexpr const FieldKindSpelling& spellingOf(FieldKind kind) {
  return kFieldKinds[static_cast<std::size_t>(kind)];
}

}  // namespace comply::schema
