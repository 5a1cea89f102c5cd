// Documentation and ROS 2 messages generated from the field tables (see describe.hpp).

#include "comply/schema/describe.hpp"

#include <cmath>
#include <nlohmann/json.hpp>
#include <sstream>

#include "comply/core/upper_case.hpp"

namespace comply::schema {
namespace {

std::string_view groupName(CommandField field) {
  for (const GroupInfo& group : groups()) {
    if (group.field == field) {
      return group.name;
    }
  }
  return "?";
}

std::string valueNames(const FieldInfo& field, std::string_view separator) {
  std::string text;
  for (const EnumValue& value : field.values) {
    text += (text.empty() ? "" : std::string(separator)) + std::string(value.name);
  }
  return text;
}

/// Size and layout as a user writes it.
std::string typeText(const FieldInfo& field) {
  switch (field.kind) {
    case FieldKind::kVector3:
      return "3";
    case FieldKind::kVector6:
      return "6";
    case FieldKind::kJointVector:
      return "dof";
    case FieldKind::kBlock3:
      return "3x3, row-major";
    case FieldKind::kQuaternion:
      return "4, x y z w";
    case FieldKind::kEnum:
      return valueNames(field, " | ");
  }
  return "?";
}

/// A markdown table cell: `|` would end it.
std::string cell(std::string_view text) {
  std::string out;
  for (const char c : text) {
    out += c == '|' ? std::string("\\|") : std::string(1, c);
  }
  return out;
}

/// 100, 1e4, 1e6: a power of ten from 1e4 up as the exponent alone.
std::string limitText(double limit) {
  const int exponent = static_cast<int>(std::lround(std::log10(limit)));
  if (exponent >= 4 && limit == std::pow(10.0, exponent)) {
    return "1e" + std::to_string(exponent);
  }
  std::ostringstream text;
  text << limit;
  return text.str();
}

std::string constraintText(Constraint constraint, std::string_view unit) {
  const std::string limit = ", entries <= " + limitText(gainLimit(unit));
  switch (constraint) {
    case Constraint::kNone:
      return std::isinf(valueLimit(unit)) ? "" : "entries <= " + limitText(valueLimit(unit));
    case Constraint::kNonNegative:
      return ">= 0" + limit;
    case Constraint::kSymmetricPsd:
      return "symmetric PSD" + limit;
    case Constraint::kUnitQuaternion:
      return "unit norm";
    case Constraint::kSelection:
      return "entries 0 or 1";
  }
  return "?";
}

std::string msgType(const FieldInfo& field) {
  switch (field.kind) {
    case FieldKind::kVector3:
      return "float64[3]";
    case FieldKind::kVector6:
      return "float64[6]";
    case FieldKind::kJointVector:
      return "float64[]";
    case FieldKind::kBlock3:
      return "float64[9]";
    case FieldKind::kQuaternion:
      return "float64[4]";
    case FieldKind::kEnum:
      return "uint8";
  }
  return "?";
}

/// rosidl's DDS IDL spelling of the .msg type (the wire is the same for octet and uint8).
std::string idlMember(const FieldInfo& field) {
  const std::string name(field.name);
  switch (field.kind) {
    case FieldKind::kVector3:
      return "double " + name + "[3]";
    case FieldKind::kVector6:
      return "double " + name + "[6]";
    case FieldKind::kJointVector:
      return "sequence<double> " + name;
    case FieldKind::kBlock3:
      return "double " + name + "[9]";
    case FieldKind::kQuaternion:
      return "double " + name + "[4]";
    case FieldKind::kEnum:
      return "octet " + name;
  }
  return "?";
}

std::string_view messageName(CommandKind kind) {
  return kind == CommandKind::kCartesian ? "CartesianCommand" : "JointCommand";
}

/// The groups a kind's table uses, in bit order.
std::vector<GroupInfo> groupsOf(CommandKind kind) {
  std::vector<GroupInfo> used;
  for (const GroupInfo& group : groups()) {
    for (const FieldInfo& field : fields(kind)) {
      if (field.group == group.field) {
        used.push_back(group);
        break;
      }
    }
  }
  return used;
}

nlohmann::json rowsOf(CommandKind kind) {
  nlohmann::json rows = nlohmann::json::array();
  for (const FieldInfo& field : fields(kind)) {
    nlohmann::json row{{"name", field.name},
                       {"group", groupName(field.group)},
                       {"kind", toString(field.kind)},
                       {"unit", field.unit},
                       {"constraint", toString(field.constraint)},
                       {"role", toString(field.role)},
                       {"description", field.description}};
    if (field.constraint == Constraint::kNonNegative ||
        field.constraint == Constraint::kSymmetricPsd) {
      row["gain_limit"] = gainLimit(field.unit);
    }
    if (field.constraint == Constraint::kNone && !std::isinf(valueLimit(field.unit))) {
      row["value_limit"] = valueLimit(field.unit);
    }
    if (!field.values.empty()) {
      row["values"] = nlohmann::json::array();
      for (const EnumValue& value : field.values) {
        row["values"].push_back(value.name);
      }
    }
    rows.push_back(row);
  }
  return rows;
}

}  // namespace

std::string markdownTable(CommandKind kind) {
  std::ostringstream out;
  out << "| field | group | type | unit | constraint | description |\n"
      << "|---|---|---|---|---|---|\n";
  for (const FieldInfo& field : fields(kind)) {
    out << "| `" << field.name << "` | " << groupName(field.group) << " | " << cell(typeText(field))
        << " | " << cell(field.unit) << " | " << constraintText(field.constraint, field.unit)
        << " | " << cell(field.description) << " |\n";
  }
  return out.str();
}

std::string markdownDocument() {
  std::ostringstream out;
  out << "# Command schema\n\n"
      << "<!-- Generated by `comply schema --format markdown` from "
         "include/comply/schema/table.hpp; do not edit. -->\n\n"
      << "The same field names are used in C++ (`include/comply/core/commands.hpp`), in the "
         "plugin's C\nstructs (`include/comply/plugin/abi.h`), in JSON and YAML, and in the ROS 2 "
         "messages\n(`msg/CartesianCommand.msg`, `msg/JointCommand.msg`). Every command also "
         "carries `stamp` [s]\n(newer than the last accepted command's: stamps increase strictly) "
         "and a field mask\n`fields`: a sender sets only the groups it updates, the rest stays "
         "in force.\n\n"
      << "## Field groups\n\n| group | bit | meaning |\n|---|---|---|\n";
  for (const GroupInfo& group : groups()) {
    out << "| `" << group.name << "` | " << static_cast<std::uint32_t>(group.field) << " | "
        << cell(group.description) << " |\n";
  }
  out << "\n## Cartesian command\n\n"
      << markdownTable(CommandKind::kCartesian)
      << "\nPoses, twists and wrenches are in the base frame; gain blocks in the task frame.\n"
      << "\n## Joint command\n\n"
      << markdownTable(CommandKind::kJoint) << "\n## JSON and YAML\n\n"
      << "Keys are the field names, plus `stamp` and `fields` (a list of group names; without "
         "it, the\ngroups of the keys present). Quaternions are `[x, y, z, w]`; a 3x3 block is 9 "
         "numbers\nrow-major or 3 rows of 3. YAML files (the `initial:` block of a controller "
         "file, task-file\nwaypoints) also take shorthand: a block as 1 number (isotropic) or 3 "
         "(diagonal), a vector\nas 1 number for every entry.\n";
  return out.str();
}

std::string jsonDescription(CommandKind kind) {
  return rowsOf(kind).dump(2) + "\n";
}

std::string jsonDescription() {
  const nlohmann::json both{{"cartesian", rowsOf(CommandKind::kCartesian)},
                            {"joint", rowsOf(CommandKind::kJoint)}};
  return both.dump(2) + "\n";
}

std::string rosMessage(CommandKind kind) {
  std::ostringstream out;
  out << "# comply_msgs/" << messageName(kind) << ": generated by `comply schema --format msg "
      << "--kind " << toString(kind) << "`\n# from include/comply/schema/table.hpp; do not edit.\n"
      << "\nstd_msgs/Header header\n"
      << "uint32 fields  # FIELD_* groups this message sets; the others stay in force\n";
  for (const GroupInfo& group : groupsOf(kind)) {
    out << "uint32 FIELD_" << upperCase(group.name) << "="
        << static_cast<std::uint32_t>(group.field) << "\n";
  }
  for (const FieldInfo& field : fields(kind)) {
    for (const EnumValue& value : field.values) {
      out << "uint8 " << upperCase(field.name) << "_" << upperCase(value.name) << "="
          << value.number << "\n";
    }
  }
  out << "\n";
  for (const FieldInfo& field : fields(kind)) {
    out << msgType(field) << " " << field.name << "  # ";
    if (field.kind == FieldKind::kQuaternion) {
      out << "x y z w; ";
    } else if (field.kind == FieldKind::kBlock3) {
      out << "3x3 row-major; ";
    } else if (field.kind == FieldKind::kEnum) {
      out << upperCase(field.name) << "_*; ";
    }
    out << "[" << (field.unit.empty() ? "-" : field.unit) << "] " << field.description << "\n";
  }
  return out.str();
}

std::string ddsIdl(CommandKind kind) {
  const std::string name(messageName(kind));
  std::ostringstream out;
  out << "// comply_msgs/" << name << " as ROS 2 (rosidl) puts it on the wire: generated by\n"
      << "// `comply schema --format idl --kind " << toString(kind)
      << "` from include/comply/schema/table.hpp; do not edit.\n\n"
      << "#include \"std_msgs/msg/Header.idl\"\n\n"
      << "module comply_msgs {\nmodule msg {\nmodule dds_ {\n\nmodule " << name << "_Constants {\n";
  for (const GroupInfo& group : groupsOf(kind)) {
    out << "const unsigned long FIELD_" << upperCase(group.name) << " = "
        << static_cast<std::uint32_t>(group.field) << ";\n";
  }
  for (const FieldInfo& field : fields(kind)) {
    for (const EnumValue& value : field.values) {
      out << "const octet " << upperCase(field.name) << "_" << upperCase(value.name) << " = "
          << value.number << ";\n";
    }
  }
  out << "};\n\nstruct " << name << "_ {\n"
      << "  std_msgs::msg::dds_::Header_ header;\n  unsigned long fields;\n";
  for (const FieldInfo& field : fields(kind)) {
    out << "  " << idlMember(field) << ";\n";
  }
  out << "};\n\n};  // module dds_\n};  // module msg\n};  // module comply_msgs\n";
  return out.str();
}

}  // namespace comply::schema
