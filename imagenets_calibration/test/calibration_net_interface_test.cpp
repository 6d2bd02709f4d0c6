// What the calibration node reads of a net of one's own: found through its declared outputs, and
// a net without one is refused naming the file and the output it lacks.
#include "imagenets_calibration/calibration_net_interface.h"

#include <algorithm>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>
#include <unistd.h>

#include "imagenets/package_file.h"

namespace imagenets_calibration {
namespace {

namespace fs = std::filesystem;

// A calibration net built of net ports only (no robot): `plan` and `solve` stand where the
// blocks the node sets are, `samples` repeats sample.yaml.
const char* kTop = R"(
blocks:
  plan: {type: imagenets/SubNetInput, properties: {port: plan, type: imagenets_calibration_msgs/CalibrationPlan}}
  samples: {type: imagenets/SubNet, properties: {net: sample.yaml}}
  solve: {type: imagenets/SubNetInput, properties: {port: solved, type: imagenets_calibration_msgs/CalibrationResult}}
  my_result: {type: imagenets/SubNetOutput, properties: {port: result, type: imagenets_calibration_msgs/CalibrationResult}}
links:
  - solve.value -> my_result.value
)";

const char* kSampleBlocks = R"(
blocks:
  measured: {type: imagenets/SubNetInput, properties: {port: measured, type: imagenets_calibration_msgs/CalibrationSample}}
  grabbed: {type: imagenets/SubNetInput, properties: {port: grabbed, type: sensor_msgs/Image}}
  grabbed_info: {type: imagenets/SubNetInput, properties: {port: grabbed_info, type: sensor_msgs/CameraInfo}}
)";

struct CalibrationNetInterfaceTest : ::testing::Test {
  fs::path dir = fs::temp_directory_path() / ("calib_net_interface_" + std::to_string(::getpid()));
  void SetUp() override { fs::create_directories(dir); }
  void TearDown() override { fs::remove_all(dir); }

  void write(const std::string& name, const std::string& text) { std::ofstream(dir / name) << text; }
  // The interface of the net top.yaml (with sample.yaml); the error message if it is refused.
  std::string check(const std::string& top, const std::string& sample, std::vector<std::string>* cameras = nullptr) {
    write("top.yaml", top);
    write("sample.yaml", sample);
    try {
      imagenets::Executor exec(imagenets::Net::loadFile((dir / "top.yaml").string()));
      const CalibrationNetInterface net(exec);
      if (cameras) *cameras = net.cameras();
      return "";
    } catch (const std::exception& e) {
      return e.what();
    }
  }
};

TEST_F(CalibrationNetInterfaceTest, FindsTheDeclaredOutputsWhateverTheBlocksAreCalled) {
  const std::string sample = std::string(kSampleBlocks) + R"(
  out: {type: imagenets/SubNetOutput, properties: {port: sample, type: imagenets_calibration_msgs/CalibrationSample}}
  picture: {type: imagenets/SubNetOutput, properties: {port: left_image, type: sensor_msgs/Image}}
  picture_info: {type: imagenets/SubNetOutput, properties: {port: left_info, type: sensor_msgs/CameraInfo}}
links:
  - measured.value -> out.value
  - grabbed.value -> picture.value
  - grabbed_info.value -> picture_info.value
)";
  std::vector<std::string> cameras;
  EXPECT_EQ(check(kTop, sample, &cameras), "");
  EXPECT_EQ(cameras, std::vector<std::string>{"left"});
}

TEST_F(CalibrationNetInterfaceTest, ASampleNetWithoutItsSampleIsRefusedNamingTheOutput) {
  const std::string sample = std::string(kSampleBlocks) + R"(
  out: {type: imagenets/SubNetOutput, properties: {port: measurement, type: imagenets_calibration_msgs/CalibrationSample}}
links:
  - measured.value -> out.value
)";
  const std::string error = check(kTop, sample);
  EXPECT_NE(error.find("sample.yaml: no output 'sample' (imagenets_calibration_msgs/CalibrationSample"), std::string::npos)
      << error;
  EXPECT_NE(error.find("its outputs: measurement"), std::string::npos) << error;
}

TEST_F(CalibrationNetInterfaceTest, AnImageWithoutItsCameraInfoIsRefusedNamingTheOutput) {
  const std::string sample = std::string(kSampleBlocks) + R"(
  out: {type: imagenets/SubNetOutput, properties: {port: sample, type: imagenets_calibration_msgs/CalibrationSample}}
  picture: {type: imagenets/SubNetOutput, properties: {port: left_image, type: sensor_msgs/Image}}
links:
  - measured.value -> out.value
  - grabbed.value -> picture.value
)";
  const std::string error = check(kTop, sample);
  EXPECT_NE(error.find("no output 'left_info' (sensor_msgs/CameraInfo: the camera_info of output 'left_image'"),
            std::string::npos)
      << error;
}

TEST_F(CalibrationNetInterfaceTest, ANetWithoutItsResultOrWithAnotherTypeIsRefused) {
  const std::string sample = std::string(kSampleBlocks) + R"(
  out: {type: imagenets/SubNetOutput, properties: {port: sample, type: imagenets_calibration_msgs/CalibrationSample}}
links:
  - measured.value -> out.value
)";
  std::string top = kTop;
  top.replace(top.find("port: result"), 12, "port: answer");
  std::string error = check(top, sample);
  EXPECT_NE(error.find("top.yaml: no output 'result' (imagenets_calibration_msgs/CalibrationResult"), std::string::npos)
      << error;
  top = R"(
blocks:
  plan: {type: imagenets/SubNetInput, properties: {port: plan, type: imagenets_calibration_msgs/CalibrationPlan}}
  samples: {type: imagenets/SubNet, properties: {net: sample.yaml}}
  solve: {type: imagenets/SubNetInput, properties: {port: solved, type: imagenets_calibration_msgs/CalibrationSample}}
  result: {type: imagenets/SubNetOutput, properties: {port: result, type: imagenets_calibration_msgs/CalibrationSample}}
links:
  - solve.value -> result.value
)";
  error = check(top, sample);
  EXPECT_NE(error.find("top.yaml: output 'result' is imagenets_calibration_msgs/CalibrationSample, expected "
                       "imagenets_calibration_msgs/CalibrationResult"),
            std::string::npos)
      << error;
}

// The shipped net: each camera's image processing is its own detection (and what joins them), so
// the node times the two detections as running in parallel.
TEST(CalibrationNetInterface, TheShippedNetsCamerasAreProcessedByTheirOwnDetection) {
  imagenets::Executor exec(imagenets::Net::loadFile(imagenets::packageFile("imagenets_calibration", "config/nets/calibration.yaml")));
  const CalibrationNetInterface net(exec);
  ASSERT_EQ(net.cameras(), (std::vector<std::string>{"left", "right"}));
  auto has = [](const std::vector<std::string>& blocks, const std::string& block) {
    return std::find(blocks.begin(), blocks.end(), block) != blocks.end();
  };
  for (size_t c = 0; c < 2; ++c) {
    const std::string own = net.cameras()[c], other = net.cameras()[1 - c];
    EXPECT_TRUE(has(net.imageBlocks()[c], own + "_detection"));
    EXPECT_TRUE(has(net.imageBlocks()[c], own + "_observation"));
    EXPECT_TRUE(has(net.imageBlocks()[c], "assemble"));
    EXPECT_FALSE(has(net.imageBlocks()[c], other + "_detection"));
    EXPECT_FALSE(has(net.imageBlocks()[c], "grab"));
  }
}

}  // namespace
}  // namespace imagenets_calibration
