#pragma once
// CDR of a message table's fields, by their C++ type (message_tables.hpp): what one row's Type
// puts on the wire and reads back. A message of the tables is its fields in order (visit()).

#include <array>
#include <string>
#include <type_traits>
#include <vector>

#include "cdr_reader.hpp"
#include "cdr_writer.hpp"
#include "comply/transport/messages.hpp"

namespace comply::transport::cdr {

// ---- writing ----

template <typename T>
void putField(Writer& w, const T& value);

template <typename T>
void putFields(Writer& w, const T& message) {
  T::visit(message, [&](FieldName, const auto& value) { putField(w, value); });
}

template <typename T>
void putField(Writer& w, const T& value) {
  if constexpr (std::is_same_v<T, bool>) {
    w.putBool(value);
  } else if constexpr (std::is_enum_v<T>) {
    w.put(static_cast<std::uint8_t>(value));
  } else if constexpr (std::is_arithmetic_v<T>) {
    w.put(value);
  } else if constexpr (std::is_same_v<T, std::string>) {
    w.putString(value);
  } else if constexpr (std::is_same_v<T, Stamp>) {
    w.put(value.sec);
    w.put(value.nanosec);
  } else if constexpr (std::is_same_v<T, Header>) {
    putField(w, value.stamp);
    w.putString(value.frame_id);
  } else if constexpr (TableMessage<T>) {
    putFields(w, value);
  } else if constexpr (requires { std::tuple_size<T>::value; }) {  // std::array: no count
    w.putArray(value.data(), value.size());
  } else {  // std::vector
    using Element = typename T::value_type;
    if constexpr (std::is_arithmetic_v<Element> && !std::is_same_v<Element, bool>) {
      w.putSequence(value.data(), value.size());
    } else {
      w.putCount(value.size());
      for (const Element& element : value) {
        putField(w, element);
      }
    }
  }
}

// ---- reading ----

/// The fewest bytes a value of T takes on the wire (alignment aside): a bound on a sequence's
/// count before reading it, so that a forged count cannot make the reader allocate.
template <typename T>
std::size_t minimumBytes() {
  if constexpr (std::is_enum_v<T> || std::is_same_v<T, bool>) {
    return 1;
  } else if constexpr (std::is_arithmetic_v<T>) {
    return sizeof(T);
  } else if constexpr (std::is_same_v<T, std::string>) {
    return 5;  // length and NUL
  } else if constexpr (std::is_same_v<T, Stamp>) {
    return 8;
  } else if constexpr (std::is_same_v<T, Header>) {
    return 8 + 5;
  } else if constexpr (TableMessage<T>) {
    std::size_t bytes = 0;
    const T empty{};
    T::visit(empty, [&](FieldName, const auto& value) {
      bytes += minimumBytes<std::remove_cvref_t<decltype(value)>>();
    });
    return bytes;
  } else if constexpr (requires { std::tuple_size<T>::value; }) {
    return std::tuple_size<T>::value * sizeof(typename T::value_type);
  } else {
    return 4;  // a sequence's count
  }
}

template <typename T>
void getField(Reader& r, T& value);

template <typename T>
void getFields(Reader& r, T& message) {
  T::visit(message, [&](FieldName, auto& value) { getField(r, value); });
}

template <typename T>
void getField(Reader& r, T& value) {
  if constexpr (std::is_same_v<T, bool>) {
    value = r.getBool();
  } else if constexpr (std::is_enum_v<T>) {
    value = static_cast<T>(r.get<std::uint8_t>());
  } else if constexpr (std::is_arithmetic_v<T>) {
    value = r.get<T>();
  } else if constexpr (std::is_same_v<T, std::string>) {
    value = r.getString();
  } else if constexpr (std::is_same_v<T, Stamp>) {
    value.sec = r.get<std::int32_t>();
    value.nanosec = r.get<std::uint32_t>();
  } else if constexpr (std::is_same_v<T, Header>) {
    getField(r, value.stamp);
    value.frame_id = r.getString();
  } else if constexpr (TableMessage<T>) {
    getFields(r, value);
  } else if constexpr (requires { std::tuple_size<T>::value; }) {
    r.getArray(value.data(), value.size());
  } else {
    using Element = typename T::value_type;
    value.resize(r.getCount(minimumBytes<Element>()));
    if constexpr (std::is_arithmetic_v<Element> && !std::is_same_v<Element, bool>) {
      r.getArray(value.data(), value.size());
    } else {
      for (Element& element : value) {
        getField(r, element);
      }
    }
  }
}

}  // namespace comply::transport::cdr
