// Target files (config/targets/), their bad-input errors, and the AprilTag / ChArUco detection on
// rendered prints whose true pose is known.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>

#include <boost/filesystem.hpp>

#include "imagenets/vision/apriltag_marker.h"
#include "imagenets/vision/marker_scene.h"
#include "imagenets/vision/target.h"

using namespace imagenets;
using target::TargetDescription;
using target::TargetDetection;
using target::TargetError;

namespace {

const double kDeg = M_PI / 180.0;

render::CameraModel friendCamera(bool strong_distortion = false) {
  render::CameraModel cam;
  cam.width = 1024;
  cam.height = 768;
  cam.K = cv::Matx33d(1400, 0, 515.2, 0, 1400, 381.6, 0, 0, 1);
  cam.D = strong_distortion ? std::vector<double>{-0.25, 0.12, 0.0, 0.0, 0.0}
                            : std::vector<double>{-0.082, 0.124, 0.00042, -0.00031, 0.0};
  return cam;
}

// A target file written for one test; removed with the object.
struct TempTarget {
  std::string path;
  explicit TempTarget(const std::string& yaml) {
    path = (boost::filesystem::temp_directory_path() / boost::filesystem::unique_path("target-%%%%%%.yaml")).string();
    std::ofstream(path) << yaml;
  }
  ~TempTarget() { std::remove(path.c_str()); }
};

// The error message of loading `yaml`, or "" when it loads.
std::string loadError(const std::string& yaml, std::string* file = nullptr) {
  TempTarget t(yaml);
  if (file) *file = t.path;
  try {
    TargetDescription::load(t.path);
  } catch (const TargetError& e) {
    return e.what();
  }
  return "";
}

struct Rendered {
  cv::Mat image;
  Eigen::Isometry3d truth;
};

Rendered renderTarget(const render::CameraModel& cam, const TargetDescription& t, double distance, double pan_deg,
                double tilt_deg, double blur = 0.7, double noise = 2.0, std::uint64_t seed = 5) {
  render::Plane plane = t.plane(Eigen::Isometry3d::Identity());
  marker::applyPrintReflectance(&plane);
  marker::ViewSettings view;
  view.distance = distance;
  view.pan = pan_deg * kDeg;
  view.tilt = tilt_deg * kDeg;
  view.blur = blur;
  view.noise = noise;
  view.seed = seed;
  Rendered r;
  r.image = marker::renderView(*marker::sharedRenderer(cam, 3), plane, view, &r.truth);
  return r;
}

// RMS distance (px) of the detected points from where the truth projects the corners of their ids.
double cornerErrorPx(const render::CameraModel& cam, const TargetDescription& t, const TargetDetection& d,
                     const Eigen::Isometry3d& truth) {
  const auto corners = t.corners();
  double sq = 0;
  for (size_t i = 0; i < d.ids.size(); ++i) {
    const cv::Point2d p = cam.project(truth * corners.at(d.ids[i]));
    sq += std::pow(cv::norm(p - d.points[i]), 2);
  }
  return d.ids.empty() ? 1e9 : std::sqrt(sq / d.ids.size());
}

double mm(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) { return 1000 * (a.translation() - b.translation()).norm(); }
double deg(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) { return marker::rotationAngle(a, b) / kDeg; }

}  // namespace

TEST(TargetDescription, TheShippedTargetsLoadWithTheirCorners) {
  const TargetDescription square = TargetDescription::load("config/targets/gripper_square_marker.yaml");
  EXPECT_EQ(square.typeName(), "square_marker");
  EXPECT_EQ(square.corners().size(), 8u);
  EXPECT_NEAR(square.corners().at(1).x(), 0.03, 1e-12);  // outer top-right
  EXPECT_NEAR(square.corners().at(1).y(), 0.03, 1e-12);

  const TargetDescription tag = TargetDescription::load("config/targets/apriltag_36h11_60mm.yaml");
  EXPECT_EQ(tag.typeName(), "apriltag");
  EXPECT_EQ(tag.tag_cells, 8);
  ASSERT_EQ(tag.corners().size(), 4u);
  EXPECT_NEAR(tag.corners().at(0).x(), -0.03, 1e-12);  // id 0, top-left
  EXPECT_NEAR(tag.corners().at(0).y(), 0.03, 1e-12);

  const TargetDescription grid = TargetDescription::load("config/targets/aprilgrid_36h11_4x3.yaml");
  EXPECT_EQ(grid.corners().size(), 48u);
  EXPECT_NEAR(grid.patternWidth(), 4 * 0.03 + 3 * 0.009, 1e-12);
  // Tag 0 is the bottom-left one, tag 11 the top-right one.
  EXPECT_LT(grid.corners().at(4 * 0 + 3).x(), -0.07);
  EXPECT_LT(grid.corners().at(4 * 0 + 3).y(), -0.05);
  EXPECT_GT(grid.corners().at(4 * 11 + 1).x(), 0.07);
  EXPECT_GT(grid.corners().at(4 * 11 + 1).y(), 0.05);

  const TargetDescription board = TargetDescription::load("config/targets/charuco_5x7_5x5_100.yaml");
  EXPECT_EQ(board.corners().size(), 4u * 6u);
  // Corner 0 at the top left (OpenCV's), one square in from the board's corner; ids along x first.
  EXPECT_NEAR(board.corners().at(0).x(), -0.075 + 0.03, 1e-6);
  EXPECT_NEAR(board.corners().at(0).y(), 0.105 - 0.03, 1e-6);
  EXPECT_NEAR(board.corners().at(1).x(), -0.075 + 0.06, 1e-6);
  EXPECT_NEAR(board.corners().at(4).y(), 0.105 - 0.06, 1e-6);
}

TEST(TargetDescription, BadInputNamesTheFileAndTheKey) {
  std::string file;
  std::string e = loadError("type: apriltag\nfamily: tag99h1\nid: 0\nsize: 0.06\n", &file);
  EXPECT_NE(e.find(file), std::string::npos) << e;
  EXPECT_NE(e.find("'family'"), std::string::npos) << e;
  EXPECT_NE(e.find("tag36h11"), std::string::npos) << e;  // the known families

  e = loadError("type: apriltag\nfamily: tag16h5\nid: 30\nsize: 0.06\n", &file);
  EXPECT_NE(e.find(file + ": 'id'"), std::string::npos) << e;
  EXPECT_NE(e.find("0..29"), std::string::npos) << e;

  e = loadError("type: apriltag\nfamily: tag36h11\nid: 580\nsize: 0.03\nrows: 3\ncols: 4\nspacing: 0.01\n");
  EXPECT_NE(e.find("'id': the grid's ids 580..591 out of range"), std::string::npos) << e;

  e = loadError("type: apriltag\nfamily: tag36h11\nid: 0\nsize: 0.03\nrows: 2\ncols: 2\nspacing: 0.001\n");
  EXPECT_NE(e.find("'spacing'"), std::string::npos) << e;

  e = loadError("type: apriltag\nfamily: tag36h11\nid: 0\nsize: 0.06\ncolour: red\n", &file);
  EXPECT_NE(e.find(file + ": 'colour': unknown key for type 'apriltag'"), std::string::npos) << e;

  e = loadError("type: apriltag\nfamily: tag36h11\nsize: 0.06\n");
  EXPECT_NE(e.find("'id': missing"), std::string::npos) << e;

  e = loadError("type: apriltag\nfamily: tag36h11\nid: 0\nsize: sixty\n");
  EXPECT_NE(e.find("'size': 'sixty' is not a number"), std::string::npos) << e;

  e = loadError("type: charuco\ndictionary: DICT_9X9_50\nsquares_x: 5\nsquares_y: 7\nsquare_size: 0.03\nmarker_size: 0.02\n");
  EXPECT_NE(e.find("'dictionary'"), std::string::npos) << e;
  EXPECT_NE(e.find("DICT_5X5_100"), std::string::npos) << e;

  e = loadError("type: charuco\ndictionary: DICT_5X5_100\nsquares_x: 5\nsquares_y: 7\nsquare_size: 0.03\nmarker_size: 0.03\n");
  EXPECT_NE(e.find("'marker_size': 0.03 m does not fit in its square"), std::string::npos) << e;

  e = loadError("type: charuco\ndictionary: DICT_5X5_100\nsquares_x: 5\nsquares_y: 7\nsquare_size: 0.03\n"
                "marker_size: 0.022\nwidth: 0.14\nheight: 0.3\n");
  EXPECT_NE(e.find("'width': 0.14 m is smaller than its 5 squares"), std::string::npos) << e;

  e = loadError("type: charuco\ndictionary: DICT_4X4_50\nsquares_x: 11\nsquares_y: 11\nsquare_size: 0.03\nmarker_size: 0.02\n");
  EXPECT_NE(e.find("'dictionary': DICT_4X4_50 has 50 markers, the 11 x 11 board needs 60"), std::string::npos) << e;

  e = loadError("type: qr_code\n");
  EXPECT_NE(e.find("'type': 'qr_code' is not a target type (square_marker, apriltag, charuco)"), std::string::npos) << e;

  e = loadError("type: square_marker\nmarker: no_such_marker.yaml\n");
  EXPECT_NE(e.find("'marker'"), std::string::npos) << e;

  e = loadError("- a list\n");
  EXPECT_NE(e.find("a target file is a YAML map"), std::string::npos) << e;
  EXPECT_THROW(TargetDescription::load("no/such/target.yaml"), TargetError);
}

TEST(TargetDetection, ASingleTagIsFoundWithItsCornersAndPoseThroughLensDistortion) {
  const render::CameraModel cam = friendCamera(true);
  const TargetDescription tag = TargetDescription::load("config/targets/apriltag_36h11_60mm.yaml");
  for (double pan : {20.0, 140.0, 260.0}) {
    const Rendered r = renderTarget(cam, tag, 0.6, pan, 35);
    const TargetDetection d = target::detectTarget(r.image, cam, tag);
    ASSERT_TRUE(d.found) << d.reason;
    ASSERT_EQ(d.ids, (std::vector<int>{0, 1, 2, 3}));
    EXPECT_EQ(d.tags, 1);
    EXPECT_LT(cornerErrorPx(cam, tag, d, r.truth), 0.15) << "pan " << pan;
    EXPECT_LT(mm(d.pose, r.truth), 0.6) << "pan " << pan;
    EXPECT_LT(deg(d.pose, r.truth), 0.3) << "pan " << pan;
    EXPECT_LT(d.reprojection_error, 0.2);
  }
}

TEST(TargetDetection, OurEdgeFitLocatesTheTagsCornersBetterThanLibapriltag) {
  const render::CameraModel cam = friendCamera();
  const TargetDescription tag = TargetDescription::load("config/targets/apriltag_36h11_60mm.yaml");
  double refined = 0, own = 0;
  int views = 0;
  for (double pan : {0.0, 70.0, 150.0, 230.0, 310.0}) {
    for (double tilt : {0.0, 30.0, 55.0}) {
      const Rendered r = renderTarget(cam, tag, 0.6, pan, tilt, 1.0, 2.0, static_cast<std::uint64_t>(pan + tilt));
      target::TargetDetectorOptions options;
      const TargetDetection a = target::detectTarget(r.image, cam, tag, options);
      options.refine_edges = false;
      const TargetDetection b = target::detectTarget(r.image, cam, tag, options);
      ASSERT_TRUE(a.found && b.found) << "pan " << pan << " tilt " << tilt;
      refined += cornerErrorPx(cam, tag, a, r.truth);
      own += cornerErrorPx(cam, tag, b, r.truth);
      ++views;
    }
  }
  std::printf("mean corner error over %d views: libapriltag %.3f px, refined %.3f px\n", views, own / views, refined / views);
  EXPECT_LT(refined, 0.5 * own);
}

TEST(TargetDetection, AnAprilGridGivesEveryTagsCornersAndOtherIdsAreIgnored) {
  const render::CameraModel cam = friendCamera();
  const TargetDescription grid = TargetDescription::load("config/targets/aprilgrid_36h11_4x3.yaml");
  const Rendered r = renderTarget(cam, grid, 0.5, 200, 25);
  const TargetDetection d = target::detectTarget(r.image, cam, grid);
  ASSERT_TRUE(d.found) << d.reason;
  EXPECT_EQ(d.tags, 12);
  EXPECT_EQ(d.ids.size(), 48u);
  EXPECT_LT(cornerErrorPx(cam, grid, d, r.truth), 0.2);
  EXPECT_LT(mm(d.pose, r.truth), 0.5);
  EXPECT_LT(deg(d.pose, r.truth), 0.1);

  // A grid whose ids start elsewhere finds none of these tags.
  TempTarget other("type: apriltag\nfamily: tag36h11\nid: 100\nrows: 3\ncols: 4\nsize: 0.03\nspacing: 0.009\n");
  const TargetDetection none = target::detectTarget(r.image, cam, TargetDescription::load(other.path));
  EXPECT_FALSE(none.found);
  EXPECT_NE(none.reason.find("100..111"), std::string::npos) << none.reason;
}

TEST(TargetDetection, OtherFamiliesToo) {
  const render::CameraModel cam = friendCamera();
  for (const char* family : {"tag25h9", "tag16h5", "tagStandard41h12", "tagCircle21h7"}) {
    TempTarget file(std::string("type: apriltag\nfamily: ") + family + "\nid: 3\nsize: 0.05\n");
    const TargetDescription tag = TargetDescription::load(file.path);
    const Rendered r = renderTarget(cam, tag, 0.5, 100, 20);
    const TargetDetection d = target::detectTarget(r.image, cam, tag);
    ASSERT_TRUE(d.found) << family << ": " << d.reason;
    EXPECT_EQ(d.ids.front(), 12) << family;
    // Families whose code ring is outside the border (tagStandard41h12, tagCircle21h7) keep
    // libapriltag's corners (our edge fit wants a dark square on a bright surround): 0.71 px here.
    const bool reversed = std::string(family) == "tagStandard41h12" || std::string(family) == "tagCircle21h7";
    EXPECT_LT(cornerErrorPx(cam, tag, d, r.truth), reversed ? 0.8 : 0.5) << family;
    EXPECT_LT(mm(d.pose, r.truth), 2.0) << family;
  }
}

TEST(TargetDetection, AChArUcoBoardGivesItsChessboardCornersAtTheirIds) {
  const render::CameraModel cam = friendCamera(true);
  const TargetDescription board = TargetDescription::load("config/targets/charuco_5x7_5x5_100.yaml");
  for (double pan : {10.0, 120.0, 250.0}) {
    const Rendered r = renderTarget(cam, board, 0.55, pan, 30);
    const TargetDetection d = target::detectTarget(r.image, cam, board);
    ASSERT_TRUE(d.found) << d.reason;
    EXPECT_EQ(d.ids.size(), 24u) << "pan " << pan;
    EXPECT_GE(d.tags, 15);
    // aruco's corners, moved to the camera model's pixel centres, are 0.02-0.06 px RMS off the
    // renderer's truth (0.7 px uncorrected: aruco counts from a pixel's corner).
    EXPECT_LT(cornerErrorPx(cam, board, d, r.truth), 0.15) << "pan " << pan;
    EXPECT_LT(mm(d.pose, r.truth), 0.1) << "pan " << pan;
    EXPECT_LT(deg(d.pose, r.truth), 0.06) << "pan " << pan;
  }
  // An even number of rows too: found with every corner at its id.
  TempTarget even("type: charuco\ndictionary: DICT_4X4_50\nsquares_x: 6\nsquares_y: 4\nsquare_size: 0.03\nmarker_size: 0.02\n");
  const TargetDescription b2 = TargetDescription::load(even.path);
  const Rendered r = renderTarget(cam, b2, 0.5, 30, 20);
  const TargetDetection d = target::detectTarget(r.image, cam, b2);
  ASSERT_TRUE(d.found) << d.reason;
  EXPECT_EQ(d.ids.size(), 15u);
  EXPECT_LT(cornerErrorPx(cam, b2, d, r.truth), 0.15);
}

TEST(TargetDetection, AChArUcoBoardsCornersAreLocatedClearOfItsMarkers) {
  // Upright boards at 0.6-1.0 m, where the white margin round the markers is 5-9 px wide: aruco's
  // own refinement window reaches into the markers' edges there (0.133 px RMS over these views; in
  // the calibration rostest, 0.2 mm of error on the head's fixed point), ours stays clear of them.
  const render::CameraModel cam = friendCamera();
  const TargetDescription board = TargetDescription::load("config/targets/charuco_5x7_5x5_100.yaml");
  Eigen::Vector3d mean_error = Eigen::Vector3d::Zero();
  double mean_corner_px = 0;
  int views = 0;
  for (double distance : {0.6, 0.8, 1.0}) {
    for (double pan : {0.0, 90.0, 180.0}) {
      for (double tilt : {0.0, 12.0}) {
        const Rendered r = renderTarget(cam, board, distance, pan, tilt, 0.7, 2.0, static_cast<std::uint64_t>(11 + views));
        const TargetDetection d = target::detectTarget(r.image, cam, board);
        ASSERT_TRUE(d.found) << d.reason;
        mean_error += r.truth.inverse() * d.pose.translation();  // the found origin in the true board frame
        mean_corner_px += cornerErrorPx(cam, board, d, r.truth);
        ++views;
      }
    }
  }
  mean_error /= views;
  mean_corner_px /= views;
  std::printf("ChArUco, %d upright views at 0.6-1.0 m: mean pose error (board frame) %.4f %.4f %.4f mm, "
              "corner RMS %.3f px\n", views, 1000 * mean_error.x(), 1000 * mean_error.y(), 1000 * mean_error.z(),
              mean_corner_px);
  EXPECT_LT(mean_corner_px, 0.115);
  EXPECT_LT(1000 * mean_error.norm(), 0.06);
}

TEST(TargetDetection, ASquareMarkerTargetIsNotDetectedHereAndABadImageIsRefused) {
  const render::CameraModel cam = friendCamera();
  const TargetDescription square = TargetDescription::load("config/targets/gripper_square_marker.yaml");
  const TargetDescription tag = TargetDescription::load("config/targets/apriltag_36h11_60mm.yaml");
  const cv::Mat gray(cam.height, cam.width, CV_8UC1, cv::Scalar(128));
  EXPECT_THROW(target::detectTarget(gray, cam, square), std::invalid_argument);
  EXPECT_THROW(target::detectTarget(cv::Mat(10, 10, CV_8UC1), cam, tag), std::invalid_argument);
  const TargetDetection nothing = target::detectTarget(gray, cam, tag);
  EXPECT_FALSE(nothing.found);
  EXPECT_NE(nothing.reason.find("no tag of tag36h11 with id 0 found"), std::string::npos) << nothing.reason;
}
