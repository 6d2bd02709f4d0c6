// Calibration files: round trip, replay reproduces the result, archive of the previous file,
// named errors for bad files.
#include "imagenets_calibration/storage.h"

#include <cstdio>
#include <filesystem>
#include <fstream>

#include <boost/crc.hpp>
#include <gtest/gtest.h>
#include <urdf/model.h>

#include "imagenets/testing/read_file.h"

namespace imagenets_calibration {
namespace {

namespace fs = std::filesystem;
using imagenets::testing::readFile;

// `text` with the CRC line a saved file ends with (storage.h).
std::string withCrc(const std::string& text) {
  boost::crc_32_type crc;
  crc.process_bytes(text.data(), text.size());
  char line[32];
  std::snprintf(line, sizeof line, "crc32: 0x%08x\n", crc.checksum());
  return text + line;
}

struct StorageTest : ::testing::Test {
  RobotModel model{robot_description::loadRobotDescription(robot_description::exampleRobotDescriptionPath())};
  fs::path dir = fs::temp_directory_path() / ("calib_storage_" + std::to_string(::getpid()));
  void SetUp() override { fs::create_directories(dir); }
  void TearDown() override { fs::remove_all(dir); }

  Result someResult() {
    const auto& d = model.description();
    std::vector<Sample> samples;
    Eigen::Isometry3d truth = model.headBase();
    truth.translation() += Eigen::Vector3d(0.01, -0.005, 0.002);
    for (int k = 0; k < 3; ++k) {
      Sample s;
      s.arm_q = d.arm_calibration_pose;
      s.arm_q[6] += 0.1 * k;
      s.head_q = d.head_calibration_pose;
      s.left.found = true;
      s.left.pose = (truth * headChain(model, s.head_q)).inverse() * model.marker(s.arm_q);
      s.left.pose.translation().z() += 0.0003 * k;
      s.left.confidence = 0.9;
      s.left.threshold = 100;
      s.left.points.assign(8, Eigen::Vector2d(1.5, 2.25));
      s.right.found = k != 1;
      s.right.pose = model.leftToRight().inverse() * s.left.pose;
      if (!s.right.found) s.right.reason = "reflection";
      s.stamp = 100.0 + k;
      samples.push_back(s);
    }
    return calibrate(model, samples, "joint", FusionLimits(), CombineOptions());
  }
};

TEST_F(StorageTest, RoundTripAndReplayReproduceTheResult) {
  StoredCalibration c;
  c.result = someResult();
  ASSERT_TRUE(c.result.success) << c.result.message;
  const std::string path = (dir / "pth_fixed_point.yaml").string();
  EXPECT_EQ(saveCalibration(c, path), "");
  const StoredCalibration loaded = loadCalibration(path);
  EXPECT_EQ(loaded.result.method, "joint");
  ASSERT_EQ(loaded.result.samples.size(), 3u);
  EXPECT_FALSE(loaded.result.samples[1].right.found);
  EXPECT_EQ(loaded.result.samples[1].right.reason, "reflection");
  EXPECT_EQ(loaded.result.samples[0].left.points.size(), 8u);
  EXPECT_LT((loaded.result.fixed_point.translation() - c.result.fixed_point.translation()).norm(), 1e-12);
  const Result replay = calibrate(model, loaded.result.samples, loaded.result.method, FusionLimits(), CombineOptions());
  ASSERT_TRUE(replay.success);
  // Same to a micrometre / microradian (17 significant digits in the file; the least squares
  // iterates from values that differ in the last bit).
  EXPECT_LT((replay.fixed_point.translation() - c.result.fixed_point.translation()).norm(), 1e-6);
  EXPECT_LT(angleBetween(replay.fixed_point, c.result.fixed_point), 1e-6);
  EXPECT_EQ(replay.used, c.result.used);
}

TEST_F(StorageTest, AMonoCamerasObservationsAreKeptAndAStereoFileHasNone) {
  StoredCalibration c;
  c.result = someResult();
  c.result.samples[0].mono = c.result.samples[0].left;
  c.result.samples[0].mono.threshold = 77;
  c.result.samples[2].mono.reason = "no tag";
  const std::string path = (dir / "mono.yaml").string();
  EXPECT_EQ(saveCalibration(c, path), "");
  const StoredCalibration loaded = loadCalibration(path);
  ASSERT_EQ(loaded.result.samples.size(), 3u);
  EXPECT_TRUE(loaded.result.samples[0].mono.found);
  EXPECT_EQ(loaded.result.samples[0].mono.threshold, 77);
  EXPECT_TRUE(loaded.result.samples[0].mono.pose.isApprox(c.result.samples[0].left.pose, 1e-12));
  EXPECT_FALSE(loaded.result.samples[1].mono.found);
  EXPECT_EQ(loaded.result.samples[2].mono.reason, "no tag");
  // A stereo calibration's file names no mono observation.
  c.result = someResult();
  const std::string stereo = (dir / "stereo.yaml").string();
  EXPECT_EQ(saveCalibration(c, stereo), "");
  const std::string text = readFile(stereo);
  EXPECT_EQ(text.find("mono:"), std::string::npos);
}

TEST_F(StorageTest, PreviousFileIsArchivedAndNoTemporaryFileRemains) {
  StoredCalibration c;
  c.result = someResult();
  const std::string path = (dir / "pth_fixed_point.yaml").string();
  saveCalibration(c, path);
  const std::string before = readFile(path);
  c.created = "2030-01-01T00:00:00Z";
  const std::string archived = saveCalibration(c, path);
  ASSERT_FALSE(archived.empty());
  const std::string kept = readFile(archived);
  EXPECT_EQ(kept, before);
  int files = 0;
  for (const auto& e : fs::directory_iterator(dir)) {
    ++files;
    EXPECT_EQ(e.path().string().find(".tmp"), std::string::npos) << e.path();
  }
  EXPECT_EQ(files, 2);
}

TEST_F(StorageTest, BadFilesAreNamedErrors) {
  try {
    loadCalibration((dir / "missing.yaml").string());
    FAIL();
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("missing.yaml"), std::string::npos) << e.what();
  }
  const std::string bad = (dir / "bad.yaml").string();
  std::ofstream(bad) << withCrc("method: paper\nfixed_point: {xyz: [1, 2], quaternion_xyzw: [0, 0, 0, 1]}\n");
  try {
    loadCalibration(bad);
    FAIL();
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("fixed_point.xyz"), std::string::npos) << e.what();
  }
}

// A file cut short anywhere (a full disk, an interrupted copy) or altered is refused with a named
// error, also where the rest would parse (between two samples, inside a number); so is an empty one.
TEST_F(StorageTest, TruncatedCorruptOrEmptyFilesAreRefused) {
  StoredCalibration c;
  c.result = someResult();
  const std::string path = (dir / "pth_fixed_point.yaml").string();
  saveCalibration(c, path);
  const std::string whole = readFile(path);
  ASSERT_NO_THROW(loadCalibration(path));
  const std::string damaged = (dir / "damaged.yaml").string();
  auto refusal = [&](const std::string& content) -> std::string {
    std::ofstream(damaged, std::ios::trunc | std::ios::binary) << content;
    try {
      loadCalibration(damaged);
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find("damaged.yaml"), std::string::npos) << e.what();
      return e.what();
    }
    return "";
  };
  for (size_t n = 0; n + 1 < whole.size(); n += 7) {
    EXPECT_NE(refusal(whole.substr(0, n)), "") << "accepted the file cut after " << n << " of " << whole.size() << " bytes";
  }
  // Cut at the start of its last line: everything else is there and parses.
  EXPECT_NE(refusal(whole.substr(0, whole.rfind("crc32:"))).find("incomplete"), std::string::npos);
  // One digit of the fixed point changed: still valid YAML with a plausible value.
  std::string altered = whole;
  const size_t digit = altered.find_first_of("123456789", altered.find("fixed_point: {xyz: [") + 25);
  altered[digit] = altered[digit] == '9' ? '8' : altered[digit] + 1;
  EXPECT_NE(refusal(altered).find("corrupt"), std::string::npos);
  EXPECT_NE(refusal(whole.substr(0, 100) + "\x01\x02{{[[ garbage" + whole.substr(140)).find("corrupt"), std::string::npos);
  EXPECT_NE(refusal("").find("empty"), std::string::npos);
}

Eigen::Isometry3d originOf(const urdf::Model& urdf, const std::string& joint) {
  const auto j = urdf.getJoint(joint);
  if (!j) throw std::runtime_error("the URDF has no joint '" + joint + "'");
  const auto& p = j->parent_to_joint_origin_transform;
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.translation() = Eigen::Vector3d(p.position.x, p.position.y, p.position.z);
  t.linear() = Eigen::Quaterniond(p.rotation.w, p.rotation.x, p.rotation.y, p.rotation.z).toRotationMatrix();
  return t;
}

void expectSameFrame(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b, const std::string& what) {
  EXPECT_LT((a.translation() - b.translation()).norm(), 1e-9) << what;
  EXPECT_LT(angleBetween(a, b), 1e-9) << what;
}

TEST_F(StorageTest, CalibratedUrdfCarriesTheFixedPointMarkerOffsetAndJointOffsets) {
  StoredCalibration c;
  c.result = someResult();
  Result& r = c.result;
  r.fixed_point = robot_description::fromXyzRpy({-0.04, 0.006, 1.37}, {0.01, -0.02, 0.03});
  r.marker_offset = robot_description::fromXyzRpy({0.001, 0.046, -0.029}, {-1.55, 0.01, 0.0});
  r.arm_joint_offsets = {0, 0.01, -0.02, 0.003, 0, 0.004, 0};
  r.head_joint_offsets = {0, 0.005};
  const std::string path = (dir / "pth_fixed_point.urdf").string();
  saveCalibratedUrdf(model, c, path);
  urdf::Model urdf;
  ASSERT_TRUE(urdf.initFile(path)) << path;
  expectSameFrame(originOf(urdf, "head_link_0_mount"), r.fixed_point, "head mount = fixed point");
  expectSameFrame(originOf(urdf, "gripper_marker_joint"), r.marker_offset, "marker joint = marker offset");
  // A joint's zero offset turns its origin about the joint axis (z): the nominal origin is the
  // identity (theta offsets 0 in robot.yaml).
  const auto& d = model.description();
  for (size_t i = 0; i < d.arm.joints.size(); ++i) {
    expectSameFrame(originOf(urdf, d.arm.joints[i].name),
                    Eigen::Isometry3d(Eigen::AngleAxisd(r.arm_joint_offsets[i], Eigen::Vector3d::UnitZ())),
                    d.arm.joints[i].name);
  }
  expectSameFrame(originOf(urdf, "head_tilt_joint"), Eigen::Isometry3d(Eigen::AngleAxisd(0.005, Eigen::Vector3d::UnitZ())),
                  "head_tilt_joint");
  const std::string text = readFile(path);
  EXPECT_NE(text.find("arm_joint_3 -1.14591559 deg"), std::string::npos) << text.substr(0, 800);
  EXPECT_NE(text.find("robot_state_publisher ignores <calibration>"), std::string::npos);
  EXPECT_EQ(urdfFileBeside((dir / "pth_fixed_point.yaml").string()), path);
}

// A robot that exists only as its own URDF (config/six_axis) gets that URDF back calibrated: its
// link and joint names stay, its head mount joint (head_mast) holds the fixed point.
TEST_F(StorageTest, CalibratedUrdfOfARobotWithItsOwnUrdfKeepsItsNames) {
  const RobotModel six_axis(robot_description::loadRobotDescription(
      fs::path(robot_description::exampleRobotDescriptionPath()).parent_path().parent_path().string() +
      "/six_axis/robot.yaml"));
  StoredCalibration c;
  Result& r = c.result;
  r.method = "joint";
  r.fixed_point = robot_description::fromXyzRpy({-0.07, 0.046, 1.35}, {0.01, -0.02, 0.03});
  r.marker_offset = six_axis.description().marker.pose;
  r.arm_joint_offsets = {0, 0.01, -0.02, 0.003, 0.002, 0};
  r.head_joint_offsets = {0, 0.005};
  c.child_frame = "pth_fixed_point";
  const std::string path = (dir / "six_axis.urdf").string();
  saveCalibratedUrdf(six_axis, c, path);
  urdf::Model urdf;
  ASSERT_TRUE(urdf.initFile(path)) << path;
  EXPECT_EQ(urdf.getName(), "six_axis");
  expectSameFrame(originOf(urdf, "head_mast"), r.fixed_point, "head mount = fixed point");
  EXPECT_TRUE(urdf.getLink("head_mount") && urdf.getLink("shoulder") && !urdf.getLink("head_link_0"));
  const std::string text = readFile(path);
  EXPECT_NE(text.find("joint head_mast (base_link -> head_mount, the calibrated pth_fixed_point)"), std::string::npos)
      << text.substr(0, 800);
  EXPECT_NE(text.find("elbow -1.14591559 deg"), std::string::npos) << text.substr(0, 800);
}

TEST_F(StorageTest, CalibratedUrdfThatCannotBeWrittenIsANamedErrorAndLeavesNoTemporaryFile) {
  StoredCalibration c;
  c.result = someResult();
  // A directory where the file should go (with something in it): the rename fails.
  const fs::path path = dir / "pth_fixed_point.urdf";
  fs::create_directories(path / "occupied");
  try {
    saveCalibratedUrdf(model, c, path.string());
    ADD_FAILURE() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("calibrated URDF"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find(path.string()), std::string::npos) << e.what();
  }
  EXPECT_TRUE(fs::is_directory(path / "occupied"));
  for (const auto& e : fs::directory_iterator(dir)) EXPECT_EQ(e.path().string().find(".tmp"), std::string::npos) << e.path();
}

}  // namespace
}  // namespace imagenets_calibration
