#pragma once
// An enum's names as one table, read both ways: the name of a value (messages, files, tables)
// and the value of a name (controller files, command lines). A table lists every enumerator once,
// in the order of their values, which listsValuesInOrder() checks beside the table: a value
// skipped or listed twice fails to compile.

#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace comply {

template <typename Enum>
struct EnumName {
  Enum value;
  std::string_view name;
};

template <typename Enum, std::size_t N>
using EnumNames = std::array<EnumName<Enum>, N>;

/// Whether `names` lists the values first, first + 1, first + 2, ... in that order.
template <typename Enum, std::size_t N>
constexpr bool listsValuesInOrder(const EnumNames<Enum, N>& names, std::size_t first = 0) {
  for (std::size_t i = 0; i < N; ++i) {
    if (static_cast<std::size_t>(names[i].value) != first + i) {
      return false;
    }
  }
  return true;
}

/// The name of `value`; `unknown` for a value the table lacks (a cast from a bad integer).
template <typename Enum, std::size_t N>
constexpr std::string_view nameIn(const EnumNames<Enum, N>& names, Enum value,
                                  std::string_view unknown = "unknown") noexcept {
  for (const EnumName<Enum>& entry : names) {
    if (entry.value == value) {
      return entry.name;
    }
  }
  return unknown;
}

/// The value called `name`; none for a name the table lacks.
template <typename Enum, std::size_t N>
constexpr std::optional<Enum> valueIn(const EnumNames<Enum, N>& names,
                                      std::string_view name) noexcept {
  for (const EnumName<Enum>& entry : names) {
    if (entry.name == name) {
      return entry.value;
    }
  }
  return std::nullopt;
}

/// Every name, in the table's order (a command line's choices).
template <typename Enum, std::size_t N>
std::vector<std::string> namesIn(const EnumNames<Enum, N>& names) {
  std::vector<std::string> list;
  list.reserve(N);
  for (const EnumName<Enum>& entry : names) {
    list.emplace_back(entry.name);
  }
  return list;
}

}  // namespace comply
