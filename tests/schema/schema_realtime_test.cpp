// The bus operations run in the control cycle: they must not touch the heap. Counted by
// interposing the allocator in this executable (tests/support/allocation_counter.hpp).

#include <gtest/gtest.h>

#include "allocation_counter.hpp"
#include "comply/schema/schema.hpp"
#include "schema_support.hpp"

namespace comply::schema {
namespace {

static_assert(noexcept(mergeBus(std::declval<comply_cartesian_command&>(),
                                std::declval<const comply_cartesian_command&>())));
static_assert(noexcept(seedReference(std::declval<comply_joint_command&>(),
                                     std::declval<const MeasuredPose&>())));
static_assert(noexcept(stopMotion(std::declval<comply_cartesian_command&>())));

TEST(SchemaRealtime, BusOperationsDoNotAllocate) {
  comply_cartesian_command cartesian = toBus(test::distinctCartesian(), test::kDof);
  const comply_cartesian_command cartesian_in = toBus(test::distinctCartesian(), test::kDof);
  comply_joint_command joint = toBus(test::distinctJoint(), test::kDof);
  const comply_joint_command joint_in = toBus(test::distinctJoint(), test::kDof);
  MeasuredPose pose;
  pose.position = test::ramp(0.0);
  pose.valid = true;

  testing::AllocationCounter counter;
  counter.start();
  for (int i = 0; i < 100; ++i) {
    mergeBus(cartesian, cartesian_in);
    mergeBus(joint, joint_in);
    seedReference(cartesian, pose);
    seedReference(joint, pose);
    stopMotion(cartesian);
    stopMotion(joint);
  }
  EXPECT_EQ(counter.stop(), 0U);
}

}  // namespace
}  // namespace comply::schema
