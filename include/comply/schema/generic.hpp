#pragma once
// The generic machinery behind schema.hpp: every operation is a template over a schema type made
// by COMPLY_SCHEMA_DEFINE from a command struct, a bus struct and an X-macro table, so a new table
// (or a table with one more line) gets every operation without per-field code. Include only from
// the .cpp files that instantiate a schema (and tests): it is template-heavy.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <tuple>
#include <type_traits>
#include <utility>

#include "comply/core/gains.hpp"
#include "comply/schema/schema.hpp"

namespace comply::schema::generic {

/// One table row with its kind, constraint and role as types, so that each operation compiles only
/// the code for that kind.
template <FieldKind K, Constraint C, Role R, typename Command, typename Value, typename Bus,
          typename BusValue>
struct Field {
  static constexpr FieldKind kKind = K;
  static constexpr Constraint kConstraint = C;
  static constexpr Role kRole = R;
  using CommandType = Command;
  using ValueType = Value;
  std::string_view name;
  std::string_view unit;
  CommandField group;
  Value Command::*member;
  BusValue Bus::*bus_member;
};

template <FieldKind K, Constraint C, Role R, typename Command, typename Value, typename Bus,
          typename BusValue>
constexpr auto field(std::string_view name, std::string_view unit, CommandField group,
                     Value Command::*member, BusValue Bus::*bus_member) {
  return std::make_tuple(
      Field<K, C, R, Command, Value, Bus, BusValue>{name, unit, group, member, bus_member});
}

// Each row becomes a one-element tuple followed by a comma; the table ends in std::tuple<>{}.
#define COMPLY_SCHEMA_GENERIC_FIELD(name, group, kind, type, unit, constraint, role, init, doc) \
  ::comply::schema::generic::field<::comply::schema::FieldKind::kind,                           \
                                   ::comply::schema::Constraint::constraint,                    \
                                   ::comply::schema::Role::role>(                               \
      #name, unit, ::comply::CommandField::group, &SchemaCommand::name, &SchemaBus::name),

/// Defines the schema type `Name` of `CommandType` / `BusType` from the X-macro `TABLE`.
#define COMPLY_SCHEMA_DEFINE(Name, CommandType, BusType, TABLE)                 \
  struct Name {                                                                 \
    using Command = CommandType;                                                \
    using Bus = BusType;                                                        \
    static constexpr auto fields() {                                            \
      using SchemaCommand = CommandType;                                        \
      using SchemaBus = BusType;                                                \
      return std::tuple_cat(TABLE(COMPLY_SCHEMA_GENERIC_FIELD) std::tuple<>{}); \
    }                                                                           \
  }

template <typename Schema>
inline constexpr std::size_t kFieldCount = std::tuple_size_v<decltype(Schema::fields())>;

/// Calls f(field, index) for each row in table order while f returns true; false if one did not.
template <typename Schema, typename F>
constexpr bool visitFields(F&& f) {
  constexpr auto table = Schema::fields();
  static_assert(std::tuple_size_v<decltype(table)> <= 64, "FieldSet has 64 bits");
  return [&]<std::size_t... I>(std::index_sequence<I...>) {
    return (f(std::get<I>(table), I) && ...);
  }
  (std::make_index_sequence<std::tuple_size_v<decltype(table)>>{});
}

template <typename Schema, typename F>
constexpr void forEachField(F&& f) {
  visitFields<Schema>([&](const auto& field, std::size_t index) {
    f(field, index);
    return true;
  });
}

template <typename F>
using FieldOf = std::remove_cvref_t<F>;

/// Entries of a fixed-size kind (also the JSON length outside shorthand); joint vectors: -1.
template <FieldKind K>
constexpr int fixedSize() {
  switch (K) {
    case FieldKind::kVector3:
      return 3;
    case FieldKind::kVector6:
      return 6;
    case FieldKind::kBlock3:
      return 9;
    case FieldKind::kQuaternion:
      return 4;
    case FieldKind::kEnum:
      return 1;
    case FieldKind::kJointVector:
      break;
  }
  return -1;
}

/// A default command with its joint vectors sized `dof` and zero (what Command::zero() does).
template <typename Schema>
typename Schema::Command zeroCommand(int dof) {
  typename Schema::Command command;
  forEachField<Schema>([&](const auto& f, std::size_t) {
    if constexpr (FieldOf<decltype(f)>::kKind == FieldKind::kJointVector) {
      (command.*f.member).setZero(dof);
    }
  });
  return command;
}

// --- one value to and from its bus array; the bus is zero-initialised by the caller ---

template <FieldKind K, typename Value, typename BusValue>
void writeBus(const Value& value, BusValue& out, int dof) noexcept {
  if constexpr (K == FieldKind::kQuaternion) {
    toXyzw(value, out);
  } else if constexpr (K == FieldKind::kBlock3) {
    toRowMajor(value, out);
  } else if constexpr (K == FieldKind::kEnum) {
    out = static_cast<std::int32_t>(value);
  } else if constexpr (K == FieldKind::kJointVector) {
    for (int i = 0; i < dof; ++i) {
      out[i] = i < value.size() ? value[i] : 0.0;
    }
  } else {
    static_assert(std::extent_v<BusValue> == fixedSize<K>(), "bus array of the wrong length");
    for (int i = 0; i < fixedSize<K>(); ++i) {
      out[i] = value[i];
    }
  }
}

template <FieldKind K, typename Value, typename BusValue>
void readBus(const BusValue& in, Value& value, int dof) {
  if constexpr (K == FieldKind::kQuaternion) {
    value = fromXyzw(in);
  } else if constexpr (K == FieldKind::kBlock3) {
    value = fromRowMajor(in);
  } else if constexpr (K == FieldKind::kEnum) {
    value = static_cast<Value>(in);
  } else if constexpr (K == FieldKind::kJointVector) {
    value.resize(dof);
    for (int i = 0; i < dof; ++i) {
      value[i] = in[i];
    }
  } else {
    for (int i = 0; i < fixedSize<K>(); ++i) {
      value[i] = in[i];
    }
  }
}

template <typename Schema>
typename Schema::Bus toBus(const typename Schema::Command& command, int dof) {
  typename Schema::Bus bus{};
  bus.stamp_s = command.stamp_s;
  bus.fields = static_cast<std::uint32_t>(command.fields);
  bus.dof = dof;
  forEachField<Schema>([&](const auto& f, std::size_t) {
    writeBus<FieldOf<decltype(f)>::kKind>(command.*f.member, bus.*f.bus_member, dof);
  });
  return bus;
}

template <typename Schema>
typename Schema::Command fromBus(const typename Schema::Bus& bus) {
  typename Schema::Command command;
  command.stamp_s = bus.stamp_s;
  command.fields = static_cast<CommandField>(bus.fields);
  forEachField<Schema>([&](const auto& f, std::size_t) {
    readBus<FieldOf<decltype(f)>::kKind>(bus.*f.bus_member, command.*f.member, bus.dof);
  });
  return command;
}

// --- merging ---

/// Bus or command: copies the groups set in `incoming.fields`, and the stamp. Plain assignment of
/// fixed arrays and inline-storage vectors: no allocation.
template <typename Schema, bool kBus, typename T>
void mergeInto(T& into, const T& incoming) noexcept {
  const auto set = static_cast<CommandField>(incoming.fields);
  forEachField<Schema>([&](const auto& f, std::size_t) {
    if (!has(set, f.group)) {
      return;
    }
    if constexpr (kBus) {
      auto& target = into.*f.bus_member;
      const auto& source = incoming.*f.bus_member;
      if constexpr (std::is_array_v<std::remove_reference_t<decltype(target)>>) {
        std::copy(std::begin(source), std::end(source), std::begin(target));
      } else {
        target = source;
      }
    } else {
      into.*f.member = incoming.*f.member;
    }
  });
  into.stamp_s = incoming.stamp_s;
  into.fields = static_cast<decltype(into.fields)>(static_cast<std::uint32_t>(into.fields) |
                                                   static_cast<std::uint32_t>(incoming.fields));
}

template <typename Schema>
void assign(typename Schema::Command& into, const typename Schema::Command& from, FieldSet keys) {
  forEachField<Schema>([&](const auto& f, std::size_t index) {
    if ((keys >> index & 1U) != 0) {
      into.*f.member = from.*f.member;
    }
  });
}

// --- reference rules ---

/// Zero: a whole bus array, a joint vector sized `dof` (or kept when dof < 0), any other value.
template <FieldKind K, typename Target>
void zeroValue(Target& target, int dof) noexcept {
  if constexpr (std::is_array_v<Target>) {
    std::fill(std::begin(target), std::end(target), 0.0);
  } else if constexpr (K == FieldKind::kJointVector) {
    dof < 0 ? target.setZero() : target.setZero(dof);
  } else {
    target.setZero();
  }
}

template <bool kBus, FieldKind K, typename Target, typename Source>
void seedValue(Target& target, const Source& source, int dof) noexcept {
  if constexpr (kBus) {
    writeBus<K>(source, target, dof);
  } else {
    target = source;
  }
}

/// Applies the roles to a bus (kBus) or a command: rates zero and, with `measured`, the seeded
/// fields from it. `dof`: entries of joint fields (< 0: keep a command's sizes).
template <typename Schema, bool kBus, typename T>
void applyRoles(T& target, const MeasuredPose* measured, int dof) noexcept {
  forEachField<Schema>([&](const auto& f, std::size_t) {
    using F = FieldOf<decltype(f)>;
    auto& value = [&]() -> auto& {
      if constexpr (kBus) {
        return target.*f.bus_member;
      } else {
        return target.*f.member;
      }
    }
    ();
    if constexpr (F::kRole == Role::kZeroOnStop) {
      zeroValue<F::kKind>(value, dof);
    } else if constexpr (F::kRole == Role::kSeedTcpPosition) {
      static_assert(F::kKind == FieldKind::kVector3, "a TCP position seeds a 3-vector");
      if (measured != nullptr) {
        seedValue<kBus, F::kKind>(value, measured->tcp_position, dof);
      }
    } else if constexpr (F::kRole == Role::kSeedTcpOrientation) {
      static_assert(F::kKind == FieldKind::kQuaternion, "a TCP orientation seeds a quaternion");
      if (measured != nullptr) {
        seedValue<kBus, F::kKind>(value, measured->tcp_orientation, dof);
      }
    } else if constexpr (F::kRole == Role::kSeedJointPosition) {
      static_assert(F::kKind == FieldKind::kJointVector, "joint positions seed a joint vector");
      if (measured != nullptr) {
        seedValue<kBus, F::kKind>(value, measured->position, dof);
      }
    }
  });
}

}  // namespace comply::schema::generic
