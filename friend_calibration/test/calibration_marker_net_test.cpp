// The calibration's hand-written robust detection (marker_measurement.cpp) and the net that
// declares the same method with the engine's generic feedback (config/nets/calibration_marker_detection.yaml)
// agree exactly on the simulator's renderings, clean and with reflections: same threshold chosen,
// same corners to 1e-9 px.
#include <gtest/gtest.h>

#include <map>

#include "calibration_views.h"
#include "friend_calibration/calibration_marker_net.h"
#include "friend_calibration/marker_measurement.h"
#include "imagenets/blocks/image.h"
#include "imagenets/net.h"

using namespace friend_calibration;

namespace {

const CalibrationViews& views() {
  static const CalibrationViews data = renderCalibrationViews();
  return data;
}

void expectSame(const MarkerObservation& hand, const MarkerObservation& net, const std::string& what) {
  ASSERT_EQ(hand.found, net.found) << what << ": " << hand.reason << " / " << net.reason;
  if (!hand.found) return;
  EXPECT_EQ(hand.threshold, net.threshold) << what;
  EXPECT_EQ(hand.confidence, net.confidence) << what;
  EXPECT_EQ(hand.reprojection_error, net.reprojection_error) << what;
  ASSERT_EQ(hand.points.size(), 8u) << what;
  ASSERT_EQ(net.points.size(), 8u) << what;
  for (size_t i = 0; i < 8; ++i) {
    EXPECT_NEAR(hand.points[i].x(), net.points[i].x(), 1e-9) << what << " point " << i;
    EXPECT_NEAR(hand.points[i].y(), net.points[i].y(), 1e-9) << what << " point " << i;
  }
  EXPECT_NEAR((hand.pose.translation() - net.pose.translation()).norm(), 0.0, 1e-9) << what;
  EXPECT_NEAR(angleBetween(hand.pose, net.pose), 0.0, 1e-7) << what;
}

}  // namespace

TEST(CalibrationMarkerNet, ReproducesTheHandWrittenDetectionOnCleanAndReflectedViews) {
  const auto& data = views();
  CalibrationMarkerNet net;
  std::map<std::string, int> stops;
  int clean_found = 0, clean = 0, reflected = 0;
  for (size_t i = 0; i < data.views.size(); ++i) {
    const CalibrationView& v = data.views[i];
    const std::string what = "view " + std::to_string(i) + (v.reflection ? " (reflection)" : "");
    const MarkerObservation hand = detectMarkerRobustly(v.image, v.info, data.marker, v.predicted);
    const MarkerObservation by_net =
        net.detect(imagenets::blocks::toImageMsg(v.image, "mono8", v.info.header), v.info, v.predicted);
    expectSame(hand, by_net, what);
    const auto trace = net.lastTrace();
    ASSERT_TRUE(trace) << what;
    ++stops[trace->stop_reason];
    // The search starts at the region's Otsu threshold (feedback `initial`).
    ASSERT_FALSE(trace->values.empty());
    if (!v.reflection) {
      ++clean;
      clean_found += by_net.found;
    }
    reflected += v.reflection;
  }
  // Both ways through the method were exercised: stopped at a good first guess, and swept.
  EXPECT_GT(stops["good_enough"], 0);
  EXPECT_GT(stops["finished"] + stops["all_tried"], 0);
  EXPECT_EQ(clean_found, clean);
  EXPECT_GT(reflected, 5);
}

TEST(CalibrationMarkerNet, ParallelTrialsChooseTheSameAsSequentialOnes) {
  const auto& data = views();
  imagenets::NetSpec spec = imagenets::parseNetFile(CalibrationMarkerNet::defaultNetPath());
  for (auto& b : spec.blocks) {
    if (b.feedback) b.feedback->parallel = true;
  }
  CalibrationMarkerNet sequential, parallel(spec, 2);
  for (size_t i = 0; i < data.views.size(); i += 3) {
    const CalibrationView& v = data.views[i];
    const auto image = imagenets::blocks::toImageMsg(v.image, "mono8", v.info.header);
    expectSame(sequential.detect(image, v.info, v.predicted), parallel.detect(image, v.info, v.predicted),
               "view " + std::to_string(i));
    EXPECT_EQ(sequential.lastTrace()->values, parallel.lastTrace()->values);
    EXPECT_EQ(sequential.lastTrace()->stop_reason, parallel.lastTrace()->stop_reason);
  }
}

TEST(CalibrationMarkerNet, WithoutAPredictionBothSearchTheWholeImage) {
  const auto& data = views();
  CalibrationMarkerNet net;
  for (size_t i : {0u, 7u}) {
    const CalibrationView& v = data.views[i];
    expectSame(detectMarkerRobustly(v.image, v.info, data.marker, std::nullopt),
               net.detect(imagenets::blocks::toImageMsg(v.image, "mono8", v.info.header), v.info, std::nullopt),
               "view " + std::to_string(i) + " without prediction");
  }
}

TEST(CalibrationMarkerNet, UnusableInputIsANamedError) {
  CalibrationMarkerNet net;
  const auto& v = views().views[0];
  sensor_msgs::CameraInfo small = v.info;
  small.width = 640;
  try {
    net.detect(imagenets::blocks::toImageMsg(v.image, "mono8", v.info.header), small, v.predicted);
    FAIL() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("block 'region'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("1024x768"), std::string::npos) << e.what();
  }
}
