// comply's URScript control program: what is written is read back the same, each mode calls its
// command with the registers it was given, and text that is not the program, or values out of
// UR's ranges, are refused by name. The robot's modes say why an arm takes no commands.

#include "comply/ur/control_program.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "comply/ur/robot_status.hpp"

namespace comply::ur {
namespace {

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

TEST(ControlProgram, IsReadBackAsWritten) {
  for (const OutputMode mode :
       {OutputMode::kPosition, OutputMode::kVelocity, OutputMode::kTorque}) {
    ControlProgram program;
    program.mode = mode;
    program.register_offset = 30;
    program.watchdog_s = 0.1;
    program.servoj_lookahead_s = 0.05;
    program.servoj_gain = 600.0;
    const std::string script = controlProgramScript(program);
    const ControlProgram read = readControlProgram(script);
    EXPECT_EQ(read.mode, mode);
    EXPECT_EQ(read.register_offset, 30);
    EXPECT_DOUBLE_EQ(read.watchdog_s, 0.1);
    EXPECT_DOUBLE_EQ(read.servoj_lookahead_s, 0.05);
    EXPECT_DOUBLE_EQ(read.servoj_gain, 600.0);
    EXPECT_TRUE(contains(script, std::string(driveCommand(mode)) + "(target")) << script;
    // The registers it reads are the ones it was given, and no others.
    EXPECT_TRUE(contains(script, "read_input_integer_register(30)"));
    EXPECT_TRUE(contains(script, "read_input_integer_register(31)"));
    EXPECT_TRUE(contains(script, "read_input_float_register(35)"));
    EXPECT_FALSE(contains(script, "read_input_float_register(36)"));
    EXPECT_FALSE(contains(script, "register(24)"));
  }
}

// What a controller takes over its secondary interface: `def` first and `end` last, in column 0,
// nothing after; textmsg with at most two arguments; the program numbered as it was sent.
TEST(ControlProgram, IsOneDefinitionTheControllerRuns) {
  ControlProgram program;
  program.instance = 123456;
  const std::string script = controlProgramScript(program);
  EXPECT_TRUE(script.starts_with("def comply_control():\n")) << script.substr(0, 40);
  EXPECT_TRUE(script.ends_with("\nend\n"));
  EXPECT_EQ(script.find("\nend\n"), script.size() - 5) << "text after the definition";
  for (std::size_t at = script.find("textmsg("); at != std::string::npos;
       at = script.find("textmsg(", at + 1)) {
    const std::string call = script.substr(at, script.find('\n', at) - at);
    EXPECT_LE(std::count(call.begin(), call.end(), ','), 1) << call;
  }
  EXPECT_TRUE(contains(script, "write_output_integer_register(25, COMPLY_INSTANCE)"));
  EXPECT_TRUE(contains(script, "write_output_integer_register(25, -COMPLY_INSTANCE)"));
  EXPECT_EQ(readControlProgram(script).instance, 123456);
  std::string trailing = script + "comply_control()\n";
  EXPECT_THROW((void)readControlProgram(trailing), ControlProgramError);
}

TEST(ControlProgram, HasAWatchdogThatStopsTheArm) {
  const std::string script = controlProgramScript({});
  EXPECT_TRUE(contains(script, "if armed and quiet > COMPLY_WATCHDOG:"));
  EXPECT_TRUE(contains(script, "stopj(COMPLY_DECELERATION)\n      halt"));
}

TEST(ControlProgram, RefusesWhatAUrCannotRun) {
  ControlProgram pd;
  pd.mode = OutputMode::kJointPd;
  EXPECT_THROW(
      {
        try {
          (void)controlProgramScript(pd);
        } catch (const ControlProgramError& error) {
          EXPECT_TRUE(contains(error.what(), "no per-joint PD")) << error.what();
          throw;
        }
      },
      ControlProgramError);
  ControlProgram gain;
  gain.servoj_gain = 5000.0;
  EXPECT_THROW((void)controlProgramScript(gain), ControlProgramError);
  ControlProgram registers;
  registers.register_offset = 44;  // 44..49: past the last register, 47
  EXPECT_THROW((void)controlProgramScript(registers), ControlProgramError);
  ControlProgram watchdog;
  watchdog.watchdog_s = 0.001;
  EXPECT_THROW((void)controlProgramScript(watchdog), ControlProgramError);
}

TEST(ControlProgram, RefusesTextThatIsNotIt) {
  EXPECT_THROW((void)readControlProgram("def prog():\n  movej([0,0,0,0,0,0])\nend\n"),
               ControlProgramError);
  std::string script = controlProgramScript({});
  const std::size_t gain = script.find("COMPLY_GAIN = ");
  script.replace(gain, script.find('\n', gain) - gain, "COMPLY_GAIN = fast");
  try {
    (void)readControlProgram(script);
    FAIL() << "a gain that is not a number was read";
  } catch (const ControlProgramError& error) {
    EXPECT_TRUE(contains(error.what(), "COMPLY_GAIN")) << error.what();
  }
}

TEST(RobotStatus, SaysWhyTheArmTakesNoCommands) {
  const auto running = static_cast<std::int32_t>(RobotMode::kRunning);
  const auto normal = static_cast<std::int32_t>(SafetyMode::kNormal);
  const auto playing = static_cast<std::uint32_t>(RuntimeState::kPlaying);
  EXPECT_EQ(stopReason(running, normal, playing, true), nullptr);
  EXPECT_EQ(stopReason(running, static_cast<std::int32_t>(SafetyMode::kReduced), playing, true),
            nullptr);
  EXPECT_TRUE(contains(
      stopReason(running, static_cast<std::int32_t>(SafetyMode::kProtectiveStop), playing, true),
      "protective stop"));
  EXPECT_TRUE(
      contains(stopReason(running, static_cast<std::int32_t>(SafetyMode::kRobotEmergencyStop),
                          playing, true),
               "emergency stop"));
  EXPECT_TRUE(
      contains(stopReason(static_cast<std::int32_t>(RobotMode::kPowerOff), normal, playing, true),
               "not powered on"));
  EXPECT_TRUE(contains(
      stopReason(running, normal, static_cast<std::uint32_t>(RuntimeState::kStopped), true),
      "program is not running"));
  EXPECT_TRUE(contains(stopReason(running, normal, playing, false), "program is not running"));
  EXPECT_EQ(safetyModeName(3), "PROTECTIVE_STOP");
  EXPECT_EQ(robotModeName(7), "RUNNING");
  EXPECT_EQ(robotModeName(-1), "NO_CONTROLLER");
  EXPECT_EQ(runtimeStateName(2), "PLAYING");
  EXPECT_EQ(safetyModeName(99), "UNKNOWN");
}

}  // namespace
}  // namespace comply::ur
