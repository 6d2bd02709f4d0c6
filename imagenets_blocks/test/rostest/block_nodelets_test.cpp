// Checks block nodelets running in the real manager of block_nodelets.test.
#include <atomic>
#include <chrono>
#include <cstdlib>
#include <functional>
#include <map>
#include <mutex>
#include <thread>

#include <dynamic_reconfigure/Reconfigure.h>
#include <geometry_msgs/PointStamped.h>
#include <gtest/gtest.h>
#include <imagenets/BlockNodeletStatus.h>
#include <nodelet/NodeletList.h>
#include <nodelet/NodeletLoad.h>
#include <ros/ros.h>
#include <rosgraph_msgs/Log.h>
#include <sensor_msgs/Image.h>
#include <std_msgs/Bool.h>
#include <std_msgs/Float64.h>
#include <std_srvs/Trigger.h>
#include "imagenets/testing/rostest_util.h"

namespace {

// Latest ~status of some block nodelets.
class StatusWatch {
 public:
  explicit StatusWatch(const std::vector<std::string>& blocks) {
    ros::NodeHandle nh;
    for (const auto& b : blocks) {
      subs_.push_back(nh.subscribe<imagenets::BlockNodeletStatus>(
          b + "/status", 10, [this, b](const imagenets::BlockNodeletStatus::ConstPtr& s) {
            std::lock_guard<std::mutex> lock(mutex_);
            runs_[b] = static_cast<int>(s->runs);
          }));
    }
  }
  int runs(const std::string& block) {
    std::lock_guard<std::mutex> lock(mutex_);
    auto it = runs_.find(block);
    return it == runs_.end() ? -1 : it->second;
  }

 private:
  std::mutex mutex_;
  std::map<std::string, int> runs_;
  std::vector<ros::Subscriber> subs_;
};

TEST(BlockNodelets, ImagesPassByPointerInsideOneManager) {
  ros::NodeHandle nh;
  std::atomic<int> same{0}, different{0}, ctrl_same{0}, ctrl_different{0};
  auto count = [](std::atomic<int>& yes, std::atomic<int>& no) {
    return [&yes, &no](const std_msgs::Bool::ConstPtr& m) { (m->data ? yes : no)++; };
  };
  ros::Subscriber s1 = nh.subscribe<std_msgs::Bool>("probe/same_pointer", 100, count(same, different));
  ros::Subscriber s2 = nh.subscribe<std_msgs::Bool>("probe_ctrl/same_pointer", 100, count(ctrl_same, ctrl_different));
  ASSERT_TRUE(waitFor([&] { return same + different >= 5 && ctrl_same + ctrl_different >= 5; }, 20.0))
      << "probe reports: " << same + different << ", control: " << ctrl_same + ctrl_different;
  // Through two block nodelets (three topic hops) the probe got back the object it published.
  EXPECT_EQ(different.load(), 0);
  EXPECT_GE(same.load(), 5);
  // The control proves the probe can tell: Threshold outputs a new image.
  EXPECT_EQ(ctrl_same.load(), 0);
  EXPECT_GE(ctrl_different.load(), 5);
}

sensor_msgs::ImagePtr stampedImage(double stamp) {
  auto image = boost::make_shared<sensor_msgs::Image>();
  image->header.stamp = ros::Time(stamp);
  image->width = image->height = 2;
  image->encoding = "mono8";
  image->step = 2;
  image->data.assign(4, 0);
  return image;
}

std_msgs::Float64 number(double v) {
  std_msgs::Float64 m;
  m.data = v;
  return m;
}

TEST(BlockNodelets, InputsArePairedByStamp) {
  ros::NodeHandle nh;
  std::mutex mutex;
  std::vector<geometry_msgs::PointStamped> exact, approx;
  ros::Subscriber s1 = nh.subscribe<geometry_msgs::PointStamped>(
      "pair/out/pair", 10, [&](const geometry_msgs::PointStamped::ConstPtr& m) {
        std::lock_guard<std::mutex> lock(mutex);
        exact.push_back(*m);
      });
  ros::Subscriber s2 = nh.subscribe<geometry_msgs::PointStamped>(
      "pair_approx/out/pair", 10, [&](const geometry_msgs::PointStamped::ConstPtr& m) {
        std::lock_guard<std::mutex> lock(mutex);
        approx.push_back(*m);
      });
  auto size = [&](std::vector<geometry_msgs::PointStamped>& v) {
    std::lock_guard<std::mutex> lock(mutex);
    return v.size();
  };
  ros::Publisher a = nh.advertise<sensor_msgs::Image>("pair/in/a", 10);
  ros::Publisher b = nh.advertise<sensor_msgs::Image>("pair/in/b", 10);
  ros::Publisher c = nh.advertise<std_msgs::Float64>("pair/in/c", 10);
  ros::Publisher aa = nh.advertise<sensor_msgs::Image>("pair_approx/in/a", 10);
  ros::Publisher ab = nh.advertise<sensor_msgs::Image>("pair_approx/in/b", 10);
  ros::Publisher ac = nh.advertise<std_msgs::Float64>("pair_approx/in/c", 10);
  ASSERT_TRUE(waitFor([&] {
    for (auto* p : {&a, &b, &c, &aa, &ab, &ac}) {
      if (p->getNumSubscribers() == 0) return false;
    }
    return s1.getNumPublishers() > 0 && s2.getNumPublishers() > 0;
  }, 10.0));

  // Exact: different stamps never pair; the matching stamp does, whatever the arrival order.
  c.publish(number(5.0));
  a.publish(stampedImage(100.0));
  b.publish(stampedImage(101.0));
  EXPECT_FALSE(waitFor([&] { return size(exact) > 0; }, 0.7));
  b.publish(stampedImage(100.0));
  ASSERT_TRUE(waitFor([&] { return size(exact) == 1; }, 5.0));
  EXPECT_DOUBLE_EQ(exact[0].point.x, 100.0);
  EXPECT_DOUBLE_EQ(exact[0].point.y, 100.0);
  EXPECT_DOUBLE_EQ(exact[0].point.z, 5.0);
  // A header-less input joins with its latest value and re-runs the newest stamped set.
  c.publish(number(6.0));
  ASSERT_TRUE(waitFor([&] { return size(exact) == 2; }, 5.0));
  EXPECT_DOUBLE_EQ(exact[1].point.x, 100.0);
  EXPECT_DOUBLE_EQ(exact[1].point.y, 100.0);
  EXPECT_DOUBLE_EQ(exact[1].point.z, 6.0);

  // Approximate (slop 0.1 s): 50 ms apart pair, 500 ms apart do not.
  ac.publish(number(1.0));
  aa.publish(stampedImage(200.0));
  ab.publish(stampedImage(200.05));
  ASSERT_TRUE(waitFor([&] { return size(approx) == 1; }, 5.0));
  EXPECT_DOUBLE_EQ(approx[0].point.x, 200.0);
  EXPECT_NEAR(approx[0].point.y, 200.05, 1e-6);
  ab.publish(stampedImage(200.5));
  EXPECT_FALSE(waitFor([&] { return size(approx) > 1; }, 0.7));
  // The exact instance would not have paired 200.0 with 200.05.
  a.publish(stampedImage(200.0));
  b.publish(stampedImage(200.05));
  EXPECT_FALSE(waitFor([&] { return size(exact) > 2; }, 0.7));
}

size_t whitePixels(const sensor_msgs::Image& image) {
  size_t n = 0;
  for (uint8_t v : image.data) n += v > 0;
  return n;
}

TEST(BlockNodelets, PropertyChangeRerunsBlockAndDownstreamOnce) {
  ros::NodeHandle nh;
  StatusWatch status({"dyn_src", "dyn_blur", "dyn_thr"});
  std::mutex mutex;
  std::vector<size_t> outputs;  // white pixels of each dyn_thr output
  ros::Subscriber out = nh.subscribe<sensor_msgs::Image>("dyn_thr/out/image", 10,
                                                         [&](const sensor_msgs::Image::ConstPtr& m) {
                                                           std::lock_guard<std::mutex> lock(mutex);
                                                           outputs.push_back(whitePixels(*m));
                                                         });
  auto nOutputs = [&] {
    std::lock_guard<std::mutex> lock(mutex);
    return outputs.size();
  };
  ASSERT_TRUE(waitFor([&] { return status.runs("dyn_src") == 0 && status.runs("dyn_blur") == 0 &&
                                   status.runs("dyn_thr") == 0 && out.getNumPublishers() > 0; },
                      10.0));

  // The source runs on ~run only (source_mode: trigger): one run flows through the chain.
  std_srvs::Trigger trigger;
  ASSERT_TRUE(ros::service::call("dyn_src/run", trigger));
  EXPECT_TRUE(trigger.response.success) << trigger.response.message;
  ASSERT_TRUE(waitFor([&] { return nOutputs() == 1; }, 5.0));

  // Change kernel_size through the dynamic_reconfigure protocol.
  dynamic_reconfigure::Reconfigure set;
  dynamic_reconfigure::IntParameter kernel;
  kernel.name = "kernel_size";
  kernel.value = 7;
  set.request.config.ints.push_back(kernel);
  ASSERT_TRUE(ros::service::call("dyn_blur/set_parameters", set));
  bool reported = false;
  for (const auto& p : set.response.config.ints) reported |= p.name == "kernel_size" && p.value == 7;
  EXPECT_TRUE(reported);
  ASSERT_TRUE(waitFor([&] { return nOutputs() == 2; }, 5.0));
  std::this_thread::sleep_for(std::chrono::milliseconds(700));  // room for any extra run to show
  EXPECT_EQ(status.runs("dyn_src"), 1);
  EXPECT_EQ(status.runs("dyn_blur"), 2);
  EXPECT_EQ(status.runs("dyn_thr"), 2);
  EXPECT_EQ(nOutputs(), 2u);
  int stored = 0;
  EXPECT_TRUE(nh.getParam("dyn_blur/kernel_size", stored));
  EXPECT_EQ(stored, 7);

  // The same through the dynparam command line tool (the Python client of the protocol).
  // Debian's python3 first: dynparam runs on `env python3`, and a pyenv python lacks the ROS modules.
  ASSERT_EQ(std::system("PATH=/usr/bin:$PATH rosrun dynamic_reconfigure dynparam set /dyn_thr threshold 72"), 0);
  ASSERT_TRUE(waitFor([&] { return nOutputs() == 3; }, 5.0));
  std::this_thread::sleep_for(std::chrono::milliseconds(700));
  EXPECT_EQ(status.runs("dyn_blur"), 2);
  EXPECT_EQ(status.runs("dyn_thr"), 3);
  EXPECT_EQ(nOutputs(), 3u);
  {
    std::lock_guard<std::mutex> lock(mutex);
    EXPECT_NE(outputs[2], outputs[1]) << "threshold 72 must whiten a different number of pixels than 128";
  }
  EXPECT_TRUE(nh.getParam("dyn_thr/threshold", stored));
  EXPECT_EQ(stored, 72);

  // An out-of-range value is refused: nothing runs, the value stays.
  dynamic_reconfigure::Reconfigure bad;
  dynamic_reconfigure::IntParameter threshold;
  threshold.name = "threshold";
  threshold.value = 720;
  bad.request.config.ints.push_back(threshold);
  ASSERT_TRUE(ros::service::call("dyn_thr/set_parameters", bad));
  for (const auto& p : bad.response.config.ints) {
    if (p.name == "threshold") EXPECT_EQ(p.value, 72);
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  EXPECT_EQ(status.runs("dyn_thr"), 3);
}

// Asks the manager to load a nodelet, as `nodelet load` does; returns the load result (the
// manager answers a failed load with a failed service call).
bool loadNodelet(const std::string& name, const std::string& type) {
  nodelet::NodeletLoad load;
  load.request.name = name;
  load.request.type = type;
  return ros::service::call("manager/load_nodelet", load) && load.response.success;
}

TEST(BlockNodelets, BadParameterFailsTheLoadWithTheNamedError) {
  ros::NodeHandle nh;
  std::mutex mutex;
  std::vector<std::string> errors;
  ros::Subscriber log = nh.subscribe<rosgraph_msgs::Log>("/rosout", 100, [&](const rosgraph_msgs::Log::ConstPtr& m) {
    std::lock_guard<std::mutex> lock(mutex);
    if (m->level >= rosgraph_msgs::Log::ERROR) errors.push_back(m->msg);
  });
  auto logged = [&](const std::string& text) {
    std::lock_guard<std::mutex> lock(mutex);
    for (const auto& e : errors) {
      if (e.find(text) != std::string::npos) return true;
    }
    return false;
  };
  // Every node logs on /rosout (no rosout node needed): wait until the manager is connected.
  ASSERT_TRUE(waitFor([&] { return log.getNumPublishers() > 0; }, 30.0));
  ASSERT_TRUE(ros::service::waitForService("manager/load_nodelet", 30000));

  // Each failed load must log its named error. The manager's /rosout connection may come up
  // after our first attempt, so a failing load is retried until its message is seen.
  auto failsWith = [&](const std::string& name, const std::string& type, const std::string& text) {
    return waitFor([&] {
      EXPECT_FALSE(loadNodelet(name, type));
      return waitFor([&] { return logged(text); }, 0.5);
    }, 8.0);
  };
  nh.setParam("/bad_range/threshold", 300);
  EXPECT_TRUE(failsWith("/bad_range", "imagenets/Threshold",
                        "parameter '/bad_range/threshold': property 'threshold': value 300 is out of range [0, 255]"));
  EXPECT_TRUE(logged("nodelet '/bad_range' (imagenets/Threshold): not loaded"));

  nh.setParam("/bad_name/threshhold", 30);
  EXPECT_TRUE(failsWith("/bad_name", "imagenets/Threshold", "parameter '/bad_name/threshhold': unknown property 'threshhold'"));

  nh.setParam("/bad_type/kernel_size", std::string("large"));
  EXPECT_TRUE(failsWith("/bad_type", "imagenets/GaussianBlur", "property 'kernel_size': expected int, got 'large'"));

  // The manager carries on: a good nodelet still loads, the failed ones are not listed.
  nh.setParam("/good/threshold", 30);
  EXPECT_TRUE(loadNodelet("/good", "imagenets/Threshold"));
  nodelet::NodeletList list;
  ASSERT_TRUE(ros::service::call("manager/list", list));
  auto listed = [&](const std::string& n) {
    return std::find(list.response.nodelets.begin(), list.response.nodelets.end(), n) != list.response.nodelets.end();
  };
  EXPECT_TRUE(listed("/good"));
  EXPECT_FALSE(listed("/bad_range"));
  EXPECT_FALSE(listed("/bad_name"));
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "block_nodelets_test");
  ros::AsyncSpinner spinner(2);
  spinner.start();
  int result = RUN_ALL_TESTS();
  spinner.stop();
  ros::shutdown();
  return result;
}
