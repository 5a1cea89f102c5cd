#pragma once
// Every field of a table message (message_tables.hpp) at once, for tests that must cover each
// field a table has, today's and tomorrow's: DistinctValues sets them all, flatten() reads them all
// back in table order.

#include <cstddef>
#include <cstdint>
#include <string>
#include <type_traits>
#include <vector>

#include "comply/transport/messages.hpp"

namespace comply::transport::testing {

/// Sets every field to a value no other field has (enums excepted: they alternate between their
/// first two values, which every enumeration has). Sequences get 1 to 3 elements and strings
/// different lengths, so encoders meet varied sizes and alignments.
struct DistinctValues {
  int next = 1;

  template <typename T>
  void set(T& value) {
    if constexpr (std::is_same_v<T, std::string>) {
      value = std::string(static_cast<std::size_t>(next % 5), 'x') + std::to_string(next);
      ++next;
    } else if constexpr (std::is_same_v<T, Stamp>) {
      value = {next, static_cast<std::uint32_t>(next + 1)};
      next += 2;
    } else if constexpr (std::is_same_v<T, Header>) {
      set(value.stamp);
      set(value.frame_id);
    } else if constexpr (std::is_same_v<T, bool>) {
      value = true;  // every flag's default is false
    } else if constexpr (std::is_enum_v<T>) {
      value = static_cast<T>(next++ % 2);
    } else if constexpr (std::is_arithmetic_v<T>) {
      value = static_cast<T>(next++);
    } else if constexpr (TableMessage<T>) {
      T::visit(value, [this](FieldName, auto& field) { set(field); });
    } else {
      if constexpr (requires { value.resize(1); }) {
        value.resize(static_cast<std::size_t>(1 + next % 3));
      }
      for (auto& element : value) {
        set(element);
      }
    }
  }
};

/// A message's values as numbers and texts in table order (sequence sizes included), so two
/// messages compare field for field.
struct Flat {
  std::vector<double> numbers;
  std::vector<std::string> texts;
};

inline void flatten(const std::string& value, Flat& flat) {
  flat.texts.push_back(value);
}
template <typename T>
requires std::is_arithmetic_v<T> || std::is_enum_v<T>
void flatten(T value, Flat& flat) {
  flat.numbers.push_back(static_cast<double>(value));
}
template <typename TimeLike>
requires requires(TimeLike time) {
  time.nanosec;
}
void flatten(const TimeLike& time, Flat& flat) {
  flat.numbers.push_back(time.sec);
  flat.numbers.push_back(time.nanosec);
}
template <typename HeaderLike>
requires requires(HeaderLike header) {
  header.frame_id;
}
void flatten(const HeaderLike& header, Flat& flat) {
  flatten(header.stamp, flat);
  flatten(header.frame_id, flat);
}
template <TableMessage Message>
void flatten(const Message& message, Flat& flat);
template <typename Sequence>
requires requires(Sequence sequence) {
  sequence.size();
  sequence.begin();
}
void flatten(const Sequence& sequence, Flat& flat) {
  flat.numbers.push_back(static_cast<double>(sequence.size()));
  for (const auto& element : sequence) {
    flatten(element, flat);
  }
}
template <TableMessage Message>
void flatten(const Message& message, Flat& flat) {
  Message::visit(message, [&flat](FieldName, const auto& field) { flatten(field, flat); });
}

template <typename Message>
Flat flat(const Message& message) {
  Flat values;
  flatten(message, values);
  return values;
}

}  // namespace comply::transport::testing
