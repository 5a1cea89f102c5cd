// Plugin loading, the joint impedance laws (C++ SDK and plain C), and the SDK's parameter view.
// Every refusal of the loader must carry its code and a message naming the file and the cause,
// since that message is all a user sees when a controller fails to start.

#include <gtest/gtest.h>
#include <stdlib.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "scratch.hpp"
#include "comply/plugin/abi.h"
#include "comply/plugin/loader.hpp"
#include "comply/plugin/parameters.hpp"

namespace comply::plugin {
namespace {

namespace fs = std::filesystem;

const std::string kJointImpedance = COMPLY_TEST_JOINT_IMPEDANCE;
const std::string kJointImpedanceC = COMPLY_TEST_JOINT_IMPEDANCE_C;

/// Runs `action`, expects a PluginError with `code` whose message contains every `fragment`.
template <typename Action>
void expectPluginError(Action action, PluginErrc code, const std::vector<std::string>& fragments) {
  try {
    action();
    FAIL() << "expected PluginErrc " << static_cast<int>(code);
  } catch (const PluginError& error) {
    EXPECT_EQ(error.code(), code) << error.what();
    const std::string message = error.what();
    for (const auto& fragment : fragments) {
      EXPECT_NE(message.find(fragment), std::string::npos)
          << "'" << fragment << "' not in: " << message;
    }
  }
}

/// Sets (or unsets, for nullopt) COMPLY_PLUGIN_PATH for one test, so a developer's own setting
/// neither breaks the test nor is lost after it.
class PluginPathGuard {
 public:
  explicit PluginPathGuard(const std::optional<std::string>& value) {
    if (const char* previous = ::getenv("COMPLY_PLUGIN_PATH"); previous != nullptr) {
      previous_ = previous;
    }
    set(value);
  }
  ~PluginPathGuard() { set(previous_); }
  PluginPathGuard(const PluginPathGuard&) = delete;
  PluginPathGuard& operator=(const PluginPathGuard&) = delete;

 private:
  static void set(const std::optional<std::string>& value) {
    if (value) {
      ::setenv("COMPLY_PLUGIN_PATH", value->c_str(), 1);
    } else {
      ::unsetenv("COMPLY_PLUGIN_PATH");
    }
  }
  std::optional<std::string> previous_;
};

std::shared_ptr<const PluginLibrary> load(const std::string& path, int kind = 0) {
  return std::make_shared<const PluginLibrary>(path, kind);
}

ParameterMap maxStiffness(double limit) {
  ParameterMap parameters;
  parameters["max_stiffness"].numbers = {limit};
  return parameters;
}

comply_input jointInput(int dof) {
  comply_input input{};
  input.dof = dof;
  input.period_s = 0.001;
  return input;
}

comply_joint_command jointCommand(int dof) {
  comply_joint_command command{};
  command.dof = dof;
  command.fields = COMPLY_FIELD_POSITION | COMPLY_FIELD_VELOCITY | COMPLY_FIELD_STIFFNESS |
                   COMPLY_FIELD_DAMPING | COMPLY_FIELD_TORQUE_FEEDFORWARD;
  for (int i = 0; i < dof; ++i) {
    command.stiffness[i] = 100.0;
    command.damping[i] = 10.0;
  }
  return command;
}

// ---------------------------------------------------------------------------------------------
// Loader refusals

TEST(PluginLoader, MissingFileIsFileNotFound) {
  const std::string path = "/nonexistent/comply/libcomply_missing.so";
  expectPluginError([&] { PluginLibrary library(path); }, PluginErrc::kFileNotFound,
                    {path, "does not exist"});
}

// A symlink loop once threw std::filesystem's own error; it is refused like a missing file, with
// the cause.
TEST(PluginLoader, ASymlinkLoopIsNamedAsOne) {
  const testing::ScratchDir dir("plugin_test");
  const std::string path = (dir.path() / "libcomply_loop.so").string();
  fs::create_symlink("libcomply_loop.so", path);
  expectPluginError([&] { PluginLibrary library(path); }, PluginErrc::kFileNotFound,
                    {"plugin file '" + path + "': too many levels of symbolic links"});
}

TEST(PluginLoader, UnknownNameListsEveryPathTried) {
  const testing::ScratchDir dir("plugin_test");
  const PluginPathGuard guard(dir.path().string());
  const fs::path default_dir = fs::path(kJointImpedance).parent_path();
  expectPluginError([] { (void)resolvePlugin("no_such_law"); }, PluginErrc::kFileNotFound,
                    {"no_such_law", (dir.path() / "libcomply_no_such_law.so").string(),
                     (default_dir / "libcomply_no_such_law.so").string()});
}

TEST(PluginLoader, TextFileIsNotASharedLibrary) {
  const testing::ScratchDir dir("plugin_test");
  const fs::path path = dir.path() / "libfoo.so";
  std::ofstream(path) << "This is a text file that only has the name of a shared library.\n"
                      << "dlopen has to refuse it rather than the loader crashing on it.\n";
  expectPluginError([&] { PluginLibrary library(path.string()); }, PluginErrc::kLoadFailed,
                    {path.string(), "cannot load plugin", "invalid ELF header"});
}

TEST(PluginLoader, LibraryWithoutEntryPoint) {
  expectPluginError([] { PluginLibrary library(COMPLY_TEST_FIXTURE_NO_ENTRY); },
                    PluginErrc::kMissingEntry, {COMPLY_TEST_FIXTURE_NO_ENTRY, COMPLY_ENTRY_SYMBOL});
}

TEST(PluginLoader, AbiMismatchNamesBothVersions) {
  expectPluginError(
      [] { PluginLibrary library(COMPLY_TEST_FIXTURE_ABI_MISMATCH); }, PluginErrc::kAbiMismatch,
      {COMPLY_TEST_FIXTURE_ABI_MISMATCH, "ABI version " + std::to_string(COMPLY_ABI_VERSION + 1),
       "expects " + std::to_string(COMPLY_ABI_VERSION)});
}

TEST(PluginLoader, JointLawRefusedByCartesianWrapper) {
  for (const auto& path : {kJointImpedance, kJointImpedanceC}) {
    SCOPED_TRACE(path);
    expectPluginError([&] { PluginLibrary library(path, COMPLY_COMMAND_CARTESIAN); },
                      PluginErrc::kWrongCommandKind,
                      {path, "takes joint commands", "sends Cartesian commands"});
    EXPECT_NO_THROW(PluginLibrary(path, COMPLY_COMMAND_JOINT));
  }
}

TEST(PluginLoader, CreateFailurePropagatesThePluginsReason) {
  ParameterMap text_limit;
  text_limit["max_stiffness"].is_text = true;
  text_limit["max_stiffness"].text = "very stiff";
  for (const auto& path : {kJointImpedance, kJointImpedanceC}) {
    SCOPED_TRACE(path);
    const auto library = load(path);
    expectPluginError(
        [&] { PluginInstance instance(library, 3, text_limit); }, PluginErrc::kCreateFailed,
        {path, "refused its configuration", "parameter 'max_stiffness' must be one number"});
    expectPluginError([&] { PluginInstance instance(library, 3, maxStiffness(-1.0)); },
                      PluginErrc::kCreateFailed, {path, "'max_stiffness' must be >= 0"});
    expectPluginError([&] { PluginInstance instance(library, 3, maxStiffness(std::nan(""))); },
                      PluginErrc::kCreateFailed, {path, "'max_stiffness' must be >= 0"});
    expectPluginError([&] { PluginInstance instance(library, 0, {}); }, PluginErrc::kCreateFailed,
                      {path, "dof 0 outside 1..12"});
    expectPluginError([&] { PluginInstance instance(library, COMPLY_MAX_DOF + 1, {}); },
                      PluginErrc::kCreateFailed, {path, "dof 13 outside 1..12"});
  }
  const auto fixture = load(COMPLY_TEST_FIXTURE_CREATE_FAILS);
  expectPluginError([&] { PluginInstance instance(fixture, 3, {}); }, PluginErrc::kCreateFailed,
                    {COMPLY_TEST_FIXTURE_CREATE_FAILS, "fixture refuses to be created"});
}

TEST(PluginLoader, TrialStepErrorPropagatesThePluginsMessage) {
  const comply_input input = jointInput(3);
  comply_joint_command command = jointCommand(3);
  {
    PluginInstance instance(load(COMPLY_TEST_FIXTURE_STEP_ERROR), 3, {});
    expectPluginError(
        [&] { instance.trialStep(input, &command); }, PluginErrc::kTrialStepFailed,
        {COMPLY_TEST_FIXTURE_STEP_ERROR, "activation trial step", "fixture step error"});
  }
  command.stiffness[1] = 150.0;
  for (const auto& path : {kJointImpedance, kJointImpedanceC}) {
    SCOPED_TRACE(path);
    PluginInstance instance(load(path), 3, maxStiffness(100.0));
    expectPluginError([&] { instance.trialStep(input, &command); }, PluginErrc::kTrialStepFailed,
                      {path, "joint 1: stiffness 150 exceeds max_stiffness 100"});
  }
}

TEST(PluginLoader, NonFiniteTrialTorqueIsRefused) {
  PluginInstance instance(load(COMPLY_TEST_FIXTURE_STEP_NAN), 3, {});
  const comply_input input = jointInput(3);
  const comply_joint_command command = jointCommand(3);
  expectPluginError([&] { instance.trialStep(input, &command); }, PluginErrc::kNonFiniteOutput,
                    {COMPLY_TEST_FIXTURE_STEP_NAN, "non-finite torque for joint 2"});
}

TEST(PluginLoader, WellFormedPluginPassesTrialStep) {
  for (const auto& path : {kJointImpedance, kJointImpedanceC}) {
    SCOPED_TRACE(path);
    PluginInstance instance(load(path), 3, maxStiffness(100.0));
    EXPECT_EQ(instance.requiredQuantities(), 0U);
    const comply_input input = jointInput(3);
    const comply_joint_command command = jointCommand(3);
    EXPECT_EQ(instance.activate(input), COMPLY_OK);
    EXPECT_NO_THROW(instance.trialStep(input, &command));
  }
}

// ---------------------------------------------------------------------------------------------
// Name resolution

TEST(PluginResolution, NamesResolveInTheBuildsControllerFolder) {
  const PluginPathGuard guard(std::nullopt);
  EXPECT_TRUE(fs::equivalent(resolvePlugin("joint_impedance"), kJointImpedance));
  EXPECT_TRUE(fs::equivalent(resolvePlugin("joint_impedance_c"), kJointImpedanceC));
  EXPECT_STREQ(PluginLibrary("joint_impedance").api().name, "joint_impedance");
  EXPECT_STREQ(PluginLibrary("joint_impedance_c").api().name, "joint_impedance_c");
}

TEST(PluginResolution, PluginPathIsSearchedFirst) {
  const testing::ScratchDir dir("plugin_test");
  fs::create_symlink(kJointImpedanceC, dir.path() / "libcomply_renamed_law.so");
  // Shadows the build's C++ joint_impedance, as a user's own build of a law would.
  fs::create_symlink(kJointImpedanceC, dir.path() / "libcomply_joint_impedance.so");
  const PluginPathGuard guard("/nonexistent/comply::" + dir.path().string());

  EXPECT_EQ(resolvePlugin("renamed_law"), dir.path() / "libcomply_renamed_law.so");
  EXPECT_STREQ(PluginLibrary("renamed_law").api().name, "joint_impedance_c");
  EXPECT_EQ(resolvePlugin("joint_impedance"), dir.path() / "libcomply_joint_impedance.so");
  // Names not on COMPLY_PLUGIN_PATH still fall back to the build's folder.
  EXPECT_TRUE(fs::equivalent(resolvePlugin("joint_impedance_c"), kJointImpedanceC));
}

// ---------------------------------------------------------------------------------------------
// Joint impedance law

TEST(JointImpedance, MatchesHandComputedTorques) {
  comply_input input = jointInput(3);
  comply_joint_command command = jointCommand(3);
  const double q[] = {0.1, -0.2, 0.3};
  const double dq[] = {0.5, 0.0, -1.0};
  const double q_d[] = {0.6, 0.3, -0.7};
  const double dq_d[] = {0.0, 0.25, 0.0};
  const double k[] = {100.0, 200.0, 50.0};
  const double d[] = {10.0, 4.0, 2.0};
  const double tau_ff[] = {1.0, -2.0, 0.5};
  for (int i = 0; i < 3; ++i) {
    input.position[i] = q[i];
    input.velocity[i] = dq[i];
    command.position[i] = q_d[i];
    command.velocity[i] = dq_d[i];
    command.stiffness[i] = k[i];
    command.damping[i] = d[i];
    command.torque_feedforward[i] = tau_ff[i];
  }
  // 100 * 0.5 + 10 * -0.5 + 1,  200 * 0.5 + 4 * 0.25 - 2,  50 * -1 + 2 * 1 + 0.5
  const double expected[] = {46.0, 99.0, -47.5};

  for (const auto& path : {kJointImpedance, kJointImpedanceC}) {
    SCOPED_TRACE(path);
    PluginInstance instance(load(path), 3, {});
    ASSERT_EQ(instance.activate(input), COMPLY_OK);
    comply_output output{};
    ASSERT_EQ(instance.step(input, &command, output), COMPLY_OK);
    for (int i = 0; i < 3; ++i) {
      EXPECT_NEAR(output.torque[i], expected[i], 1e-12) << "joint " << i;
    }
  }
}

TEST(JointImpedance, CAndCppPluginsAreBitIdentical) {
  constexpr double kLimit = 1000.0;
  const auto cpp = load(kJointImpedance);
  const auto c = load(kJointImpedanceC);
  std::vector<std::unique_ptr<PluginInstance>> cpp_instances;
  std::vector<std::unique_ptr<PluginInstance>> c_instances;
  for (int dof = 1; dof <= COMPLY_MAX_DOF; ++dof) {
    cpp_instances.push_back(std::make_unique<PluginInstance>(cpp, dof, maxStiffness(kLimit)));
    c_instances.push_back(std::make_unique<PluginInstance>(c, dof, maxStiffness(kLimit)));
  }

  std::mt19937_64 rng(20240611);
  std::uniform_int_distribution<int> dof_distribution(1, COMPLY_MAX_DOF);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::uniform_real_distribution<double> exponent(-3.0, 3.0);
  // Magnitudes over six decades, so the sums round differently from joint to joint.
  const auto value = [&] { return unit(rng) * std::pow(10.0, exponent(rng)); };
  const auto gain = [&] { return std::abs(unit(rng)) * kLimit; };

  int failures = 0;
  for (int sample = 0; sample < 1000; ++sample) {
    const int dof = dof_distribution(rng);
    comply_input input = jointInput(dof);
    comply_joint_command command{};
    command.dof = dof;
    command.fields = static_cast<std::uint32_t>(rng() & 0x1ffU);
    for (int i = 0; i < dof; ++i) {
      input.position[i] = value();
      input.velocity[i] = value();
      input.effort[i] = value();
      command.position[i] = value();
      command.velocity[i] = value();
      command.acceleration[i] = value();
      command.stiffness[i] = gain();
      command.damping[i] = gain();
      command.torque_feedforward[i] = value();
    }
    if (sample % 10 == 0) {
      command.stiffness[rng() % static_cast<unsigned>(dof)] = kLimit * (1.0 + std::abs(unit(rng)));
    }

    comply_output cpp_output{};
    comply_output c_output{};
    const comply_status cpp_status =
        cpp_instances[static_cast<std::size_t>(dof - 1)]->step(input, &command, cpp_output);
    const comply_status c_status =
        c_instances[static_cast<std::size_t>(dof - 1)]->step(input, &command, c_output);
    ASSERT_EQ(cpp_status, c_status) << "sample " << sample;
    if (cpp_status != COMPLY_OK) {
      ++failures;
      EXPECT_STREQ(cpp_output.message, c_output.message) << "sample " << sample;
      continue;
    }
    for (int i = 0; i < dof; ++i) {
      EXPECT_EQ(std::bit_cast<std::uint64_t>(cpp_output.torque[i]),
                std::bit_cast<std::uint64_t>(c_output.torque[i]))
          << "sample " << sample << " joint " << i << ": " << cpp_output.torque[i] << " vs "
          << c_output.torque[i];
    }
  }
  EXPECT_EQ(failures, 100);
}

// ---------------------------------------------------------------------------------------------
// Parameter view

class ParametersTest : public ::testing::Test {
 protected:
  const double one_[1] = {2.5};
  const double three_[3] = {1.0, 2.0, 3.0};
  const comply_parameter items_[3] = {
      {"gain", one_, 1, nullptr}, {"gains", three_, 3, nullptr}, {"mode", nullptr, 0, "fast"}};
  const comply_parameters table_{items_, 3};
  const Parameters parameters_{&table_};
};

TEST_F(ParametersTest, Has) {
  EXPECT_TRUE(parameters_.has("gain"));
  EXPECT_TRUE(parameters_.has("mode"));
  EXPECT_FALSE(parameters_.has("missing"));
  EXPECT_FALSE(Parameters(nullptr).has("gain"));
}

TEST_F(ParametersTest, Number) {
  EXPECT_EQ(parameters_.number("gain", 0.0), 2.5);
  EXPECT_EQ(parameters_.number("missing", 7.0), 7.0);
  EXPECT_EQ(Parameters(nullptr).number("gain", 7.0), 7.0);
  EXPECT_THROW((void)parameters_.number("gains", 0.0), ParameterError);
  EXPECT_THROW((void)parameters_.number("mode", 0.0), ParameterError);
}

TEST_F(ParametersTest, Numbers) {
  const auto gains = parameters_.numbers("gains", 3);
  ASSERT_EQ(gains.size(), 3U);
  EXPECT_EQ(gains[0], 1.0);
  EXPECT_EQ(gains[2], 3.0);
  EXPECT_TRUE(parameters_.numbers("missing", 3).empty());
  EXPECT_EQ(parameters_.numbers("gain", 1).size(), 1U);
}

TEST_F(ParametersTest, NumbersErrorsNameTheParameter) {
  try {
    (void)parameters_.numbers("gains", 7);
    FAIL() << "expected ParameterError";
  } catch (const ParameterError& error) {
    EXPECT_STREQ(error.what(), "parameter 'gains' has 3 values, expected 7");
  }
  try {
    (void)parameters_.numbers("mode", 1);
    FAIL() << "expected ParameterError";
  } catch (const ParameterError& error) {
    EXPECT_STREQ(error.what(), "parameter 'mode' must be a list of numbers");
  }
}

TEST_F(ParametersTest, Text) {
  EXPECT_EQ(parameters_.text("mode", "slow"), "fast");
  EXPECT_EQ(parameters_.text("missing", "slow"), "slow");
  try {
    (void)parameters_.text("gain", "");
    FAIL() << "expected ParameterError";
  } catch (const ParameterError& error) {
    EXPECT_STREQ(error.what(), "parameter 'gain' must be a string");
  }
}

}  // namespace
}  // namespace comply::plugin
