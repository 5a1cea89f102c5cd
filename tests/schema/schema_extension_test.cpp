// Adding a field is one table line plus the bus member: a copy of the Cartesian table with one
// more field (a per-axis force limit, non-negative, sent with the wrench feedforward), a command
// struct generated from it and a bus with the extra member get JSON reading and writing,
// validation, merging and bus conversion from the generic machinery with no other code.

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "comply/core/input_error.hpp"
#include "comply/schema/generic.hpp"
#include "comply/schema/generic_check.hpp"
#include "comply/schema/generic_json.hpp"
#include "comply/schema/table.hpp"
#include "schema_support.hpp"

namespace comply::schema {
namespace {

#define TEST_EXTENDED_CARTESIAN_FIELDS(X)                                                 \
  COMPLY_CARTESIAN_COMMAND_FIELDS(X)                                                      \
  X(force_limit, kWrenchFeedforward, kVector3, Eigen::Vector3d, "N", kNonNegative, kNone, \
    Eigen::Vector3d::Constant(10.0), "largest contact force per axis")

struct ExtendedCommand {
  double stamp_s = 0.0;
  CommandField fields = CommandField::kAll;
  TEST_EXTENDED_CARTESIAN_FIELDS(COMPLY_SCHEMA_MEMBER)

  static ExtendedCommand zero(int dof);
};

/// The ABI struct with the new member, as plugin/abi.h would spell it.
struct ExtendedBus : comply_cartesian_command {
  double force_limit[3];
};

COMPLY_SCHEMA_DEFINE(ExtendedSchema, ExtendedCommand, ExtendedBus, TEST_EXTENDED_CARTESIAN_FIELDS);

ExtendedCommand ExtendedCommand::zero(int dof) {
  return generic::zeroCommand<ExtendedSchema>(dof);
}

constexpr std::size_t kForceLimitRow = 22;
using test::kDof;

static_assert(generic::kFieldCount<ExtendedSchema> == kForceLimitRow + 1);

TEST(SchemaExtension, JsonReadsAndWritesTheNewField) {
  ReadOptions<ExtendedCommand> options;
  const Parsed<ExtendedCommand> parsed = generic::fromJson<ExtendedSchema>(
      nlohmann::json{{"force_limit", {1.0, 2.0, 3.0}}}, kDof, options);
  EXPECT_EQ(parsed.command.force_limit, Eigen::Vector3d(1.0, 2.0, 3.0));
  EXPECT_EQ(parsed.command.fields, CommandField::kWrenchFeedforward);
  EXPECT_EQ(parsed.keys, FieldSet{1} << kForceLimitRow);
  EXPECT_EQ(parsed.command.nullspace_damping.size(), kDof);  // zero() from the table

  const nlohmann::json written = generic::toJson<ExtendedSchema>(parsed.command);
  EXPECT_EQ(written["force_limit"], nlohmann::json({1.0, 2.0, 3.0}));
  const ExtendedCommand back =
      generic::fromJson<ExtendedSchema>(nlohmann::json::parse(written.dump()), kDof, options)
          .command;
  EXPECT_EQ(back.force_limit, parsed.command.force_limit);
  EXPECT_EQ(back.task_frame.coeffs(), parsed.command.task_frame.coeffs());

  options.allow_shorthand = true;
  EXPECT_EQ(generic::fromJson<ExtendedSchema>(nlohmann::json{{"force_limit", 4.0}}, kDof, options)
                .command.force_limit,
            Eigen::Vector3d::Constant(4.0));
  EXPECT_THROW((void)generic::fromJson<ExtendedSchema>(nlohmann::json{{"force_limit", {1.0, 2.0}}},
                                                       kDof, options),
               InputError);
}

TEST(SchemaExtension, ValidationChecksTheNewFieldsConstraint) {
  ExtendedCommand command = ExtendedCommand::zero(kDof);
  EXPECT_TRUE(generic::checkFields<ExtendedSchema>(command, kDof, {}).ok());
  command.force_limit.y() = -1.0;
  const CheckResult negative = generic::checkFields<ExtendedSchema>(command, kDof, {});
  EXPECT_EQ(negative.violation, Violation::kNegative);
  EXPECT_EQ(negative.field, "force_limit");
  command.force_limit.y() = std::numeric_limits<double>::infinity();
  EXPECT_EQ(generic::checkFields<ExtendedSchema>(command, kDof, {}).violation,
            Violation::kNonFinite);
  command.fields = CommandField::kStiffness;  // the group is not sent: not checked
  EXPECT_TRUE(generic::checkFields<ExtendedSchema>(command, kDof, {}).ok());
}

TEST(SchemaExtension, MergeAndBusCarryTheNewField) {
  ExtendedCommand incoming = ExtendedCommand::zero(kDof);
  incoming.force_limit = {5.0, 6.0, 7.0};
  incoming.stamp_s = 3.0;
  const ExtendedBus bus = generic::toBus<ExtendedSchema>(incoming, kDof);
  EXPECT_EQ(bus.force_limit[2], 7.0);
  EXPECT_EQ(bus.dof, kDof);
  EXPECT_EQ(generic::fromBus<ExtendedSchema>(bus).force_limit, incoming.force_limit);

  ExtendedCommand into = ExtendedCommand::zero(kDof);
  ExtendedBus bus_into = generic::toBus<ExtendedSchema>(into, kDof);
  incoming.fields = CommandField::kStiffness;  // force_limit travels with the wrench group
  generic::mergeInto<ExtendedSchema, false>(into, incoming);
  EXPECT_EQ(into.force_limit, Eigen::Vector3d::Constant(10.0));
  incoming.fields = CommandField::kWrenchFeedforward;
  generic::mergeInto<ExtendedSchema, false>(into, incoming);
  EXPECT_EQ(into.force_limit, incoming.force_limit);
  EXPECT_EQ(into.stamp_s, 3.0);

  generic::mergeInto<ExtendedSchema, true>(bus_into,
                                           generic::toBus<ExtendedSchema>(incoming, kDof));
  EXPECT_EQ(bus_into.force_limit[0], 5.0);
  EXPECT_EQ(bus_into.fields, static_cast<std::uint32_t>(CommandField::kAll));
}

}  // namespace
}  // namespace comply::schema
