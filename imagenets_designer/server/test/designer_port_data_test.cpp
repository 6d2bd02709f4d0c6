// Port values as the protocol's binary frames: clouds as float32 points, disparity images as
// thumbnails and raw floats, scenes and messages as JSON.
#include <cmath>
#include <cstring>

#include <geometry_msgs/TransformStamped.h>
#include <sensor_msgs/Image.h>
#include <sensor_msgs/PointCloud2.h>
#include <sensor_msgs/image_encodings.h>
#include <std_msgs/Float64.h>

#include "designer_test_util.h"
#include "imagenets/executor.h"
#include "port_data.h"

using namespace imagenets;
using namespace imagenets::designer;
using nlohmann::json;

namespace {

struct Frame {
  json header;
  std::string payload;
};

Frame encode(const Value& value, const std::string& mode) {
  Frame f;
  EXPECT_TRUE(decodePortFrame(encodePortFrame(value, mode, {{"port", "b.p"}}), f.header, f.payload));
  return f;
}

}  // namespace

TEST(PortData, FrameIsLengthHeaderPayload) {
  auto number = boost::make_shared<std_msgs::Float64>();
  number->data = 2.5;
  const std::string frame = encodePortFrame(PortType::of<std_msgs::Float64>().wrap<std_msgs::Float64>(number), "preview",
                                            {{"port", "b.p"}});
  uint32_t n = 0;
  std::memcpy(&n, frame.data(), 4);  // little-endian on this machine, as on every browser's
  const json header = json::parse(frame.substr(4, n));
  EXPECT_EQ(header["port"], "b.p");
  EXPECT_EQ(header["format"], "json");
  EXPECT_EQ(header["type"], "std_msgs/Float64");
  EXPECT_EQ(json::parse(frame.substr(4 + n))["data"], 2.5);
  EXPECT_EQ(encode(Value(), "preview").header["format"], "none");
}

TEST(PortData, FramesComeWithXyzRpyAndQuaternion) {
  auto t = boost::make_shared<geometry_msgs::TransformStamped>();
  t->header.frame_id = "base_link";
  t->child_frame_id = "camera";
  t->transform.translation.x = 1;
  t->transform.rotation.z = std::sin(0.25);  // yaw 0.5 rad
  t->transform.rotation.w = std::cos(0.25);
  const json v = json::parse(encode(PortType::of<geometry_msgs::TransformStamped>().wrap<geometry_msgs::TransformStamped>(t), "preview").payload);
  EXPECT_EQ(v["frame_id"], "base_link");
  EXPECT_EQ(v["child_frame_id"], "camera");
  EXPECT_EQ(v["xyz"][0], 1.0);
  EXPECT_NEAR(v["rpy"][2].get<double>(), 0.5, 1e-12);
  EXPECT_NEAR(v["q"][3].get<double>(), std::cos(0.25), 1e-12);
}

TEST(PortData, DisparityImagesAreStretchedForThePreviewAndRawInFull) {
  auto image = boost::make_shared<sensor_msgs::Image>();
  image->width = 512;
  image->height = 2;
  image->encoding = sensor_msgs::image_encodings::TYPE_32FC1;
  image->step = image->width * 4;
  image->data.resize(image->step * image->height);
  float* px = reinterpret_cast<float*>(image->data.data());
  for (int i = 0; i < 1024; ++i) px[i] = i % 512 == 0 ? NAN : 10.0f + static_cast<float>(i % 512);
  const Value value = PortType::of<sensor_msgs::Image>().wrap<sensor_msgs::Image>(image);
  const Frame preview = encode(value, "preview");
  EXPECT_EQ(preview.header["format"], "pixels");
  EXPECT_EQ(preview.header["preview_width"], 256);
  EXPECT_EQ(preview.header["channels"], 1);
  // Stretched over the finite values: the NaN and the smallest show black, the largest white.
  ASSERT_EQ(preview.payload.size(), 256u * 1u);
  EXPECT_EQ(static_cast<unsigned char>(preview.payload[0]), 0);
  EXPECT_GE(static_cast<unsigned char>(preview.payload[255]), 254);
  EXPECT_EQ(preview.header["encoding"], "32FC1");
  const Frame full = encode(value, "full");
  EXPECT_EQ(full.header["format"], "raw");
  EXPECT_EQ(full.header["step"], 2048);
  ASSERT_EQ(full.payload.size(), image->data.size());
  float second;
  std::memcpy(&second, full.payload.data() + 4, 4);
  EXPECT_EQ(second, 11.0f);
}

TEST(PortData, PrinterOutputBecomesNestedJson) {
  const json j = printedMessageToJson(
      "header: \n  seq: 3\n  frame_id: cam\nfound: 1\nname: \npoints[]\n  points[0]: \n    x: 1.5\n    y: 2\n"
      "  points[1]: \n    x: 3\n    y: nan\nvalues[]\n  values[0]: 4\n");
  EXPECT_EQ(j["header"]["seq"], 3);
  EXPECT_EQ(j["header"]["frame_id"], "cam");
  EXPECT_EQ(j["name"], "");
  ASSERT_EQ(j["points"].size(), 2u);
  EXPECT_EQ(j["points"][0]["x"], 1.5);
  EXPECT_TRUE(j["points"][1]["y"].is_null());
  EXPECT_EQ(j["values"], json::array({4}));
}

TEST_F(DesignerTest, PointCloudsComeAsFloat32PointsAndScenesAsMarkers) {
  start(kSourceDir + "/config/nets/scene_3d.yaml");
  DesignerClient& c = connect();
  const json run = c.request({{"op", "run"}});
  ASSERT_TRUE(run["failed"].empty()) << run.dump();
  expectOk(c.request({{"op", "watch"}, {"ports", {"downsample.cloud", "scene.markers", "camera_mount.frame"}}}));
  const DesignerClient::Message cloud = c.waitForFrame("downsample.cloud", "preview");
  EXPECT_EQ(cloud.json["format"], "xyzrgb");
  const size_t points = cloud.json["points"];
  EXPECT_GT(points, 100u);
  ASSERT_EQ(cloud.payload.size(), 16 * points);
  float z;
  std::memcpy(&z, cloud.payload.data() + 8, 4);
  EXPECT_GT(z, 1.0f);  // in front of the camera (the synthetic scene is 1.5 to 3 m away)
  EXPECT_LT(z, 3.5f);

  const json scene = json::parse(c.waitForFrame("scene.markers", "preview").payload);
  ASSERT_FALSE(scene["markers"].empty());
  bool has_points = false;
  for (const auto& m : scene["markers"]) has_points |= m["points"].size() > 100;
  EXPECT_TRUE(has_points);
  const json frame = json::parse(c.waitForFrame("camera_mount.frame", "preview").payload);
  EXPECT_EQ(frame["child_frame_id"], "left_camera_optical");
  EXPECT_NEAR(frame["xyz"][2].get<double>(), 1.2, 1e-9);
}
