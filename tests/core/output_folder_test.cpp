// Where comply writes: a file's folder must exist, and an output folder is made only as its last
// folder. A missing folder is named, with the command that would make it, and nothing is made.

#include "comply/core/output_folder.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <fstream>
#include <stdexcept>

namespace comply {
namespace {

namespace fs = std::filesystem;

class OutputFolderTest : public ::testing::Test {
 protected:
  fs::path folder =
      fs::temp_directory_path() / ("comply_output_folder_" + std::to_string(::getpid()));
  void SetUp() override { fs::create_directories(folder); }
  void TearDown() override { fs::remove_all(folder); }

  /// makeOutputFolder(path)'s error, "" when it made or found the folder.
  static std::string makeError(const fs::path& path) {
    try {
      makeOutputFolder(path);
    } catch (const std::runtime_error& error) {
      return error.what();
    }
    return {};
  }
};

TEST_F(OutputFolderTest, AFileInAnExistingFolderIsAccepted) {
  EXPECT_EQ(missingFolderOf(folder / "run.mcap"), "");
  EXPECT_EQ(missingFolderOf("run.mcap"), "");  // the working folder
}

TEST_F(OutputFolderTest, AFileInAMissingFolderNamesItAndMakesNothing) {
  const fs::path missing = folder / "a" / "b";
  EXPECT_EQ(missingFolderOf(missing / "run.mcap"),
            "the folder '" + missing.string() + "' does not exist (create it first: mkdir -p '" +
                missing.string() + "')");
  EXPECT_FALSE(fs::exists(folder / "a"));
  std::ofstream(folder / "file") << "x";
  EXPECT_EQ(missingFolderOf(folder / "file" / "run.mcap"),
            "'" + (folder / "file").string() + "' is not a folder");
}

TEST_F(OutputFolderTest, MakesTheLastFolderOnly) {
  EXPECT_TRUE(makeOutputFolder(folder / "out"));
  EXPECT_TRUE(fs::is_directory(folder / "out"));
  EXPECT_FALSE(makeOutputFolder(folder / "out"));  // there already
  EXPECT_TRUE(makeOutputFolder((folder / "slash").string() + "/"));
  EXPECT_TRUE(fs::is_directory(folder / "slash"));

  const std::string error = makeError(folder / "a" / "b" / "out");
  EXPECT_EQ(error, "cannot make the output folder '" + (folder / "a" / "b" / "out").string() +
                       "': the folder '" + (folder / "a" / "b").string() +
                       "' does not exist (create it first: mkdir -p '" +
                       (folder / "a" / "b").string() + "')");
  EXPECT_FALSE(fs::exists(folder / "a"));
}

TEST_F(OutputFolderTest, AFileWhereTheFolderShouldBeIsRefused) {
  std::ofstream(folder / "taken") << "x";
  EXPECT_NE(makeError(folder / "taken").find("it is a file, not a folder"), std::string::npos);
  EXPECT_TRUE(fs::is_regular_file(folder / "taken"));
}

}  // namespace
}  // namespace comply
