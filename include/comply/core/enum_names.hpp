#pragma once
// An enum's names as one table, read both ways: the name of a value (messages, files, tables)
// and the value of a name (controller files, command lines). A table lists the enumerators in the
// order of their values, without a gap, each name once; a table that does not fails to compile.
// A table that stops short of the enum's last enumerator does compile (C++ cannot count an enum's
// enumerators): its value then has the name nameIn() gives for an unknown value.

#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace comply {

template <typename Enum>
struct EnumName {
  Enum value{};
  std::string_view name;
};

template <typename Enum, std::size_t N>
class EnumNames {
 public:
  /// Implicit, so that a table reads as its rows: EnumNames<E, 2> kNames{{{E::kA, "a"}, ...}}.
  consteval EnumNames(const EnumName<Enum> (&entries)[N]) {  // NOLINT(google-explicit-constructor)
    for (std::size_t i = 0; i < N; ++i) {
      if (i > 0 && static_cast<long long>(entries[i].value) !=
                       static_cast<long long>(entries[i - 1].value) + 1) {
        // Reached only while compiling: a table out of order or with a gap is an error there.
        throw "EnumNames: list the enumerators in the order of their values, without a gap";
      }
      for (std::size_t j = 0; j < i; ++j) {
        if (entries[j].name == entries[i].name) {
          throw "EnumNames: each name once";
        }
      }
      entries_[i] = entries[i];
    }
  }

  [[nodiscard]] constexpr auto begin() const noexcept { return entries_.begin(); }
  [[nodiscard]] constexpr auto end() const noexcept { return entries_.end(); }
  [[nodiscard]] static constexpr std::size_t size() noexcept { return N; }

 private:
  std::array<EnumName<Enum>, N> entries_{};
};

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
