// The committed output of `comply schema` (docs/command-schema.md, msg/*.msg) must be what the
// generator prints now, so that the docs and the messages cannot drift from the tables. After a
// table change: build/apps/comply/comply schema > docs/command-schema.md, and likewise
// --format msg --kind cartesian|joint for msg/.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "comply/schema/describe.hpp"
#include "text_file.hpp"

namespace comply::schema {
namespace {

const std::filesystem::path kSourceDir = COMPLY_SOURCE_DIR;

std::string contents(const std::filesystem::path& file) {
  return comply::testing::textOf(file);
}

TEST(SchemaGeneratedFiles, MarkdownIsUpToDate) {
  EXPECT_EQ(contents(kSourceDir / "docs" / "command-schema.md"), markdownDocument())
      << "regenerate with: comply schema > docs/command-schema.md";
}

TEST(SchemaGeneratedFiles, RosMessagesAreUpToDate) {
  EXPECT_EQ(contents(kSourceDir / "msg" / "CartesianCommand.msg"),
            rosMessage(CommandKind::kCartesian))
      << "regenerate with: comply schema --format msg --kind cartesian";
  EXPECT_EQ(contents(kSourceDir / "msg" / "JointCommand.msg"), rosMessage(CommandKind::kJoint))
      << "regenerate with: comply schema --format msg --kind joint";
}

TEST(SchemaGeneratedFiles, JsonListsEveryFieldInTableOrder) {
  const nlohmann::json both = nlohmann::json::parse(jsonDescription());
  ASSERT_EQ(both["cartesian"].size(), fields(CommandKind::kCartesian).size());
  EXPECT_EQ(both["cartesian"][1]["name"], "orientation");
  EXPECT_EQ(both["cartesian"][1]["constraint"], "unit_quaternion");
  EXPECT_EQ(both["cartesian"][8]["values"], nlohmann::json({"absolute", "ratio"}));
  EXPECT_EQ(both["joint"][0]["role"], "seed_joint_position");
}

}  // namespace
}  // namespace comply::schema
