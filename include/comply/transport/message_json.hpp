#pragma once
// A table's message as JSON (`comply echo --json`, `comply send`'s outcomes): each field under its
// wire name (message_tables.hpp); enums by name, stamps as {sec, nanosec}, a GUID as hex.

#include <nlohmann/json.hpp>
#include <string>
#include <type_traits>

#include "comply/transport/messages.hpp"

namespace comply::transport {

template <TableMessage Message>
nlohmann::json messageJson(const Message& message);

/// A sequence of a table's messages (Diagnostics.outcomes).
template <typename T>
concept TableMessageList = requires {
  requires TableMessage<typename T::value_type>;
};

template <typename T>
nlohmann::json fieldJson(const T& value) {
  if constexpr (std::is_enum_v<T>) {
    return std::string(toString(value));
  } else if constexpr (std::is_same_v<T, Stamp>) {
    return {{"sec", value.sec}, {"nanosec", value.nanosec}};
  } else if constexpr (std::is_same_v<T, Header>) {
    return {{"stamp", fieldJson(value.stamp)}, {"frame_id", value.frame_id}};
  } else if constexpr (std::is_same_v<T, Gid>) {
    return toHex(value);
  } else if constexpr (TableMessage<T>) {
    return messageJson(value);
  } else if constexpr (TableMessageList<T>) {
    nlohmann::json list = nlohmann::json::array();
    for (const auto& element : value) {
      list.push_back(messageJson(element));
    }
    return list;
  } else {
    return value;
  }
}

template <TableMessage Message>
nlohmann::json messageJson(const Message& message) {
  nlohmann::json object = nlohmann::json::object();
  Message::visit(message, [&](FieldName name, const auto& value) {
    object[std::string(name.wire)] = fieldJson(value);
  });
  return object;
}

}  // namespace comply::transport
