#pragma once
// Bit-for-bit comparison of commands: a rejected command must leave the merged one untouched, and
// "approximately equal" would hide a field that was half written before the rejection.

#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <cstring>
#include <type_traits>

#include "comply/core/commands.hpp"

namespace comply::pipeline::test {

inline bool sameBits(double a, double b) {
  return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b);
}

template <typename Derived>
bool sameBits(const Eigen::PlainObjectBase<Derived>& a, const Eigen::PlainObjectBase<Derived>& b) {
  return a.rows() == b.rows() && a.cols() == b.cols() &&
         std::memcmp(a.data(), b.data(), sizeof(double) * static_cast<std::size_t>(a.size())) == 0;
}

inline bool sameBits(const Eigen::Quaterniond& a, const Eigen::Quaterniond& b) {
  return sameBits(a.coeffs(), b.coeffs());
}

template <typename Enum>
requires std::is_enum_v<Enum>
bool sameBits(Enum a, Enum b) {
  return a == b;
}

#define COMPLY_EXPECT_SAME_FIELD(a, b, field) \
  EXPECT_TRUE(::comply::pipeline::test::sameBits((a).field, (b).field)) << #field " changed"

#define COMPLY_EXPECT_SAME_ROW(name, group, kind, type, unit, constraint, role, init, doc) \
  COMPLY_EXPECT_SAME_FIELD(actual, expected, name);

/// Every field of the command table, and the stamp and mask.
inline void expectSameBits(const JointCommand& actual, const JointCommand& expected) {
  COMPLY_EXPECT_SAME_FIELD(actual, expected, stamp_s);
  EXPECT_EQ(actual.fields, expected.fields);
  COMPLY_JOINT_COMMAND_FIELDS(COMPLY_EXPECT_SAME_ROW)
}

inline void expectSameBits(const CartesianCommand& actual, const CartesianCommand& expected) {
  COMPLY_EXPECT_SAME_FIELD(actual, expected, stamp_s);
  EXPECT_EQ(actual.fields, expected.fields);
  COMPLY_CARTESIAN_COMMAND_FIELDS(COMPLY_EXPECT_SAME_ROW)
}

#undef COMPLY_EXPECT_SAME_ROW
#undef COMPLY_EXPECT_SAME_FIELD

inline JointVector joints(std::initializer_list<double> values) {
  JointVector v(static_cast<Eigen::Index>(values.size()));
  Eigen::Index i = 0;
  for (const double value : values) {
    v[i++] = value;
  }
  return v;
}

}  // namespace comply::pipeline::test
