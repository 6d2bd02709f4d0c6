#include <geometry_msgs/PoseArray.h>
#include <geometry_msgs/QuaternionStamped.h>
#include <gtest/gtest.h>

#include "frame_test_util.h"

using namespace imagenets::blocks;
using namespace imagenets::blocks::test;

namespace {
geometry_msgs::PoseArray::Ptr poses(const std::vector<Eigen::Isometry3d>& ts) {
  geometry_msgs::PoseArray::Ptr m(new geometry_msgs::PoseArray);
  m->header.frame_id = "robot";
  for (const auto& t : ts) m->poses.push_back(imagenets::frames::toPose(t));
  return m;
}
}  // namespace

TEST(MeanRotation, MeanOfKnownSetWithAntipodes) {
  // 0.2, 0.4, 0.6 rad about y; the middle one given as its antipode -q.
  auto set = poses({isometry(0, 0, 0, 0.2, Eigen::Vector3d::UnitY()), isometry(5, 0, 0, 0.4, Eigen::Vector3d::UnitY()),
                    isometry(0, 0, 0, 0.6, Eigen::Vector3d::UnitY())});
  auto& q = set->poses[1].orientation;
  q.x = -q.x, q.y = -q.y, q.z = -q.z, q.w = -q.w;
  BlockHarness h("imagenets/MeanRotation");
  h.input("poses", set);
  h.run();
  auto out = h.output<geometry_msgs::QuaternionStamped>("rotation");
  ASSERT_TRUE(out);
  EXPECT_EQ(out->header.frame_id, "robot");
  EXPECT_NEAR(out->quaternion.w, std::cos(0.2), 1e-9);
  EXPECT_NEAR(out->quaternion.y, std::sin(0.2), 1e-9);
}

TEST(MeanRotation, EmptyOrBadSetIsNamedError) {
  BlockHarness h("imagenets/MeanRotation");
  h.input("poses", poses({}));
  EXPECT_NE(h.runError().find("input 'poses': empty pose array"), std::string::npos);
  auto set = poses({isometry(0, 0, 0), isometry(0, 0, 0)});
  set->poses[1].orientation.w = 1.5;
  h.input("poses", set);
  EXPECT_NE(h.runError().find("input 'poses' pose 1: quaternion"), std::string::npos) << h.runError();
  EXPECT_FALSE(h.hasOutput("rotation"));
}
