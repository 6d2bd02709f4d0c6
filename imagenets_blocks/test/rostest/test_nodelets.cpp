// Test-only nodelets for the rostests (library imagenets_test_nodelets, built by `make tests`):
//   imagenets_test/PointerProbe  publishes a 1024x768 image and reports, for each image that comes
//                                back on ~in, whether it is the very object it published
//                                (zero-copy proven, not assumed);
//   imagenets_test/StampProbe    a block with two stamped inputs and one header-less input that
//                                reports which stamps the host paired.
#include <map>
#include <mutex>

#include <geometry_msgs/PointStamped.h>
#include <nodelet/nodelet.h>
#include <pluginlib/class_list_macros.hpp>
#include <ros/ros.h>
#include <sensor_msgs/Image.h>
#include <std_msgs/Bool.h>
#include <std_msgs/Float64.h>

#include "imagenets/register_block.h"

namespace imagenets {
namespace test {

class PointerProbe : public nodelet::Nodelet {
 private:
  void onInit() override {
    ros::NodeHandle& pnh = getPrivateNodeHandle();
    out_ = pnh.advertise<sensor_msgs::Image>("out", 5);
    same_ = pnh.advertise<std_msgs::Bool>("same_pointer", 100);
    in_ = pnh.subscribe("in", 5, &PointerProbe::onImage, this);
    timer_ = pnh.createTimer(ros::Duration(0.1), &PointerProbe::tick, this);
  }

  void tick(const ros::TimerEvent&) {
    if (out_.getNumSubscribers() == 0) return;
    auto image = boost::make_shared<sensor_msgs::Image>();
    image->header.stamp = ros::Time::now();
    image->header.frame_id = "probe";
    image->width = 1024;
    image->height = 768;
    image->encoding = "mono8";
    image->step = image->width;
    image->data.assign(static_cast<size_t>(image->step) * image->height, 100);
    sensor_msgs::ImageConstPtr sent = image;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      sent_[sent->header.stamp] = sent;  // held, so no other image can reuse the address
      while (sent_.size() > 20) sent_.erase(sent_.begin());
    }
    out_.publish(sent);
  }

  void onImage(const sensor_msgs::ImageConstPtr& received) {
    std::lock_guard<std::mutex> lock(mutex_);
    auto it = sent_.find(received->header.stamp);
    if (it == sent_.end()) return;
    std_msgs::Bool same;
    same.data = received.get() == it->second.get();
    same_.publish(same);
  }

  std::mutex mutex_;
  std::map<ros::Time, sensor_msgs::ImageConstPtr> sent_;
  ros::Publisher out_, same_;
  ros::Subscriber in_;
  ros::Timer timer_;
};

class StampProbe : public Block {
 public:
  StampProbe() {
    addInput<sensor_msgs::Image>("a", "stamped input");
    addInput<sensor_msgs::Image>("b", "stamped input");
    addInput<std_msgs::Float64>("c", "header-less input (paired by latest value)");
    addOutput<geometry_msgs::PointStamped>("pair", "x: stamp of a, y: stamp of b, z: c");
  }
  void process(Context& ctx) override {
    auto a = ctx.input<sensor_msgs::Image>("a");
    auto b = ctx.input<sensor_msgs::Image>("b");
    auto out = boost::make_shared<geometry_msgs::PointStamped>();
    out->header = a->header;
    out->point.x = a->header.stamp.toSec();
    out->point.y = b->header.stamp.toSec();
    out->point.z = ctx.input<std_msgs::Float64>("c")->data;
    ctx.output("pair", out);
  }
};

}  // namespace test
}  // namespace imagenets

PLUGINLIB_EXPORT_CLASS(imagenets::test::PointerProbe, nodelet::Nodelet)
IMAGENETS_REGISTER_BLOCK(imagenets::test::StampProbe, "imagenets_test/StampProbe", "test",
                         "Reports which input stamps were paired");
