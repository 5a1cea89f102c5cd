// Images, PNG files and headless rendering of a small MJCF scene (a red box on a grey floor).
// Rendering runs on whatever EGL offers; on a machine without a GPU that is Mesa's llvmpipe.

#include <gtest/gtest.h>
#include <mujoco/mujoco.h>
#include <unistd.h>

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <memory>
#include <string>

#include "comply/sim/image.hpp"
#include "comply/sim/renderer.hpp"
#include "comply/sim/sim_cameras.hpp"
#include "comply/sim/sim_error.hpp"
#include "comply/sim/viewer.hpp"
#include "scratch.hpp"

namespace comply::sim {
namespace {

namespace fs = std::filesystem;

using Rgb = std::array<std::uint8_t, 3>;

Rgb pixel(const Image& image, int x, int y) {
  const std::size_t at = (static_cast<std::size_t>(y) * image.width + x) * 3;
  return {image.rgb[at], image.rgb[at + 1], image.rgb[at + 2]};
}

Image filled(int width, int height, Rgb colour) {
  Image image{width, height, {}};
  for (int i = 0; i < width * height; ++i) {
    image.rgb.insert(image.rgb.end(), colour.begin(), colour.end());
  }
  return image;
}

/// Every pixel different from its neighbours: a PNG filter or a row offset that goes wrong shows.
Image gradientImage(int width, int height) {
  Image image{width, height, {}};
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      image.rgb.push_back(static_cast<std::uint8_t>(x * 7));
      image.rgb.push_back(static_cast<std::uint8_t>(y * 11));
      image.rgb.push_back(static_cast<std::uint8_t>((x * y) % 256));
    }
  }
  return image;
}

// ---- images and PNG ------------------------------------------------------------------------

TEST(Png, RoundTripKeepsEveryByte) {
  // Odd width: rows of 3 * 37 bytes are not 4-byte aligned.
  const Image gradient = gradientImage(37, 23);
  const testing::ScratchDir folder("render_test");
  const fs::path file = folder.path() / "gradient.png";
  writePng(gradient, file);
  const Image read = readPng(file);
  EXPECT_EQ(read.width, gradient.width);
  EXPECT_EQ(read.height, gradient.height);
  EXPECT_EQ(read.rgb, gradient.rgb);
}

TEST(Png, InMemoryRoundTripKeepsEveryByteAndIsTheFilesFormat) {
  const Image gradient = gradientImage(38, 24);
  const std::vector<std::uint8_t> fast = encodePng(gradient, 1);
  const std::vector<std::uint8_t> small = encodePng(gradient, 9);
  EXPECT_EQ(decodePng(fast).rgb, gradient.rgb);
  EXPECT_EQ(decodePng(small).rgb, gradient.rgb);
  EXPECT_LE(small.size(), fast.size());
  // The bytes are a PNG file: readPng takes them from the disk.
  const testing::ScratchDir folder("render_test");
  const fs::path file = folder.path() / "memory.png";
  {
    std::FILE* out = std::fopen(file.c_str(), "wb");
    ASSERT_NE(out, nullptr);
    ASSERT_EQ(std::fwrite(fast.data(), 1, fast.size(), out), fast.size());
    std::fclose(out);
  }
  EXPECT_EQ(readPng(file).rgb, gradient.rgb);
}

TEST(Png, DecodingCutBytesThrowsAndAnEmptyImageIsRefused) {
  std::vector<std::uint8_t> bytes = encodePng(filled(8, 6, {10, 20, 30}));
  bytes.resize(bytes.size() / 2);
  EXPECT_THROW((void)decodePng(bytes), SimError);
  EXPECT_THROW((void)decodePng(std::vector<std::uint8_t>{1, 2, 3}), SimError);
  EXPECT_THROW((void)encodePng(Image{}), SimError);
}

TEST(Png, WriteIntoMissingFolderNamesTheFile) {
  const testing::ScratchDir folder("render_test");
  const fs::path file = folder.path() / "no_such_folder" / "out.png";
  try {
    writePng(filled(4, 4, {1, 2, 3}), file);
    FAIL() << "writePng into a missing folder did not throw";
  } catch (const SimError& error) {
    EXPECT_NE(std::string(error.what()).find(file.string()), std::string::npos) << error.what();
  }
}

TEST(Png, ReadingSomethingElseThrowsNamingTheFile) {
  const testing::ScratchDir folder("render_test");
  const fs::path file = folder.path() / "not_a.png";
  {
    std::FILE* out = std::fopen(file.c_str(), "wb");
    ASSERT_NE(out, nullptr);
    std::fputs("this is text, not a PNG file", out);
    std::fclose(out);
  }
  try {
    (void)readPng(file);
    FAIL() << "readPng of a text file did not throw";
  } catch (const SimError& error) {
    EXPECT_NE(std::string(error.what()).find(file.string()), std::string::npos) << error.what();
  }
}

TEST(Png, GrayFileIsReadAsRgb) {
  // A 3 x 2 8-bit grayscale PNG: rows {0, 128, 255} and {10, 20, 30}.
  const unsigned char gray_png[] = {
      0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a, 0x00, 0x00, 0x00, 0x0d, 0x49, 0x48, 0x44,
      0x52, 0x00, 0x00, 0x00, 0x03, 0x00, 0x00, 0x00, 0x02, 0x08, 0x00, 0x00, 0x00, 0x00, 0xb8,
      0x1f, 0x39, 0xc6, 0x00, 0x00, 0x00, 0x10, 0x49, 0x44, 0x41, 0x54, 0x78, 0x9c, 0x63, 0x60,
      0x68, 0xf8, 0xcf, 0xc0, 0x25, 0x22, 0x07, 0x00, 0x08, 0x67, 0x01, 0xbc, 0x9c, 0x67, 0x35,
      0xa0, 0x00, 0x00, 0x00, 0x00, 0x49, 0x45, 0x4e, 0x44, 0xae, 0x42, 0x60, 0x82};
  const testing::ScratchDir folder("render_test");
  const fs::path file = folder.path() / "gray.png";
  {
    std::FILE* out = std::fopen(file.c_str(), "wb");
    ASSERT_NE(out, nullptr);
    ASSERT_EQ(std::fwrite(gray_png, 1, sizeof gray_png, out), sizeof gray_png);
    std::fclose(out);
  }
  const Image image = readPng(file);
  ASSERT_EQ(image.width, 3);
  ASSERT_EQ(image.height, 2);
  EXPECT_EQ(pixel(image, 1, 0), (Rgb{128, 128, 128}));
  EXPECT_EQ(pixel(image, 2, 0), (Rgb{255, 255, 255}));
  EXPECT_EQ(pixel(image, 2, 1), (Rgb{30, 30, 30}));
}

TEST(Image, SideBySideAlignsTopAndPadsWithBackground) {
  const Rgb red{255, 0, 0};
  const Rgb blue{0, 0, 255};
  const Rgb background{10, 20, 30};
  const Image joined = sideBySide({filled(10, 4, red), filled(6, 8, blue)}, 2, background);
  ASSERT_EQ(joined.width, 18);
  ASSERT_EQ(joined.height, 8);
  ASSERT_EQ(joined.rgb.size(), 18u * 8u * 3u);
  EXPECT_EQ(pixel(joined, 0, 0), red);
  EXPECT_EQ(pixel(joined, 9, 3), red);
  EXPECT_EQ(pixel(joined, 10, 0), background);  // the gap
  EXPECT_EQ(pixel(joined, 11, 7), background);
  EXPECT_EQ(pixel(joined, 12, 0), blue);
  EXPECT_EQ(pixel(joined, 12, 7), blue);
  EXPECT_EQ(pixel(joined, 17, 7), blue);
  EXPECT_EQ(pixel(joined, 0, 4), background);  // below the short red image
  EXPECT_EQ(pixel(joined, 9, 7), background);
}

TEST(Image, FractionDifferentCountsPixelsBeyondTolerance) {
  Image image = filled(10, 10, {100, 100, 100});
  image.rgb[0] = 110;          // pixel 0: beyond a tolerance of 8
  image.rgb[3 * 5 + 2] = 105;  // pixel 5: within it
  EXPECT_DOUBLE_EQ(fractionDifferentFrom(image, {100, 100, 100}, 8), 0.01);
  EXPECT_DOUBLE_EQ(fractionDifferentFrom(image, {100, 100, 100}, 0), 0.02);
  EXPECT_DOUBLE_EQ(fractionDifferentFrom(image, {0, 0, 0}), 1.0);
}

// ---- rendering -----------------------------------------------------------------------------

constexpr const char* kSceneXml = R"(
<mujoco model="render_test">
  <visual><global offwidth="640" offheight="480"/></visual>
  <worldbody>
    <light pos="0 0 3" dir="0 0 -1" directional="true"/>
    <light pos="0 -3 2" dir="0 1 -0.5" directional="true" castshadow="false"/>
    <geom name="floor" type="plane" size="2 2 0.1" rgba="0.6 0.6 0.6 1"/>
    <body name="box" pos="0 0 0.1">
      <freejoint/>
      <geom type="box" size="0.1 0.1 0.1" rgba="1 0 0 1"/>
    </body>
  </worldbody>
</mujoco>
)";

struct ModelDeleter {
  void operator()(mjModel* model) const { mj_deleteModel(model); }
};
struct DataDeleter {
  void operator()(mjData* data) const { mj_deleteData(data); }
};

std::unique_ptr<mjModel, ModelDeleter> loadModel(const std::string& xml) {
  // mjVFS holds 2000 file names of 1000 characters: far too big for the stack.
  auto vfs = std::make_unique<mjVFS>();
  mj_defaultVFS(vfs.get());
  if (mj_makeEmptyFileVFS(vfs.get(), "scene.xml", static_cast<int>(xml.size())) != 0) {
    throw std::runtime_error("mj_makeEmptyFileVFS failed");
  }
  std::memcpy(vfs->filedata[mj_findFileVFS(vfs.get(), "scene.xml")], xml.data(), xml.size());
  char error[1000] = "";
  mjModel* model = mj_loadXML("scene.xml", vfs.get(), error, sizeof error);
  mj_deleteVFS(vfs.get());
  if (model == nullptr) {
    throw std::runtime_error(std::string("mj_loadXML: ") + error);
  }
  return std::unique_ptr<mjModel, ModelDeleter>(model);
}

class RenderTest : public ::testing::Test {
 protected:
  RenderTest() : model_(loadModel(kSceneXml)), data_(mj_makeData(model_.get())) {
    mj_forward(model_.get(), data_.get());
  }

  void moveBox(double dx) {
    data_->qpos[0] += dx;  // free joint: x, y, z, then the quaternion
    mj_forward(model_.get(), data_.get());
  }

  static CameraView view() {
    CameraView camera;
    camera.lookat[0] = 0.0;
    camera.lookat[1] = 0.0;
    camera.lookat[2] = 0.1;
    camera.distance_m = 1.5;
    camera.azimuth_deg = 90.0;  // looking along +y: a box moved along x moves sideways
    camera.elevation_deg = -30.0;
    return camera;
  }

  std::unique_ptr<mjModel, ModelDeleter> model_;
  std::unique_ptr<mjData, DataDeleter> data_;
};

bool stronglyRed(Rgb p) {
  return p[0] > 150 && p[1] < 100 && p[2] < 100;
}

/// Number of strongly red pixels and the mean x of them (the box's column in the image).
std::pair<int, double> redPixels(const Image& image) {
  int count = 0;
  double x_sum = 0.0;
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      if (stronglyRed(pixel(image, x, y))) {
        ++count;
        x_sum += x;
      }
    }
  }
  return {count, count > 0 ? x_sum / count : -1.0};
}

TEST_F(RenderTest, DrawsTheBoxOnTheFloorRightSideUp) {
  Renderer renderer(*model_, 320, 240);
  EXPECT_EQ(renderer.width(), 320);
  EXPECT_EQ(renderer.height(), 240);
  const Image image = renderer.render(*data_, view());
  ASSERT_EQ(image.width, 320);
  ASSERT_EQ(image.height, 240);
  ASSERT_EQ(image.rgb.size(), 320u * 240u * 3u);

  // Above the horizon there is only the clear colour (no skybox in this scene).
  const Rgb sky = pixel(image, 0, 0);
  EXPECT_EQ(pixel(image, 319, 0), sky);
  EXPECT_GT(fractionDifferentFrom(image, sky), 0.05);
  // Rows top to bottom: the floor, not the sky, fills the bottom row.
  EXPECT_NE(pixel(image, 0, 239), sky);
  EXPECT_NE(pixel(image, 160, 239), sky);

  const auto [red, red_x] = redPixels(image);
  EXPECT_GT(red, 500) << "the red box should cover a few percent of the image";
  EXPECT_NEAR(red_x, 160.0, 20.0) << "the box is at the look-at point, mid image";
}

TEST_F(RenderTest, MovingTheBoxMovesItInTheImage) {
  Renderer renderer(*model_, 320, 240);
  const Image before = renderer.render(*data_, view());
  moveBox(0.3);
  const Image after = renderer.render(*data_, view());

  int changed = 0;
  for (std::size_t i = 0; i < before.rgb.size(); i += 3) {
    changed += std::memcmp(&before.rgb[i], &after.rgb[i], 3) != 0 ? 1 : 0;
  }
  EXPECT_GT(changed, 500);
  const double shift = redPixels(after).second - redPixels(before).second;
  EXPECT_GT(std::abs(shift), 30.0) << "box column moved by " << shift << " px";
}

TEST_F(RenderTest, SameStateRendersTheSameImage) {
  Renderer renderer(*model_, 320, 240);
  const Image first = renderer.render(*data_, view());
  const Image second = renderer.render(*data_, view());
  EXPECT_EQ(first.rgb, second.rgb);
}

TEST_F(RenderTest, SeveralRenderersTakeTurnsAndComeBackAfterTheLastIsGone) {
  Image reference;
  {
    Renderer small(*model_, 320, 240);
    Renderer large(*model_, 640, 480);
    reference = small.render(*data_, view());
    const Image big = large.render(*data_, view());
    EXPECT_EQ(big.width, 640);
    EXPECT_GT(redPixels(big).first, 3 * redPixels(reference).first);
    EXPECT_EQ(small.render(*data_, view()).rgb, reference.rgb);
  }
  // Both gone: the shared EGL display was terminated and must come back for a new Renderer.
  Renderer again(*model_, 320, 240);
  EXPECT_EQ(again.render(*data_, view()).rgb, reference.rgb);
}

TEST_F(RenderTest, ACameraAtAPoseSeesWhatMujocosFreeCameraSees) {
  // The pose the free camera's angles give (scenePose, worked out here, not by MuJoCo), rendered
  // by placing the scene's camera: the same picture as MuJoCo's own free camera, up to the
  // float rounding of the camera's frame (a few edge pixels).
  Renderer renderer(*model_, 320, 240);
  for (const double azimuth : {90.0, 135.0, -40.0}) {
    CameraView from = view();
    from.azimuth_deg = azimuth;
    const Image by_mujoco = renderer.render(*data_, from);
    const Image by_pose = renderer.render(*data_, scenePose(from, model_->vis.global.fovy));
    int differing = 0;
    for (std::size_t i = 0; i < by_mujoco.rgb.size(); i += 3) {
      differing += std::abs(by_mujoco.rgb[i] - by_pose.rgb[i]) > 8 ? 1 : 0;
    }
    EXPECT_LT(differing, 320 * 240 / 200) << "azimuth " << azimuth;
    EXPECT_GT(redPixels(by_pose).first, 500) << "azimuth " << azimuth;
  }
}

TEST_F(RenderTest, RebindRendersAnotherCompilationOfTheSceneAndRefusesAnotherScene) {
  auto renderer = std::make_unique<Renderer>(*model_, 160, 120);
  const Image before = renderer->render(*data_, view());
  // The model it was made for goes (as a reset's old plant does) before the new one is bound.
  auto rebuilt = loadModel(kSceneXml);
  std::unique_ptr<mjData, DataDeleter> rebuilt_data(mj_makeData(rebuilt.get()));
  mj_forward(rebuilt.get(), rebuilt_data.get());
  data_.reset();
  model_.reset();
  renderer->rebind(*rebuilt);
  EXPECT_EQ(renderer->render(*rebuilt_data, view()).rgb, before.rgb);

  std::string other(kSceneXml);
  other.replace(other.find("<body name=\"box\""), 0,
                "<geom type=\"sphere\" size=\"0.05\" pos=\"1 1 0.05\"/>");
  const auto other_model = loadModel(other);
  EXPECT_THROW(renderer->rebind(*other_model), SimError);
  EXPECT_EQ(renderer->render(*rebuilt_data, view()).rgb, before.rgb) << "a refused rebind keeps";
}

TEST_F(RenderTest, ShadowsAndReflectionsCanBeTurnedOff) {
  // A slanted light that casts the box's shadow beside it, and a floor that mirrors.
  std::string xml(kSceneXml);
  const std::string overhead = "<light pos=\"0 0 3\" dir=\"0 0 -1\"";
  xml.replace(xml.find(overhead), overhead.size(), "<light pos=\"-2 0 2\" dir=\"1 0 -1\"");
  xml.replace(xml.find("<worldbody>"), 0,
              "<asset><material name=\"mirror\" reflectance=\"0.6\"/></asset>");
  xml.replace(xml.find("rgba=\"0.6 0.6 0.6 1\""), 0, "material=\"mirror\" ");
  const auto model = loadModel(xml);
  std::unique_ptr<mjData, DataDeleter> data(mj_makeData(model.get()));
  mj_forward(model.get(), data.get());
  Renderer renderer(*model, 160, 120);
  const auto changed = [](const Image& a, const Image& b) {
    int count = 0;
    for (std::size_t i = 0; i < a.rgb.size(); ++i) {
      count += std::abs(a.rgb[i] - b.rgb[i]) > 8 ? 1 : 0;
    }
    return count;
  };
  const Image both = renderer.render(*data, view());
  renderer.setShadows(false);
  const Image no_shadow = renderer.render(*data, view());
  renderer.setReflections(false);
  const Image neither = renderer.render(*data, view());
  EXPECT_GT(changed(both, no_shadow), 100) << "the box's shadow on the floor is gone";
  EXPECT_GT(changed(no_shadow, neither), 100) << "the box's mirror image is gone";
  EXPECT_GT(redPixels(neither).first, 100);
  renderer.setShadows(true);
  renderer.setReflections(true);
  EXPECT_EQ(renderer.render(*data, view()).rgb, both.rgb);
}

TEST_F(RenderTest, AWiderFieldOfViewShowsTheBoxSmaller) {
  Renderer renderer(*model_, 320, 240);
  const int narrow = redPixels(renderer.render(*data_, scenePose(view(), 30.0))).first;
  const int wide = redPixels(renderer.render(*data_, scenePose(view(), 60.0))).first;
  // Image size goes as 1 / tan(fovy / 2): (tan 30 / tan 15)^2 = 4.6 times the area.
  EXPECT_NEAR(static_cast<double>(narrow) / wide, 4.65, 0.6);
}

TEST(CameraPoses, ATcpCameraLooksAlongItsOpticalAxisWithImageUpAgainstItsY) {
  Eigen::Isometry3d world_from_tcp = Eigen::Isometry3d::Identity();
  world_from_tcp.translation() = Eigen::Vector3d(0.5, 0.1, 0.3);
  // A TCP pointing down (its z along world -z), as an arm at home holds its tool.
  world_from_tcp.linear() = Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitX()).toRotationMatrix();
  Eigen::Isometry3d tcp_from_camera = Eigen::Isometry3d::Identity();
  tcp_from_camera.translation() = Eigen::Vector3d(0.0, 0.07, -0.10);
  const CameraPose pose = tcpPose(world_from_tcp, tcp_from_camera, 50.0);
  const Eigen::Vector3d position(pose.position[0], pose.position[1], pose.position[2]);
  EXPECT_TRUE(position.isApprox(Eigen::Vector3d(0.5, 0.1 - 0.07, 0.3 + 0.10), 1e-12));
  EXPECT_TRUE(Eigen::Vector3d(pose.forward[0], pose.forward[1], pose.forward[2])
                  .isApprox(Eigen::Vector3d(0, 0, -1), 1e-12));
  // Optical y (image down) is the TCP's y, world -y: image up is world +y.
  EXPECT_TRUE(Eigen::Vector3d(pose.up[0], pose.up[1], pose.up[2])
                  .isApprox(Eigen::Vector3d(0, 1, 0), 1e-12));
  EXPECT_EQ(pose.fovy_deg, 50.0);
}

TEST(CameraPoses, SpecsThatCannotBeRenderedAreRefusedNamingTheCamera) {
  const auto refused = [](const std::vector<CameraSpec>& specs, const std::string& words) {
    try {
      checkCameraSpecs(specs);
      ADD_FAILURE() << "accepted; expected: " << words;
    } catch (const SimError& error) {
      EXPECT_NE(std::string(error.what()).find(words), std::string::npos) << error.what();
    }
  };
  CameraSpec good;
  good.name = "front";
  EXPECT_NO_THROW(checkCameraSpecs({good}));
  CameraSpec odd = good;
  odd.width_px = 127;
  refused({odd}, "camera 'front': 127 x 96 pixels");
  refused({good, good}, "camera 'front' is named twice");
  CameraSpec unnamed = good;
  unnamed.name.clear();
  refused({unnamed}, "needs a name");
  CameraSpec flat = good;
  flat.fovy_deg = 180.0;
  refused({flat}, "fovy");
}

TEST_F(RenderTest, OddWidthKeepsRowsAligned) {
  Renderer renderer(*model_, 317, 240);
  const Image image = renderer.render(*data_, view());
  ASSERT_EQ(image.rgb.size(), 317u * 240u * 3u);
  // Padded rows would shear the picture: the sky would no longer be uniform along the top row.
  const Rgb sky = pixel(image, 0, 0);
  for (int x = 0; x < image.width; ++x) {
    ASSERT_EQ(pixel(image, x, 0), sky) << "x = " << x;
  }
  EXPECT_NEAR(redPixels(image).second, 158.0, 20.0);
}

TEST_F(RenderTest, ImageLargerThanOffscreenBufferThrowsNamingOffwidth) {
  try {
    Renderer renderer(*model_, 800, 240);
    FAIL() << "a Renderer wider than offwidth was created";
  } catch (const SimError& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("offwidth"), std::string::npos) << message;
    EXPECT_NE(message.find("640"), std::string::npos) << message;
    EXPECT_NE(message.find("800"), std::string::npos) << message;
  }
}

// ---- viewer --------------------------------------------------------------------------------

TEST(Viewer, WithoutDisplayThrowsSayingSo) {
  ::unsetenv("DISPLAY");
  ::unsetenv("WAYLAND_DISPLAY");
  EXPECT_FALSE(Viewer::displayAvailable());
  const auto model = loadModel(kSceneXml);
  try {
    Viewer viewer(*model, "render_test", CameraView{});
    FAIL() << "a Viewer was created without a display";
  } catch (const SimError& error) {
    EXPECT_NE(std::string(error.what()).find("display"), std::string::npos) << error.what();
  }
}

}  // namespace
}  // namespace comply::sim
