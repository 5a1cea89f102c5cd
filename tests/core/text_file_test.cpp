// Input files are read only when they are regular files of bounded size; each refusal names the
// file and why (a device such as /dev/zero used to be read until memory ran out).

#include "comply/core/text_file.hpp"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <fstream>

namespace comply {
namespace {

namespace fs = std::filesystem;

class TextFileTest : public ::testing::Test {
 protected:
  fs::path folder = fs::temp_directory_path() / ("comply_text_file_" + std::to_string(::getpid()));
  void SetUp() override { fs::create_directories(folder); }
  void TearDown() override { fs::remove_all(folder); }
};

TEST_F(TextFileTest, ReadsARegularFileWhole) {
  std::ofstream(folder / "a.yaml") << "key: 1\nother: [2, 3]\n";
  const TextFile file = readTextFile(folder / "a.yaml");
  ASSERT_TRUE(file.ok()) << file.error;
  EXPECT_EQ(file.text, "key: 1\nother: [2, 3]\n");
  std::ofstream(folder / "empty.yaml").close();
  EXPECT_TRUE(readTextFile(folder / "empty.yaml").ok());
}

TEST_F(TextFileTest, RefusesWhatIsNotARegularFileOfBoundedSize) {
  EXPECT_NE(readTextFile(folder / "missing.yaml").error.find("no such file"), std::string::npos);
  EXPECT_NE(readTextFile("/dev/zero").error.find("'/dev/zero' is not a regular file"),
            std::string::npos);
  EXPECT_NE(readTextFile(folder).error.find("is not a regular file"), std::string::npos);
  ASSERT_EQ(::mkfifo((folder / "fifo").c_str(), 0600), 0);
  EXPECT_NE(readTextFile(folder / "fifo").error.find("is not a regular file"), std::string::npos);

  std::ofstream(folder / "big.json") << std::string(3U << 20U, ' ');
  const TextFile big = readTextFile(folder / "big.json", 1U << 20U);
  EXPECT_FALSE(big.ok());
  EXPECT_NE(big.error.find("is 3.0 MB, more than an input file may be (1.0 MB)"), std::string::npos)
      << big.error;
  EXPECT_TRUE(big.text.empty());
  EXPECT_TRUE(readTextFile(folder / "big.json").ok());  // within the default 16 MB
}

// A symlink loop once read "no such file": the refusal names the cause the system gave.
TEST_F(TextFileTest, ASymlinkLoopIsNamedAsOne) {
  fs::create_symlink("loop.yaml", folder / "loop.yaml");
  const TextFile loop = readTextFile(folder / "loop.yaml");
  EXPECT_EQ(loop.error, "cannot read '" + (folder / "loop.yaml").string() +
                            "': too many levels of symbolic links (a symlink loop)");
  fs::create_symlink("b.yaml", folder / "a.yaml");
  fs::create_symlink("a.yaml", folder / "b.yaml");
  EXPECT_NE(readTextFile(folder / "a.yaml").error.find("symlink loop"), std::string::npos);
  // A link to nothing is still a missing file.
  fs::create_symlink("nothing.yaml", folder / "dangling.yaml");
  EXPECT_EQ(readTextFile(folder / "dangling.yaml").error,
            "cannot read '" + (folder / "dangling.yaml").string() + "': no such file");
}

}  // namespace
}  // namespace comply
