// Robot folders resolve by name or path, and a malformed robot.yaml gives a named error.

#include "comply/model/robot_description.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "comply/model/model_error.hpp"
#include "comply/model/update.hpp"
#include "robot_sampling.hpp"

namespace comply::model {
namespace {

namespace fs = std::filesystem;

class TempRobotFolder {
 public:
  TempRobotFolder()
      : folder_(fs::temp_directory_path() / ("comply_robot_" + std::to_string(::getpid()))) {
    fs::create_directories(folder_ / "twolink");
  }
  ~TempRobotFolder() { fs::remove_all(folder_); }
  [[nodiscard]] fs::path robot() const { return folder_ / "twolink"; }
  [[nodiscard]] const fs::path& parent() const { return folder_; }

  void write(const std::string& file, const std::string& text) const {
    std::ofstream(robot() / file) << text;
  }

 private:
  fs::path folder_;
};

const char* kTwoLinkUrdf = R"(<robot name="twolink"><link name="base"/>
  <link name="a"><inertial><mass value="1"/><inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial></link>
  <link name="b"><inertial><mass value="1"/><inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial></link>
  <link name="flange"/>
  <joint name="j1" type="revolute"><parent link="base"/><child link="a"/><axis xyz="0 0 1"/><limit lower="-1" upper="1" velocity="1" effort="10"/></joint>
  <joint name="j2" type="revolute"><parent link="a"/><child link="b"/><origin xyz="0 0 0.5"/><axis xyz="0 1 0"/><limit lower="-1" upper="1" velocity="1" effort="10"/></joint>
  <joint name="f" type="fixed"><parent link="b"/><child link="flange"/><origin xyz="0 0 0.5"/></joint>
</robot>)";

const char* kTwoLinkYaml = R"(name: twolink
urdf: twolink.urdf
joints: [j1, j2]
base_frame: base
flange_frame: flange
tcp_frame: flange
home: [0.1, 0.2]
)";

TEST(RobotDescriptionTest, ShippedRobotsLoadByName) {
  const auto names = availableRobots();
  for (const auto& name : testing::shippedRobots()) {
    EXPECT_NE(std::find(names.begin(), names.end(), name), names.end()) << name;
    const RobotDescription robot = loadRobotDescription(name);
    const Model model = robot.loadModel();
    EXPECT_EQ(model.dof(), static_cast<int>(robot.joints.size()));
    EXPECT_EQ(model.jointNames(), robot.joints);
    Data data(model);
    ASSERT_EQ(update(model, data, robot.home, {}, Quantity::kPose), UpdateStatus::kOk) << name;
  }
}

TEST(RobotDescriptionTest, FolderPathAndSearchPathBothWork) {
  TempRobotFolder folder;
  folder.write("twolink.urdf", kTwoLinkUrdf);
  folder.write("robot.yaml", kTwoLinkYaml);

  const RobotDescription by_path = loadRobotDescription(folder.robot().string());
  EXPECT_EQ(by_path.name, "twolink");
  EXPECT_EQ(by_path.home, (std::vector<double>{0.1, 0.2}));
  EXPECT_FALSE(by_path.friction.has_value());
  EXPECT_EQ(by_path.loadModel().dof(), 2);

  ::setenv("COMPLY_ROBOT_PATH", folder.parent().c_str(), 1);
  const RobotDescription by_name = loadRobotDescription("twolink");
  ::unsetenv("COMPLY_ROBOT_PATH");
  EXPECT_EQ(by_name.urdf_path, by_path.urdf_path);
}

TEST(RobotDescriptionTest, UrdfTextReplacesTheFolderUrdf) {
  // A ROS 2 robot_description arrives as text: the model follows it, not the folder's file.
  TempRobotFolder folder;
  folder.write("twolink.urdf", kTwoLinkUrdf);
  folder.write("robot.yaml", kTwoLinkYaml);
  RobotDescription robot = loadRobotDescription(folder.robot().string());
  std::string longer(kTwoLinkUrdf);
  const std::string flange_origin = R"(<child link="flange"/><origin xyz="0 0 0.5"/>)";
  longer.replace(longer.find(flange_origin), flange_origin.size(),
                 R"(<child link="flange"/><origin xyz="0 0 0.8"/>)");
  robot.urdf_xml = longer;
  robot.urdf_path = folder.robot() / "missing.urdf";
  const Model model = robot.loadModel();
  Data data(model);
  const std::vector<double> zero{0.0, 0.0};
  ASSERT_EQ(update(model, data, zero, zero, Quantity::kPose), UpdateStatus::kOk);
  EXPECT_NEAR(data.tip_position.z(), 1.3, 1e-12);  // 0.5 + 0.8 from the text
  robot.urdf_xml.clear();
  EXPECT_THROW((void)robot.loadModel(), ModelError);  // back to the (missing) file
}

TEST(RobotDescriptionTest, UnknownRobotListsTheAvailableOnes) {
  try {
    loadRobotDescription("robot_that_does_not_exist");
    FAIL();
  } catch (const ModelError& error) {
    EXPECT_EQ(error.code(), ModelErrc::kUnknownRobot);
    EXPECT_NE(std::string(error.what()).find("fr3"), std::string::npos) << error.what();
  }
  EXPECT_THROW(loadRobotDescription("/no/such/folder"), ModelError);
}

TEST(RobotDescriptionTest, MalformedFilesAreNamed) {
  TempRobotFolder folder;
  folder.write("twolink.urdf", kTwoLinkUrdf);
  const std::vector<std::pair<std::string, std::string>> cases{
      {"joints: [j1, j2]\n", "'name'"},
      {std::string(kTwoLinkYaml) +
           "friction: {model: sigmoid, phi1: [1], phi2: [1, 2], phi3: [0, 0]}\n",
       "phi1"},
      {std::string(kTwoLinkYaml)
           .replace(std::string(kTwoLinkYaml).find("home: [0.1, 0.2]"), 16, "home: [0.1]"),
       "home"},
      {"name: [unbalanced\n", "YAML"},
  };
  for (const auto& [yaml, fragment] : cases) {
    folder.write("robot.yaml", yaml);
    try {
      loadRobotDescription(folder.robot().string());
      FAIL() << "accepted: " << yaml;
    } catch (const ModelError& error) {
      EXPECT_EQ(error.code(), ModelErrc::kInvalidDescription) << error.what();
      EXPECT_NE(std::string(error.what()).find(fragment), std::string::npos) << error.what();
      EXPECT_NE(std::string(error.what()).find("robot.yaml"), std::string::npos) << error.what();
    }
  }
}

}  // namespace
}  // namespace comply::model
