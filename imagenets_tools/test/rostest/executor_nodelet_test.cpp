// Checks the SubNet nodelets of executor_nodelet.test against `imagenets run` on the same file.
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <functional>
#include <mutex>
#include <string>
#include <thread>

#include <dynamic_reconfigure/Reconfigure.h>
#include <gtest/gtest.h>
#include <imagenets/BlockNodeletStatus.h>
#include <opencv2/imgcodecs.hpp>
#include <ros/ros.h>
#include <sensor_msgs/Image.h>
#include <std_srvs/Trigger.h>
#include "imagenets/testing/rostest_util.h"

namespace {

std::string g_net_file;

// The last image on a topic.
class Latest {
 public:
  explicit Latest(const std::string& topic) {
    sub_ = ros::NodeHandle().subscribe<sensor_msgs::Image>(topic, 5, [this](const sensor_msgs::Image::ConstPtr& m) {
      std::lock_guard<std::mutex> lock(mutex_);
      image_ = m;
      ++count_;
    });
  }
  sensor_msgs::Image::ConstPtr get(double timeout) {
    waitFor([this] {
      std::lock_guard<std::mutex> lock(mutex_);
      return static_cast<bool>(image_);
    }, timeout);
    std::lock_guard<std::mutex> lock(mutex_);
    return image_;
  }
  int count() {
    std::lock_guard<std::mutex> lock(mutex_);
    return count_;
  }

 private:
  std::mutex mutex_;
  sensor_msgs::Image::ConstPtr image_;
  int count_ = 0;
  ros::Subscriber sub_;
};

// Runs `imagenets run NET -o DIR` once; its PNG outputs are what the nodelets must publish.
const std::string& toolOutputDir() {
  static const std::string dir = [] {
    char tmpl[] = "/tmp/imagenets_executor_nodelet_XXXXXX";
    const std::string d = mkdtemp(tmpl);
    const std::string cmd = std::string(IMAGENETS_TOOL) + " run " + g_net_file + " --output-dir " + d + " > /dev/null";
    EXPECT_EQ(std::system(cmd.c_str()), 0) << cmd;
    return d;
  }();
  return dir;
}

void expectSameMono8(const sensor_msgs::Image& msg, const cv::Mat& png, const std::string& what) {
  ASSERT_FALSE(png.empty()) << what << ": tool output missing";
  ASSERT_EQ(msg.encoding, "mono8") << what;
  ASSERT_EQ(static_cast<int>(msg.width), png.cols) << what;
  ASSERT_EQ(static_cast<int>(msg.height), png.rows) << what;
  ASSERT_EQ(png.type(), CV_8UC1) << what;
  size_t differing = 0;
  for (int r = 0; r < png.rows; ++r) {
    for (int c = 0; c < png.cols; ++c) differing += msg.data[r * msg.step + c] != png.at<uint8_t>(r, c);
  }
  EXPECT_EQ(differing, 0u) << what << ": pixels differ from `imagenets run`";
}

TEST(ExecutorNodelet, RosparamNetGivesTheSameOutputAsTheTool) {
  Latest from_param("exec_param/out/binary");
  const cv::Mat expected = cv::imread(toolOutputDir() + "/binary.value.png", cv::IMREAD_UNCHANGED);
  auto image = from_param.get(15.0);
  ASSERT_TRUE(image) << "no output from the SubNet nodelet with a rosparam net";
  expectSameMono8(*image, expected, "exec_param binary");
  // Not a trivial image: the threshold splits the scene.
  EXPECT_GT(cv::countNonZero(expected), 0);
  EXPECT_LT(cv::countNonZero(expected), expected.rows * expected.cols);
}

TEST(ExecutorNodelet, NetFileGivesTheSameOutputAsTheTool) {
  Latest from_file("exec_file/out/binary");
  auto image = from_file.get(15.0);
  ASSERT_TRUE(image);
  expectSameMono8(*image, cv::imread(toolOutputDir() + "/binary.value.png", cv::IMREAD_UNCHANGED), "exec_file binary");
}

TEST(ExecutorNodelet, SubNetInputsAreTopics) {
  Latest inverted("exec_in/out/inverted");
  auto image = inverted.get(15.0);
  ASSERT_TRUE(image) << "the net written inside the launch file produced nothing";
  cv::Mat expected = cv::imread(toolOutputDir() + "/binary.value.png", cv::IMREAD_UNCHANGED);
  ASSERT_FALSE(expected.empty());
  expected = 255 - expected;
  expectSameMono8(*image, expected, "exec_in inverted");
}

// Sets exec_in's inline net through the dynamic_reconfigure protocol; returns the net_yaml the
// server reports afterwards.
std::string setNetYaml(const std::string& yaml) {
  dynamic_reconfigure::Reconfigure set;
  dynamic_reconfigure::StrParameter p;
  p.name = "net_yaml";
  p.value = yaml;
  set.request.config.strs.push_back(p);
  EXPECT_TRUE(ros::service::call("exec_in/set_parameters", set));
  for (const auto& s : set.response.config.strs) {
    if (s.name == "net_yaml") return s.value;
  }
  return "";
}

TEST(ExecutorNodelet, TheInnerNetCanBeChangedLive) {
  Latest inverted("exec_in/out/inverted");
  ASSERT_TRUE(inverted.get(15.0));
  const int before = inverted.count();
  cv::Mat binary = cv::imread(toolOutputDir() + "/binary.value.png", cv::IMREAD_UNCHANGED);

  // Same ports, no inversion: the block re-runs on its cached input with the new net.
  const std::string plain =
      "blocks:\n"
      "  image: {type: imagenets/SubNetInput, properties: {port: image}}\n"
      "  invert: {type: imagenets/Threshold, properties: {threshold: 128}}\n"
      "  inverted: {type: imagenets/SubNetOutput, properties: {port: inverted}}\n"
      "links: [image.value -> invert.image, invert.image -> inverted.value]\n";
  EXPECT_EQ(setNetYaml(plain), plain);
  ASSERT_TRUE(waitFor([&] { return inverted.count() == before + 1; }, 5.0));
  expectSameMono8(*inverted.get(1.0), binary, "exec_in after the change");

  // A net that does not build is refused; the running net stays.
  EXPECT_EQ(setNetYaml("blocks: {x: {type: imagenets/NoSuchBlock}}\n"), plain);
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  EXPECT_EQ(inverted.count(), before + 1);
}

TEST(ExecutorNodelet, InternalPortsArePublishedWhileSubscribed) {
  Latest gray("exec_param/internal/gray/image");
  ros::NodeHandle nh;
  ASSERT_TRUE(waitFor([&] { return ros::topic::waitForMessage<sensor_msgs::Image>("exec_param/out/binary", nh,
                                                                                   ros::Duration(0.2)) != nullptr; },
                      10.0));
  // Re-run the SubNet block: the inner net's cached values go out to the new subscriber.
  std_srvs::Trigger run;
  ASSERT_TRUE(waitFor([&] { return ros::service::call("exec_param/run", run) && run.response.success; }, 10.0))
      << run.response.message;
  auto image = gray.get(5.0);
  ASSERT_TRUE(image) << "nothing on ~internal/gray/image";
  expectSameMono8(*image, cv::imread(toolOutputDir() + "/gray.image.png", cv::IMREAD_UNCHANGED), "internal gray");
}

// The inner net's run events reach ~status while it runs; after the run, the last one is the
// sub-net's repetition (1 of 1).
TEST(ExecutorNodelet, StatusShowsTheInnerRunsProgress) {
  LatestMessage<imagenets::BlockNodeletStatus> status("exec_file/status");
  ASSERT_TRUE(waitFor([&] { auto s = status.get(); return s && s->runs >= 1; }, 15.0)) << "no ~status after a run";
  auto s = status.get();
  EXPECT_EQ(s->status, "ok");
  EXPECT_EQ(s->progress, "repetition 1 of 1 done");
  // CPU time is measured only while ~status is watched (as it is now): a run we watch has it,
  // beside the wall time (the calling thread's: within it, up to the clocks' grain).
  const uint64_t runs = s->runs;
  std_srvs::Trigger run;
  ASSERT_TRUE(ros::service::call("exec_file/run", run) && run.response.success) << run.response.message;
  ASSERT_TRUE(waitFor([&] { s = status.get(); return s && s->runs > runs; }, 15.0)) << "no ~status after the run";
  EXPECT_EQ(s->progress, "repetition 1 of 1 done");
  EXPECT_GT(s->last_cpu_ms, 0.0);
  EXPECT_LE(s->last_cpu_ms, s->last_ms + 0.1);
  EXPECT_GT(s->mean_cpu_ms, 0.0);
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "executor_nodelet_test");
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s NET_FILE\n", argv[0]);
    return 2;
  }
  g_net_file = argv[1];
  ros::AsyncSpinner spinner(2);
  spinner.start();
  int result = RUN_ALL_TESTS();
  spinner.stop();
  ros::shutdown();
  return result;
}
