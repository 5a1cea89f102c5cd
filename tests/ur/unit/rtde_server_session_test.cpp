// A UR controller's side of an RTDE connection, driven by the client's packages as comply's
// encoders write them, its answers read back as a client reads them.

#include "comply/ur/rtde_server_session.hpp"

#include <gtest/gtest.h>

namespace comply::ur {
namespace {

using Bytes = std::vector<std::uint8_t>;

/// The session's answers to `request` (a whole package's bytes), as packages.
std::vector<Package> answersTo(RtdeServerSession& session, const Bytes& request) {
  PackageFramer in;
  in.feed(request);
  Package package;
  EXPECT_TRUE(in.next(package));
  PackageFramer out;
  for (const Bytes& answer : session.handle(package)) {
    out.feed(answer);
  }
  std::vector<Package> answers;
  for (Package answer; out.next(answer);) {
    answers.push_back(answer);
  }
  return answers;
}

RtdeServerSession agreed() {
  RtdeServerSession session({5, 23, 0, 0});
  const std::vector<Package> answers = answersTo(session, protocolVersionRequest(2));
  EXPECT_TRUE(readAccepted(answers.at(0).payload));
  return session;
}

TEST(RtdeServerSession, AgreesOnVersionTwoOnlyAndSaysItsControllerVersion) {
  RtdeServerSession session({5, 23, 1, 99});
  std::vector<Package> answers = answersTo(session, protocolVersionRequest(1));
  ASSERT_EQ(answers.size(), 1U);
  EXPECT_FALSE(readAccepted(answers[0].payload));
  EXPECT_EQ(session.protocolVersion(), 0);
  answers = answersTo(session, setupOutputsRequest({500, {"timestamp"}}));
  ASSERT_EQ(answers.size(), 2U) << "the reason, then the refusal";
  EXPECT_EQ(readTextMessage(answers[0].payload).message,
            "request protocol version 2 first: this controller speaks no other");
  EXPECT_EQ(readSetupReply(answers[1].payload).recipe_id, 0);
  answers = answersTo(session, protocolVersionRequest(2));
  EXPECT_TRUE(readAccepted(answers.at(0).payload));
  const ControllerVersion version =
      readControllerVersion(answersTo(session, controllerVersionRequest()).at(0).payload);
  EXPECT_EQ(version.minor, 23U);
  EXPECT_EQ(version.build, 99U);
}

TEST(RtdeServerSession, AnOutputRecipeIsServedAsTheClientReadsIt) {
  RtdeServerSession session = agreed();
  const std::vector<std::string> names{"timestamp", "actual_q", "robot_mode"};
  const SetupReply reply =
      readSetupReply(answersTo(session, setupOutputsRequest({500, names})).at(0).payload);
  const std::vector<RtdeType> types = recipeTypes(names, reply);
  ASSERT_TRUE(session.output());
  EXPECT_EQ(session.output()->id, reply.recipe_id);
  EXPECT_EQ(session.output()->frequency_hz, 500.0);
  EXPECT_TRUE(readAccepted(answersTo(session, startRequest()).at(0).payload));
  const std::vector<RtdeValue> values{12.5, std::array<double, 6>{0, -1.57, 1.57, -1.57, -1.57, 0},
                                      std::int32_t{7}};
  PackageFramer framer;
  framer.feed(session.outputPackage(values));
  Package data;
  ASSERT_TRUE(framer.next(data));
  EXPECT_EQ(readRecipeId(data.payload), reply.recipe_id);
  EXPECT_EQ(readData(data.payload, types), values);
  const std::vector<RtdeValue> wrong{12.5, 1.0, std::int32_t{7}};
  EXPECT_THROW((void)session.outputPackage(wrong), RtdeError);
}

TEST(RtdeServerSession, ARecipeItCannotServeIsRefusedAndCannotBeSent) {
  RtdeServerSession session = agreed();
  std::vector<Package> answers = answersTo(session, setupOutputsRequest({1000, {"timestamp"}}));
  ASSERT_EQ(answers.size(), 2U);
  EXPECT_NE(readTextMessage(answers[0].payload).message.find("serves up to 500"),
            std::string::npos);
  answers = answersTo(session, setupOutputsRequest({125, {"timestamp", "bogus"}}));
  ASSERT_EQ(answers.size(), 1U);
  EXPECT_THROW(recipeTypes({"timestamp", "bogus"}, readSetupReply(answers[0].payload)), RtdeError);
  EXPECT_FALSE(session.output());
  EXPECT_THROW((void)session.outputPackage({}), RtdeError);
}

TEST(RtdeServerSession, InputsTheClientWritesAreKeptByName) {
  RtdeServerSession session = agreed();
  const std::vector<std::string> names{"input_double_register_0", "input_int_register_0"};
  const SetupReply reply =
      readSetupReply(answersTo(session, setupInputsRequest(names)).at(0).payload);
  const std::vector<RtdeType> types = recipeTypes(names, reply);
  EXPECT_EQ(types, (std::vector<RtdeType>{RtdeType::kDouble, RtdeType::kInt32}));
  // A second recipe may not write what the first does.
  const SetupReply taken = readSetupReply(
      answersTo(session, setupInputsRequest({"input_double_register_0", "input_double_register_1"}))
          .at(0)
          .payload);
  EXPECT_EQ(taken.types, (std::vector<std::string>{"IN_USE", "DOUBLE"}));
  const std::vector<RtdeValue> values{0.25, std::int32_t{3}};
  std::vector<Package> answers = answersTo(session, dataPackage(reply.recipe_id, values));
  ASSERT_EQ(answers.size(), 1U);
  EXPECT_EQ(readTextMessage(answers[0].payload).message,
            "a data package while paused: start first");
  EXPECT_TRUE(session.inputs().empty());
  answersTo(session, startRequest());
  EXPECT_TRUE(answersTo(session, dataPackage(reply.recipe_id, values)).empty());
  EXPECT_EQ(session.inputs().at("input_double_register_0"), RtdeValue{0.25});
  EXPECT_EQ(session.inputs().at("input_int_register_0"), RtdeValue{std::int32_t{3}});
  answers = answersTo(session, dataPackage(77, values));
  EXPECT_EQ(readTextMessage(answers.at(0).payload).message,
            "a data package of recipe 77, which is no input recipe of this connection");
}

TEST(RtdeServerSession, RecipesAreSetUpWhilePausedOnly) {
  RtdeServerSession session = agreed();
  answersTo(session, setupOutputsRequest({500, {"timestamp"}}));
  answersTo(session, startRequest());
  std::vector<Package> answers = answersTo(session, setupOutputsRequest({500, {"actual_q"}}));
  ASSERT_EQ(answers.size(), 2U);
  EXPECT_EQ(readTextMessage(answers[0].payload).message,
            "recipes are set up while paused: pause first");
  EXPECT_EQ(session.output()->names, std::vector<std::string>{"timestamp"}) << "unchanged";
  EXPECT_TRUE(readAccepted(answersTo(session, pauseRequest()).at(0).payload));
  EXPECT_FALSE(session.started());
  answers = answersTo(session, setupOutputsRequest({500, {"actual_q"}}));
  ASSERT_EQ(answers.size(), 1U);
  EXPECT_EQ(session.output()->names, std::vector<std::string>{"actual_q"});
}

}  // namespace
}  // namespace comply::ur
