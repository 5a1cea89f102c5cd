#pragma once
// The two real schemas, made from the tables of schema/table.hpp; private to src/schema.

#include <type_traits>

#include "comply/schema/generic.hpp"

namespace comply::schema {

COMPLY_SCHEMA_DEFINE(CartesianSchema, CartesianCommand, comply_cartesian_command,
                     COMPLY_CARTESIAN_COMMAND_FIELDS);
COMPLY_SCHEMA_DEFINE(JointSchema, JointCommand, comply_joint_command, COMPLY_JOINT_COMMAND_FIELDS);

template <typename Command>
using SchemaOf =
    std::conditional_t<std::is_same_v<Command, CartesianCommand>, CartesianSchema, JointSchema>;

}  // namespace comply::schema
