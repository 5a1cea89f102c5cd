#pragma once
// The ROS 2 interface (.msg) and DDS IDL of the host's messages, written from their tables
// (message_tables.hpp): `comply schema --format msg|idl --message NAME` prints them, and
// msg/*.msg and src/transport/idl/comply_msgs/msg/*.idl are their committed output
// (`make generated`; tests/transport compares).

#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "comply/transport/messages.hpp"

namespace comply::transport {

/// One field as the interface files spell it.
struct FieldText {
  std::string name;
  std::string msg_type;    ///< "float64[3]", "builtin_interfaces/Time", ...
  std::string idl_type;    ///< "double", "sequence<double>", ... (array bounds go to the name)
  std::string idl_suffix;  ///< "[3]" for a fixed array
  std::string doc;
  std::string idl_include;  ///< the IDL file the type needs ("" for a primitive)
};

/// A constant of the message (uint8 NAME=value).
struct ConstantText {
  std::string name;
  int value = 0;
  std::string doc;  ///< "" for none
};

struct MessageText {
  std::string name;   ///< "ControllerState"
  std::string about;  ///< the leading comment, lines without "# "
  std::vector<ConstantText> constants;
  std::vector<FieldText> fields;
};

namespace text {

template <typename T>
struct Spelling;  // msg type, IDL type, IDL suffix, IDL include
template <>
struct Spelling<bool> {
  static FieldText of() { return {{}, "bool", "boolean", "", {}, ""}; }
};
template <>
struct Spelling<double> {
  static FieldText of() { return {{}, "float64", "double", "", {}, ""}; }
};
template <>
struct Spelling<std::uint8_t> {
  static FieldText of() { return {{}, "uint8", "octet", "", {}, ""}; }
};
template <>
struct Spelling<std::uint32_t> {
  static FieldText of() { return {{}, "uint32", "unsigned long", "", {}, ""}; }
};
template <>
struct Spelling<std::uint64_t> {
  static FieldText of() { return {{}, "uint64", "unsigned long long", "", {}, ""}; }
};
template <>
struct Spelling<std::string> {
  static FieldText of() { return {{}, "string", "string", "", {}, ""}; }
};
template <>
struct Spelling<Stamp> {
  static FieldText of() {
    return {{}, "builtin_interfaces/Time",        "builtin_interfaces::msg::dds_::Time_", "",
            {}, "builtin_interfaces/msg/Time.idl"};
  }
};
template <>
struct Spelling<Header> {
  static FieldText of() {
    return {{}, "std_msgs/Header",        "std_msgs::msg::dds_::Header_", "",
            {}, "std_msgs/msg/Header.idl"};
  }
};
template <>
struct Spelling<CommandOutcomeMessage> {
  static FieldText of() {
    return {{},
            "CommandOutcome",
            "comply_msgs::msg::dds_::CommandOutcome_",
            "",
            {},
            "comply_msgs/msg/CommandOutcome.idl"};
  }
};
template <typename T>
requires std::is_enum_v<T>
struct Spelling<T> : Spelling<std::uint8_t> {
};
template <typename T, std::size_t N>
struct Spelling<std::array<T, N>> {
  static FieldText of() {
    FieldText element = Spelling<T>::of();
    element.msg_type += "[" + std::to_string(N) + "]";
    element.idl_suffix = "[" + std::to_string(N) + "]";
    return element;
  }
};
template <typename T>
struct Spelling<std::vector<T>> {
  static FieldText of() {
    FieldText element = Spelling<T>::of();
    element.msg_type += "[]";
    element.idl_type = "sequence<" + element.idl_type + ">";
    return element;
  }
};

}  // namespace text

/// The fields of a table's message, in wire order.
template <typename Message>
std::vector<FieldText> fieldTexts() {
  std::vector<FieldText> fields;
  const Message empty{};
  Message::visit(empty, [&](FieldName name, const auto& value) {
    FieldText field = text::Spelling<std::remove_cvref_t<decltype(value)>>::of();
    field.name = name.wire;
    field.doc = name.doc;
    fields.push_back(std::move(field));
  });
  return fields;
}

/// msg/NAME.msg.
std::string rosMessageText(const MessageText& message);
/// src/transport/idl/comply_msgs/msg/NAME.idl: as ROS 2's rosidl puts it on the wire.
std::string ddsIdlText(const MessageText& message);

/// ControllerState, CommandOutcome and Diagnostics, from their tables; throws std::out_of_range
/// for another name.
MessageText hostMessageText(std::string_view name);
/// Their names.
std::vector<std::string_view> hostMessageNames();

}  // namespace comply::transport
