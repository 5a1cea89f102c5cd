// loadBackendLibrary: a backend built as the out-of-tree ones are (COMPLY_HARDWARE_BACKEND in a
// MODULE library) is driven through its handle, and each way a library can fail to be one is
// refused with its path and the cause (fixtures/two_joint_backend.cpp).

#include <dlfcn.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <array>
#include <cstdint>
#include <filesystem>
#include <string>
#include <utility>

#include "comply/hardware/backend.hpp"

namespace comply::hardware {
namespace {

BackendContext twoJointContext() {
  BackendContext context;
  context.robot_name = "two_joint";
  context.joints = {"joint1", "joint2"};
  context.home_position = {0.1, -0.2};
  context.period_s = 0.01;
  return context;
}

/// The message loadBackendLibrary throws for `library`; fails the test when it loads.
std::string refusal(const std::string& library, const BackendContext& context) {
  try {
    loadBackendLibrary(library, context);
  } catch (const BackendError& error) {
    return error.what();
  }
  ADD_FAILURE() << library << " was loaded";
  return {};
}

/// True while `library` is loaded in this process (RTLD_NOLOAD opens nothing new).
bool isLoaded(const char* library) {
  void* handle = ::dlopen(library, RTLD_NOW | RTLD_NOLOAD);
  if (handle == nullptr) {
    return false;
  }
  ::dlclose(handle);
  return true;
}

TEST(BackendLibrary, DrivesTheArmItLoaded) {
  const BackendHandle arm = loadBackendLibrary(COMPLY_TEST_BACKEND_GOOD, twoJointContext());
  ASSERT_TRUE(arm);
  EXPECT_EQ(arm->dof(), 2);
  EXPECT_FALSE(arm->compensatesGravity()) << "the interface's default";
  Vector6d wrench = Vector6d::Zero();
  EXPECT_FALSE(arm->readWrench(wrench)) << "the interface's default: no sensor";

  JointState state = JointState::zero(2);
  ASSERT_TRUE(arm->read(state));
  EXPECT_DOUBLE_EQ(state.position[0], 0.1) << "starts at home";
  EXPECT_DOUBLE_EQ(state.position[1], -0.2);
  EXPECT_DOUBLE_EQ(state.velocity[0], 0.0);

  const std::array<double, 2> torque_nm{1.0, -2.0};
  ASSERT_TRUE(arm->write(torque_nm));
  ASSERT_TRUE((*arm).read(state));
  // One period of 0.01 s on a unit inertia: dq = tau dt, then q += dq dt.
  EXPECT_DOUBLE_EQ(state.velocity[0], 0.01);
  EXPECT_DOUBLE_EQ(state.velocity[1], -0.02);
  EXPECT_DOUBLE_EQ(state.position[0], 0.1 + 0.01 * 0.01);
  EXPECT_DOUBLE_EQ(state.position[1], -0.2 - 0.02 * 0.01);
  EXPECT_DOUBLE_EQ(state.effort[1], -2.0) << "the effort is the torque last written";

  const std::array<double, 3> too_long{0.0, 0.0, 0.0};
  EXPECT_FALSE(arm->write(too_long));
}

TEST(BackendLibrary, HandleDestroysThroughTheLibraryThenUnloadsIt) {
  int destroyed = 0;
  BackendContext context = twoJointContext();
  context.options["destroyed_counter"] =
      std::to_string(reinterpret_cast<std::uintptr_t>(&destroyed));
  BackendHandle arm = loadBackendLibrary(COMPLY_TEST_BACKEND_GOOD, context);
  EXPECT_TRUE(isLoaded(COMPLY_TEST_BACKEND_GOOD)) << "loaded while the interface lives";

  // Moving hands over the one interface; nothing is destroyed twice.
  BackendHandle moved = std::move(arm);
  EXPECT_FALSE(arm);  // NOLINT(bugprone-use-after-move): a moved-from handle is empty by contract
  ASSERT_TRUE(moved);
  EXPECT_EQ(moved->dof(), 2);
  EXPECT_EQ(destroyed, 0);

  // Assigning over a live handle destroys the interface it held.
  moved = loadBackendLibrary(COMPLY_TEST_BACKEND_GOOD, context);
  EXPECT_EQ(destroyed, 1);

  moved.reset();
  EXPECT_FALSE(moved);
  EXPECT_EQ(destroyed, 2);
  EXPECT_FALSE(isLoaded(COMPLY_TEST_BACKEND_GOOD)) << "unloaded after the interface";
  moved.reset();
  EXPECT_EQ(destroyed, 2);
}

TEST(BackendLibrary, RefusalsNameTheLibraryAndTheCause) {
  const BackendContext context = twoJointContext();

  const std::string missing = refusal("/nonexistent/libcomply_hardware_none.so", context);
  EXPECT_NE(missing.find("/nonexistent/libcomply_hardware_none.so"), std::string::npos) << missing;
  EXPECT_NE(missing.find("no such file"), std::string::npos) << missing;

  // A symlink loop once read "no such file".
  const std::filesystem::path loop = std::filesystem::temp_directory_path() /
                                     ("comply_backend_loop_" + std::to_string(::getpid()));
  std::filesystem::remove(loop);
  std::filesystem::create_symlink(loop.filename(), loop);
  const std::string looped = refusal(loop.string(), context);
  std::filesystem::remove(loop);
  EXPECT_NE(looped.find(loop.string()), std::string::npos) << looped;
  EXPECT_NE(looped.find("too many levels of symbolic links (a symlink loop)"), std::string::npos)
      << looped;

  // A file that is not a shared library: dlopen's own reason is passed on.
  const std::string not_elf = refusal(COMPLY_TEST_SOURCE_FILE, context);
  EXPECT_NE(not_elf.find(COMPLY_TEST_SOURCE_FILE), std::string::npos) << not_elf;
  EXPECT_NE(not_elf.find("cannot load it: "), std::string::npos) << not_elf;

  const std::string no_entry = refusal(COMPLY_TEST_BACKEND_NO_ENTRY, context);
  EXPECT_NE(no_entry.find(COMPLY_TEST_BACKEND_NO_ENTRY), std::string::npos) << no_entry;
  EXPECT_NE(no_entry.find("not a comply hardware backend (no comply_hardware_create)"),
            std::string::npos)
      << no_entry;

  const std::string wrong_abi = refusal(COMPLY_TEST_BACKEND_WRONG_ABI, context);
  EXPECT_NE(wrong_abi.find(COMPLY_TEST_BACKEND_WRONG_ABI), std::string::npos) << wrong_abi;
  const std::string versions = "built for backend interface version " +
                               std::to_string(kBackendAbiVersion + 1) + ", this comply has " +
                               std::to_string(kBackendAbiVersion);
  EXPECT_NE(wrong_abi.find(versions), std::string::npos) << wrong_abi;

  BackendContext addressed = context;
  addressed.options["address"] = "192.0.2.1";
  const std::string refused = refusal(COMPLY_TEST_BACKEND_REFUSES, addressed);
  EXPECT_NE(refused.find(COMPLY_TEST_BACKEND_REFUSES), std::string::npos) << refused;
  EXPECT_NE(refused.find("refused to start: no robot at 192.0.2.1"), std::string::npos) << refused;
}

TEST(BackendLibrary, LongRefusalIsCutToTheErrorBuffer) {
  BackendContext context = twoJointContext();
  context.options["address"] = std::string(2000, 'x');
  const std::string refused = refusal(COMPLY_TEST_BACKEND_REFUSES, context);
  const auto reason = refused.find("refused to start: no robot at xxx");
  ASSERT_NE(reason, std::string::npos) << refused;
  // 512 bytes with the NUL: the backend's message arrives as its first 511 characters.
  EXPECT_EQ(refused.size() - (reason + std::string("refused to start: ").size()), 511u);
}

}  // namespace
}  // namespace comply::hardware
