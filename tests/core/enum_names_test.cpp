#include "comply/core/enum_names.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "comply/core/wrapper_state.hpp"

namespace comply {
namespace {

enum class Drive : unsigned char { kTorque = 2, kPosition = 3, kVelocity = 4 };
constexpr EnumNames<Drive, 3> kDriveNames{
    {{Drive::kTorque, "torque"}, {Drive::kPosition, "position"}, {Drive::kVelocity, "velocity"}}};

TEST(EnumNames, ReadsBothWays) {
  static_assert(nameIn(kDriveNames, Drive::kPosition) == "position");
  EXPECT_EQ(nameIn(kDriveNames, Drive::kVelocity), "velocity");
  EXPECT_EQ(valueIn(kDriveNames, "torque"), Drive::kTorque);
  EXPECT_FALSE(valueIn(kDriveNames, "Torque").has_value());  // names are exact
  EXPECT_FALSE(valueIn(kDriveNames, "").has_value());
}

TEST(EnumNames, AValueOutsideTheTableHasTheGivenName) {
  const auto bad = static_cast<Drive>(9);  // as a cast from a wire byte may give
  EXPECT_EQ(nameIn(kDriveNames, bad), "unknown");
  EXPECT_EQ(nameIn(kDriveNames, bad, "?"), "?");
  EXPECT_EQ(toString(static_cast<WrapperState>(7)), "unknown");
}

TEST(EnumNames, ListsTheNamesInTableOrder) {
  EXPECT_EQ(namesIn(kDriveNames), (std::vector<std::string>{"torque", "position", "velocity"}));
  EXPECT_EQ(kDriveNames.size(), 3U);
}

TEST(EnumNames, EveryWrapperStateHasItsOwnName) {
  EXPECT_EQ(toString(WrapperState::kInactive), "inactive");
  EXPECT_EQ(toString(WrapperState::kActive), "active");
  EXPECT_EQ(toString(WrapperState::kFault), "fault");
  for (const auto& [state, name] : kWrapperStateNames) {
    EXPECT_EQ(valueIn(kWrapperStateNames, name), state) << name;
  }
}

}  // namespace
}  // namespace comply
