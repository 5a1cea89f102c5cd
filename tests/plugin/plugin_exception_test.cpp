// An exception thrown by a C++ law through the C ABI must never end the host process: the loader
// catches it at each call into the plugin and turns it into a refusal (create), a failed call
// (activate, step) or nothing (destroy). Each fixture throws from one function.

#include <gtest/gtest.h>

#include <cstring>
#include <memory>
#include <string>

#include "comply/plugin/abi.h"
#include "comply/plugin/loader.hpp"

namespace comply::plugin {
namespace {

constexpr int kDof = 3;

std::shared_ptr<const PluginLibrary> load(const std::string& path) {
  return std::make_shared<const PluginLibrary>(path, 0);
}

comply_input jointInput() {
  comply_input input{};
  input.dof = kDof;
  input.period_s = 0.001;
  return input;
}

/// Expects creating an instance of `path` to be refused with kCreateFailed naming the file and
/// saying that the plugin threw.
void expectCreateRefused(const std::string& path) {
  try {
    PluginInstance instance(load(path), kDof, {});
    FAIL() << "expected a refusal of " << path;
  } catch (const PluginError& error) {
    EXPECT_EQ(error.code(), PluginErrc::kCreateFailed) << error.what();
    const std::string message = error.what();
    EXPECT_NE(message.find(path), std::string::npos) << message;
    EXPECT_NE(message.find("threw an exception"), std::string::npos) << message;
  }
}

TEST(PluginException, ThrowingCreateIsARefusal) {
  expectCreateRefused(COMPLY_TEST_FIXTURE_THROWING_CREATE);
}

TEST(PluginException, ThrowingRequiredQuantitiesIsARefusal) {
  expectCreateRefused(COMPLY_TEST_FIXTURE_THROWING_REQUIRED_QUANTITIES);
}

TEST(PluginException, ThrowingActivateIsAFailedActivation) {
  PluginInstance instance(load(COMPLY_TEST_FIXTURE_THROWING_ACTIVATE), kDof, {});
  EXPECT_EQ(instance.activate(jointInput()), COMPLY_ERROR);
}

TEST(PluginException, ThrowingStepIsAFailedStepWithAReason) {
  PluginInstance instance(load(COMPLY_TEST_FIXTURE_THROWING), kDof, {});
  const comply_input input = jointInput();
  comply_output output{};
  ASSERT_EQ(instance.step(input, nullptr, output), COMPLY_OK);  // the fixture's first step passes
  EXPECT_EQ(instance.step(input, nullptr, output), COMPLY_ERROR);
  EXPECT_STREQ(output.message, "step threw an exception");
}

TEST(PluginException, ThrowingDestroyIsSurvived) {
  auto instance = std::make_unique<PluginInstance>(load(COMPLY_TEST_FIXTURE_THROWING_DESTROY), kDof,
                                                   ParameterMap{});
  EXPECT_NO_FATAL_FAILURE(instance.reset());
}

}  // namespace
}  // namespace comply::plugin
