// The calibration's robust marker detection, the net config/nets/calibration_marker_detection.yaml
// (the engine's generic feedback twice: the region around the prediction, widened to the whole
// image when needed; in it, through the sub-net calibration_marker_search.yaml, Otsu first,
// good-enough stop, coarse-to-fine sweep), on the simulator's renderings of the calibration views,
// clean and with reflections: it finds the marker where it is, as accurately as the calibration
// needs, and its traces show the method's path.
#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include <imagenets/MarkerDetection.h>
#include <opencv2/imgproc.hpp>
#include <sensor_msgs/Image.h>

#include "calibration_views.h"
#include "imagenets_calibration/calibration_marker_net.h"
#include "imagenets/blocks/image.h"
#include "imagenets/executor.h"
#include "imagenets/net.h"

using namespace imagenets_calibration;

namespace {

const CalibrationViews& views() {
  static const CalibrationViews data = renderCalibrationViews();
  return data;
}

sensor_msgs::ImageConstPtr message(const CalibrationView& v) {
  return imagenets::blocks::toImageMsg(v.image, "mono8", v.info.header);
}

void expectSame(const MarkerObservation& a, const MarkerObservation& b, const std::string& what) {
  ASSERT_EQ(a.found, b.found) << what << ": " << a.reason << " / " << b.reason;
  if (!a.found) return;
  EXPECT_EQ(a.threshold, b.threshold) << what;
  EXPECT_EQ(a.confidence, b.confidence) << what;
  EXPECT_EQ(a.reprojection_error, b.reprojection_error) << what;
  ASSERT_EQ(a.points.size(), b.points.size()) << what;
  for (size_t i = 0; i < a.points.size(); ++i) EXPECT_NEAR((a.points[i] - b.points[i]).norm(), 0.0, 1e-9) << what;
  EXPECT_NEAR((a.pose.translation() - b.pose.translation()).norm(), 0.0, 1e-9) << what;
}

}  // namespace

TEST(CalibrationMarkerNet, FindsTheMarkerWhereItIsOtsuFirstAndStopsWhenGood) {
  const auto& data = views();
  CalibrationMarkerNet net;
  std::map<std::string, int> stops;
  int clean = 0, clean_found = 0, reflected = 0, swept = 0;
  double worst_mm = 0, worst_deg = 0;
  for (size_t i = 0; i < data.views.size(); ++i) {
    const CalibrationView& v = data.views[i];
    const std::string what = "view " + std::to_string(i) + (v.reflection ? " (reflection)" : "");
    const MarkerObservation o = net.detect(message(v), v.info, v.predicted);
    // The region around the prediction holds the marker: the whole image is searched only when
    // the marker was not found there, which only a reflection over it may cause.
    const auto region = net.lastRegionTrace();
    ASSERT_TRUE(region) << what;
    if (o.found && !v.reflection) EXPECT_EQ(region->values, std::vector<double>{120}) << what;
    if (!o.found) EXPECT_EQ(region->values, (std::vector<double>{120, 0})) << what;
    if (!o.found) {
      EXPECT_TRUE(v.reflection) << what << ": " << o.reason;  // only reflections may hide it
      continue;
    }
    const auto trace = net.lastTrace();
    ASSERT_TRUE(trace) << what;
    ASSERT_FALSE(trace->values.empty()) << what;
    ++stops[trace->stop_reason];
    // The search starts at the region's Otsu threshold (feedback `initial`)...
    const auto crop = net.executor().output<sensor_msgs::Image>("region.image");
    ASSERT_TRUE(crop) << what;
    cv::Mat pixels(crop->height, crop->width, CV_8UC1, const_cast<uint8_t*>(crop->data.data()), crop->step), ignored;
    EXPECT_EQ(trace->values.front(), cv::threshold(pixels, ignored, 0, 255, cv::THRESH_BINARY | cv::THRESH_OTSU)) << what;
    // ...and a good first detection ends it there (`good_enough`), else the sweep runs.
    if (trace->stop_reason == "good_enough") {
      EXPECT_GE(trace->chosen_score, 0.5) << what;
    } else {
      EXPECT_GT(trace->trials, 1u) << what;
      ++swept;
    }
    EXPECT_EQ(o.threshold, trace->chosen_value) << what;
    EXPECT_EQ(o.points.size(), 8u) << what;
    EXPECT_LE(o.reprojection_error, 1.0) << what;
    if (v.reflection) {
      // A reflection may bend the border, but what is found is the marker, not some other dark
      // quadrilateral the search stopped at (the calibration's gates reject a few millimetres;
      // a wrong object would be metres off).
      EXPECT_LT((o.pose.translation() - v.truth.translation()).norm(), 0.02) << what;
      ++reflected;
      continue;
    }
    ++clean;
    ASSERT_TRUE(o.found) << what << ": " << o.reason;
    clean_found += o.found;
    // Accuracy against the true marker pose (the simulator's truth), in the camera frame.
    worst_mm = std::max(worst_mm, (o.pose.translation() - v.truth.translation()).norm() * 1000);
    worst_deg = std::max(worst_deg, angleBetween(o.pose, v.truth) * 180 / M_PI);
  }
  // Both ways through the method were exercised: stopped at a good first guess, and swept.
  EXPECT_GT(stops["good_enough"], 0);
  EXPECT_GT(swept, 0);
  EXPECT_EQ(clean_found, clean);
  EXPECT_GT(reflected, 5);
  // A clean detection is within a few tenths of a millimetre and of a degree of the truth at
  // 0.6 m (0.15 mm / 0.05 deg seen).
  EXPECT_LT(worst_mm, 0.5);
  EXPECT_LT(worst_deg, 0.2);
  std::printf("clean views: worst %.3f mm / %.3f deg from the truth\n", worst_mm, worst_deg);
}

TEST(CalibrationMarkerNet, ParallelTrialsChooseTheSameAsSequentialOnes) {
  const auto& data = views();
  CalibrationMarkerNet sequential, parallel(CalibrationMarkerNet::specWithSearch([](imagenets::NetSpec& search) {
                                              for (auto& b : search.blocks) {
                                                if (b.feedback) b.feedback->parallel = true;
                                              }
                                            }),
                                            2);
  for (size_t i = 0; i < data.views.size(); i += 3) {
    const CalibrationView& v = data.views[i];
    const auto image = message(v);
    expectSame(sequential.detect(image, v.info, v.predicted), parallel.detect(image, v.info, v.predicted),
               "view " + std::to_string(i));
    ASSERT_EQ(!sequential.lastTrace(), !parallel.lastTrace());
    if (!sequential.lastTrace()) continue;
    EXPECT_EQ(sequential.lastTrace()->values, parallel.lastTrace()->values);
    EXPECT_EQ(sequential.lastTrace()->stop_reason, parallel.lastTrace()->stop_reason);
  }
}

TEST(CalibrationMarkerNet, WithoutAPredictionTheWholeImageIsSearched) {
  const auto& data = views();
  CalibrationMarkerNet net;
  for (size_t i : {0u, 7u}) {
    const CalibrationView& v = data.views[i];
    const MarkerObservation o = net.detect(message(v), v.info, std::nullopt);
    ASSERT_TRUE(o.found) << "view " << i << ": " << o.reason;
    EXPECT_LT((o.pose.translation() - v.truth.translation()).norm(), 0.001) << "view " << i;
    // The points are full-image pixels either way: the same marker as with the region of interest.
    const MarkerObservation in_region = net.detect(message(v), v.info, v.predicted);
    ASSERT_TRUE(in_region.found);
    EXPECT_LT((o.points[0] - in_region.points[0]).norm(), 0.5) << "view " << i;
  }
}

TEST(CalibrationMarkerNet, AMarkerFarFromThePredictionIsFoundInTheWholeImage) {
  // Before the first calibration the nominal model can be centimetres off (a robot with large
  // head-mount errors): the region around the prediction misses the marker, the whole image not.
  const auto& data = views();
  CalibrationMarkerNet net;
  for (size_t i : {0u, 5u}) {
    const CalibrationView& v = data.views[i];
    // 0.25 m sideways at 0.6 m: ~580 px, towards the wider side of the image, so that the marker
    // lies outside the first region (120 px around the 140 px marker) but the region not wholly
    // outside the image.
    Eigen::Isometry3d off = v.predicted;
    off.translation().x() += v.truth.translation().x() < 0 ? 0.25 : -0.25;
    const MarkerObservation o = net.detect(message(v), v.info, off);
    ASSERT_TRUE(o.found) << "view " << i << ": " << o.reason;
    EXPECT_LT((o.pose.translation() - v.truth.translation()).norm(), 0.001) << "view " << i;
    const auto region = net.lastRegionTrace();
    ASSERT_TRUE(region);
    EXPECT_EQ(region->values, (std::vector<double>{120, 0})) << "view " << i;
    EXPECT_EQ(region->chosen_value, 0) << "view " << i;
    EXPECT_TRUE(std::isnan(region->scores.front())) << "view " << i << ": the margin 120 px region held a marker";
  }
}

TEST(CalibrationMarkerNet, TheMarkerFileIsTheDetectorsProperty) {
  // The detector sits in the threshold-search sub-net: an unreadable marker file is an error when
  // the net is loaded, naming the block and the file (not a marker that is never found).
  try {
    CalibrationMarkerNet net(CalibrationMarkerNet::specWithSearch([](imagenets::NetSpec& search) {
                               for (auto& b : search.blocks) {
                                 for (auto& p : b.properties) {
                                   if (b.name == "detector" && p.name == "marker") p.text = "/nonexistent/marker.yaml";
                                 }
                               }
                             }),
                             1);
    FAIL() << "no error";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("block 'search'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("block 'detector'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("/nonexistent/marker.yaml"), std::string::npos) << e.what();
  }
}

TEST(CalibrationMarkerNet, UnusableInputIsANamedError) {
  CalibrationMarkerNet net;
  const auto& v = views().views[0];
  sensor_msgs::CameraInfo small = v.info;
  small.width = 640;
  try {
    net.detect(message(v), small, v.predicted);
    FAIL() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("block 'region'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("1024x768"), std::string::npos) << e.what();
  }
}
