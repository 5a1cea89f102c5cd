// The controller's RTDE variables by name, and what a controller answers a recipe's setup.

#include "comply/ur/rtde_variables.hpp"

#include <gtest/gtest.h>

namespace comply::ur {
namespace {

TEST(RtdeVariables, TheBackendsVariablesHaveTheirTypesAndDirections) {
  const auto type = [](const char* name) { return findVariable(name).value().type; };
  EXPECT_EQ(type("timestamp"), RtdeType::kDouble);
  EXPECT_EQ(type("actual_q"), RtdeType::kVector6d);
  EXPECT_EQ(type("actual_TCP_force"), RtdeType::kVector6d);
  EXPECT_EQ(type("robot_mode"), RtdeType::kInt32);
  EXPECT_EQ(type("joint_mode"), RtdeType::kVector6Int32);
  EXPECT_EQ(type("safety_status_bits"), RtdeType::kUint32);
  EXPECT_EQ(type("actual_tool_accelerometer"), RtdeType::kVector3d);
  EXPECT_EQ(findVariable("actual_q")->direction, Direction::kOutput);
  EXPECT_EQ(findVariable("speed_slider_fraction")->direction, Direction::kInput);
  EXPECT_FALSE(findVariable("actual_Q"));  // names are case-sensitive
  EXPECT_FALSE(findVariable(""));
}

TEST(RtdeVariables, RegistersExistInTheirBanksOnly) {
  EXPECT_EQ(findVariable("input_double_register_0")->type, RtdeType::kDouble);
  EXPECT_EQ(findVariable("input_double_register_47")->direction, Direction::kInput);
  EXPECT_EQ(findVariable("output_int_register_12")->type, RtdeType::kInt32);
  EXPECT_EQ(findVariable("input_bit_register_64")->type, RtdeType::kBool);
  EXPECT_EQ(findVariable("output_bit_register_127")->direction, Direction::kOutput);
  for (const char* missing :
       {"input_double_register_48", "input_bit_register_63", "input_bit_register_128",
        "input_int_register_", "input_int_register_07", "input_int_register_1x",
        "input_int_register_-1"}) {
    EXPECT_FALSE(findVariable(missing)) << missing;
  }
}

TEST(RtdeVariables, ASetupIsAnsweredPerVariableInItsDirection) {
  const SetupReply outputs = answerSetup(
      1, {"timestamp", "actual_qd", "input_int_register_0", "bogus"}, Direction::kOutput);
  EXPECT_EQ(outputs.recipe_id, 1);
  EXPECT_EQ(outputs.types,
            (std::vector<std::string>{"DOUBLE", "VECTOR6D", "NOT_FOUND", "NOT_FOUND"}));
  const SetupReply inputs =
      answerSetup(2, {"input_double_register_24", "input_int_register_24"}, Direction::kInput);
  EXPECT_EQ(inputs.types, (std::vector<std::string>{"DOUBLE", "INT32"}));
  // What the client side makes of it: the types, or the variables refused by name.
  EXPECT_EQ(recipeTypes({"input_double_register_24", "input_int_register_24"}, inputs),
            (std::vector<RtdeType>{RtdeType::kDouble, RtdeType::kInt32}));
  EXPECT_THROW(recipeTypes({"timestamp", "actual_qd", "input_int_register_0", "bogus"}, outputs),
               RtdeError);
}

}  // namespace
}  // namespace comply::ur
