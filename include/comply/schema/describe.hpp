#pragma once
// The schema as documentation and messages, generated from the tables: `comply schema` prints
// these, and docs/command-schema.md and msg/*.msg are their committed output.

#include <string>

#include "comply/schema/schema.hpp"

namespace comply::schema {

/// docs/command-schema.md: groups, both field tables, JSON and YAML notes.
std::string markdownDocument();
/// One kind's field table (name, group, type/size, unit, constraint, description).
std::string markdownTable(CommandKind kind);
/// The fields of one kind as a JSON array of row objects, or of both as {"cartesian", "joint"}.
std::string jsonDescription(CommandKind kind);
std::string jsonDescription();
/// ROS 2 interface text of comply_msgs/CartesianCommand or JointCommand (msg/*.msg).
std::string rosMessage(CommandKind kind);
/// The DDS IDL of the same message as ROS 2's rosidl puts it on the wire (module
/// comply_msgs::msg::dds_, type CartesianCommand_ or JointCommand_): src/transport/idl/.
std::string ddsIdl(CommandKind kind);

}  // namespace comply::schema
