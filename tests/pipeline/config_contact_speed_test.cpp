// The controller file's contact_speed.* options: off by default with the hands' quasi-static
// limits, every name of the body-region table accepted, and each bad value refused with the valid
// names or the reason in the error.

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "comply/pipeline/body_regions.hpp"
#include "comply/pipeline/config.hpp"
#include "config_errors.hpp"

namespace comply::pipeline {
namespace {

WrapperConfig parse(const std::string& lines) {
  return parseWrapperText(
      "arm_controller:\n  ros__parameters:\n    plugin: cartesian_impedance\n    robot: fr3\n"
      "    contact_speed:\n" +
          lines,
      "arm.yaml");
}

void expectError(const std::string& lines, const std::vector<std::string>& fragments) {
  test::expectReadError(parse, lines, fragments);
}

TEST(ContactSpeedConfig, OffByDefaultForTheHandsQuasiStaticWithTheTablesValues) {
  const WrapperConfig config = parse("      enabled: false\n");
  EXPECT_FALSE(config.contact_speed.enabled);
  EXPECT_EQ(config.contact_speed.body_region, BodyRegion::kHands);
  EXPECT_EQ(config.contact_speed.contact, ContactKind::kQuasiStatic);
  EXPECT_EQ(config.contact_speed.force_limit_n, 0.0);
  EXPECT_EQ(config.contact_speed.stiffness_n_per_m, 0.0);
  EXPECT_FALSE(config.contact_speed.body_mass);
}

TEST(ContactSpeedConfig, EveryRegionOfTheTableIsReadByItsName) {
  for (const auto& [region, name] : kBodyRegionNames) {
    const WrapperConfig config =
        parse("      enabled: true\n      body_region: " + std::string(name) + "\n");
    EXPECT_EQ(config.contact_speed.body_region, region) << name;
    const BodyRegionLimits limits = bodyRegionLimits(region);
    EXPECT_GT(limits.quasi_static_force_n, 0.0) << name;
    EXPECT_GT(limits.stiffness_n_per_m, 0.0) << name;
    EXPECT_GT(limits.effective_mass_kg, 0.0) << name;
  }
}

TEST(ContactSpeedConfig, AnUnknownRegionIsRefusedWithTheValidNames) {
  expectError("      body_region: fingers\n",
              {"contact_speed.body_region", "skull_forehead", "hands", "lower_legs"});
  expectError("      contact: impact\n", {"contact_speed.contact", "quasi_static", "transient"});
}

TEST(ContactSpeedConfig, TransientContactWhereTheTableForbidsItIsRefused) {
  for (const char* region : {"face", "skull_forehead"}) {
    expectError(std::string("      enabled: true\n      contact: transient\n      body_region: ") +
                    region + "\n",
                {"contact_speed.contact", region, "quasi_static"});
  }
  // The same with a force limit of the user's own is the user's call.
  const WrapperConfig config = parse(
      "      enabled: true\n      contact: transient\n      body_region: face\n"
      "      force_limit_n: 50\n");
  EXPECT_EQ(config.contact_speed.force_limit_n, 50.0);
}

TEST(ContactSpeedConfig, ANegativeOrAbsurdLimitIsRefused) {
  expectError("      force_limit_n: -5\n",
              {"contact_speed.force_limit_n", "must be in [0, 10000]"});
  expectError("      stiffness_n_per_m: -1\n", {"contact_speed.stiffness_n_per_m"});
  expectError("      enabled: maybe\n", {"contact_speed.enabled"});
}

}  // namespace
}  // namespace comply::pipeline
