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
#include <utility>
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

/// A type the interface files name as it is: its .msg type, its IDL type and the IDL file that
/// declares it ("" for a primitive).
inline FieldText named(std::string msg_type, std::string idl_type, std::string idl_include = "") {
  return {{}, std::move(msg_type), std::move(idl_type), "", {}, std::move(idl_include)};
}

template <typename T>
inline constexpr bool kIsStdArray = false;
template <typename T, std::size_t N>
inline constexpr bool kIsStdArray<std::array<T, N>> = true;
template <typename T>
inline constexpr bool kIsStdVector = false;
template <typename T>
inline constexpr bool kIsStdVector<std::vector<T>> = true;

/// How the interface files spell a member of C++ type T (its name and doc left empty). An enum is
/// its uint8 code on the wire.
template <typename T>
FieldText spelling() {
  if constexpr (std::is_same_v<T, bool>) {
    return named("bool", "boolean");
  } else if constexpr (std::is_same_v<T, double>) {
    return named("float64", "double");
  } else if constexpr (std::is_same_v<T, std::uint8_t> || std::is_enum_v<T>) {
    return named("uint8", "octet");
  } else if constexpr (std::is_same_v<T, std::uint32_t>) {
    return named("uint32", "unsigned long");
  } else if constexpr (std::is_same_v<T, std::uint64_t>) {
    return named("uint64", "unsigned long long");
  } else if constexpr (std::is_same_v<T, std::string>) {
    return named("string", "string");
  } else if constexpr (std::is_same_v<T, Stamp>) {
    return named("builtin_interfaces/Time", "builtin_interfaces::msg::dds_::Time_",
                 "builtin_interfaces/msg/Time.idl");
  } else if constexpr (std::is_same_v<T, Header>) {
    return named("std_msgs/Header", "std_msgs::msg::dds_::Header_", "std_msgs/msg/Header.idl");
  } else if constexpr (std::is_same_v<T, CommandOutcomeMessage>) {
    return named("CommandOutcome", "comply_msgs::msg::dds_::CommandOutcome_",
                 "comply_msgs/msg/CommandOutcome.idl");
  } else if constexpr (std::is_same_v<T, ChunkTimingMessage>) {
    return named("ChunkTiming", "comply_msgs::msg::dds_::ChunkTiming_",
                 "comply_msgs/msg/ChunkTiming.idl");
  } else if constexpr (kIsStdArray<T>) {
    FieldText element = spelling<typename T::value_type>();
    const std::string bound = "[" + std::to_string(std::tuple_size_v<T>) + "]";
    element.msg_type += bound;
    element.idl_suffix = bound;
    return element;
  } else if constexpr (kIsStdVector<T>) {
    FieldText element = spelling<typename T::value_type>();
    element.msg_type += "[]";
    element.idl_type = "sequence<" + element.idl_type + ">";
    return element;
  } else {
    static_assert(sizeof(T) == 0, "a message member of a type the interface files cannot spell");
  }
}

}  // namespace text

/// The fields of a table's message, in wire order.
template <typename Message>
std::vector<FieldText> fieldTexts() {
  std::vector<FieldText> fields;
  const Message empty{};
  Message::visit(empty, [&](FieldName name, const auto& value) {
    FieldText field = text::spelling<std::remove_cvref_t<decltype(value)>>();
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

/// ControllerState, CommandOutcome, ChunkTiming and Diagnostics, from their tables; throws
/// std::out_of_range for another name.
MessageText hostMessageText(std::string_view name);
/// Their names.
std::vector<std::string_view> hostMessageNames();

}  // namespace comply::transport
