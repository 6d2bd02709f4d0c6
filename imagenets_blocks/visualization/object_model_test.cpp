#include <gtest/gtest.h>
#include <visualization_msgs/Marker.h>

#include "../frames/frame_test_util.h"

using namespace imagenets::blocks;
using namespace imagenets::blocks::test;

TEST(ObjectModel, BoxAtInputPoseWithOffset) {
  BlockHarness h("imagenets/ObjectModel");
  h.set("name", "marker_board").set("size", std::vector<double>{0.06, 0.06, 0.002});
  h.set("offset", std::vector<double>{0, 0, 0.001, 0, 0, 0});
  h.input("pose", frame(isometry(0.2, 0, 0, M_PI, Eigen::Vector3d::UnitX()), "gripper", "marker"));
  h.run();
  auto m = h.output<visualization_msgs::Marker>("marker");
  ASSERT_TRUE(m);
  EXPECT_EQ(m->type, visualization_msgs::Marker::CUBE);
  EXPECT_EQ(m->header.frame_id, "gripper");
  EXPECT_NEAR(m->pose.position.z, -0.001, 1e-12);  // offset along the flipped z
  EXPECT_DOUBLE_EQ(m->scale.z, 0.002);
}

TEST(ObjectModel, MeshNeedsAUrl) {
  BlockHarness h("imagenets/ObjectModel");
  h.set("shape", "mesh").set("mesh_url", "gripper.stl");
  EXPECT_NE(h.runError().find("property 'mesh_url': 'gripper.stl' is not a package:// or file:// URL"),
            std::string::npos);
  h.set("mesh_url", "package://imagenets/config/meshes/gripper.stl");
  h.run();
  auto m = h.output<visualization_msgs::Marker>("marker");
  EXPECT_EQ(m->type, visualization_msgs::Marker::MESH_RESOURCE);
  EXPECT_EQ(m->header.frame_id, "base_link");
  h.set("size", std::vector<double>{1, 0, 1});
  EXPECT_NE(h.runError().find("extents must be positive"), std::string::npos);
}
