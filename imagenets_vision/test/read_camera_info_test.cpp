#include "imagenets/vision/read_camera_info.h"

#include <fstream>

#include <boost/filesystem.hpp>
#include <gtest/gtest.h>

namespace {

std::string writeFile(const std::string& name, const std::string& text) {
  const auto path = boost::filesystem::temp_directory_path() / (std::to_string(getpid()) + "_" + name);
  std::ofstream(path.string()) << text;
  return path.string();
}

std::string errorOf(const std::string& path) {
  try {
    imagenets::readCameraInfo(path);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

const char* kHead = "image_width: 640\nimage_height: 480\ncamera_name: cam\ndistortion_model: plumb_bob\n";
const char* kRest =
    "distortion_coefficients: {rows: 1, cols: 5, data: [0, 0, 0, 0, 0]}\n"
    "rectification_matrix: {rows: 3, cols: 3, data: [1, 0, 0, 0, 1, 0, 0, 0, 1]}\n"
    "projection_matrix: {rows: 3, cols: 4, data: [500, 0, 320, 0, 0, 500, 240, 0, 0, 0, 1, 0]}\n";

}  // namespace

TEST(ReadCameraInfo, ReadsAWellFormedFile) {
  const std::string path = writeFile("good.yaml", std::string(kHead) +
                                                      "camera_matrix: {rows: 3, cols: 3, data: [500, 0, 320, 0, 500, 240, 0, 0, 1]}\n" +
                                                      kRest);
  std::string name;
  const auto info = imagenets::readCameraInfo(path, &name);
  EXPECT_EQ(info.width, 640u);
  EXPECT_DOUBLE_EQ(info.K[0], 500);
  EXPECT_EQ(name, "cam");
}

// Each of these made camera_calibration_parsers fail an assert (abort) before: found by fuzzing.
TEST(ReadCameraInfo, AMatrixThatDoesNotFitItsDataIsNamedNotAborted) {
  std::string path = writeFile("rows.yaml", std::string(kHead) +
                                                "camera_matrix: {rows: 2, cols: 3, data: [500, 0, 320, 0, 500, 240, 0, 0, 1]}\n" +
                                                kRest);
  std::string error = errorOf(path);
  EXPECT_NE(error.find(path), std::string::npos) << error;
  EXPECT_NE(error.find("'camera_matrix' is 2x3, expected 3x3"), std::string::npos) << error;

  path = writeFile("count.yaml", std::string(kHead) + "camera_matrix: {rows: 3, cols: 3, data: [500, 0, 320]}\n" + kRest);
  error = errorOf(path);
  EXPECT_NE(error.find("'camera_matrix': 3x3 needs 9 numbers, 'data' has 3"), std::string::npos) << error;

  path = writeFile("nan.yaml", std::string(kHead) +
                                   "camera_matrix: {rows: 3, cols: 3, data: [500, 0, x, 0, 500, 240, 0, 0, 1]}\n" + kRest);
  error = errorOf(path);
  EXPECT_NE(error.find("'camera_matrix': 'data' holds 'x', not a number"), std::string::npos) << error;
}
