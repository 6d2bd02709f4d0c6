// stereo_pair_publisher: publishes a rectified stereo pair read from files, with the camera_info
// of each side, under one stamp per pair, the way a stereo camera driver plus image_proc would:
//   left/image_rect_color (bgr8), left/image_rect (mono8), left/camera_info, and the same for right.
// Feeds launch-file nets such as launch/nets/stereo_point_cloud.launch.
// Private parameters: ~left_image, ~right_image (image files), ~left_camera_info,
// ~right_camera_info (camera_calibration_parsers YAML/INI), ~rate (Hz, default 2), ~frame_id
// (default left_camera_optical). Both sides carry the left optical frame, as ROS stereo drivers do:
// the right model's P holds the baseline relative to it (image_geometry requires one frame).
#include <cv_bridge/cv_bridge.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <ros/ros.h>
#include <sensor_msgs/CameraInfo.h>

#include "imagenets/vision/read_camera_info.h"
#include <sensor_msgs/Image.h>

namespace {

struct Side {
  sensor_msgs::ImagePtr colour, mono;
  sensor_msgs::CameraInfoPtr info;
  ros::Publisher colour_pub, mono_pub, info_pub;
};

bool load(ros::NodeHandle& nh, ros::NodeHandle& pnh, const std::string& side, Side& out) {
  std::string image_path, info_path, frame;
  pnh.param<std::string>("frame_id", frame, "left_camera_optical");
  pnh.param<std::string>(side + "_image", image_path, "");
  pnh.param<std::string>(side + "_camera_info", info_path, "");
  const cv::Mat image = cv::imread(image_path, cv::IMREAD_COLOR);
  if (image.empty()) {
    ROS_FATAL("parameter ~%s_image: cannot read image '%s'", side.c_str(), image_path.c_str());
    return false;
  }
  try {
    out.info.reset(new sensor_msgs::CameraInfo(imagenets::readCameraInfo(info_path)));
  } catch (const std::exception& e) {
    ROS_FATAL("parameter ~%s_camera_info: %s", side.c_str(), e.what());
    return false;
  }
  if (out.info->width != static_cast<unsigned>(image.cols) || out.info->height != static_cast<unsigned>(image.rows)) {
    ROS_FATAL("'%s' is for %ux%u images, '%s' is %dx%d", info_path.c_str(), out.info->width, out.info->height,
              image_path.c_str(), image.cols, image.rows);
    return false;
  }
  cv::Mat gray;
  cv::cvtColor(image, gray, cv::COLOR_BGR2GRAY);
  std_msgs::Header header;
  header.frame_id = frame;
  out.info->header = header;
  out.colour = cv_bridge::CvImage(header, "bgr8", image).toImageMsg();
  out.mono = cv_bridge::CvImage(header, "mono8", gray).toImageMsg();
  out.colour_pub = nh.advertise<sensor_msgs::Image>(side + "/image_rect_color", 1);
  out.mono_pub = nh.advertise<sensor_msgs::Image>(side + "/image_rect", 1);
  out.info_pub = nh.advertise<sensor_msgs::CameraInfo>(side + "/camera_info", 1);
  return true;
}

void publish(Side& s, const ros::Time& stamp) {
  // Fresh messages per pair: subscribers in the same process may still hold the previous ones.
  auto colour = boost::make_shared<sensor_msgs::Image>(*s.colour);
  auto mono = boost::make_shared<sensor_msgs::Image>(*s.mono);
  auto info = boost::make_shared<sensor_msgs::CameraInfo>(*s.info);
  colour->header.stamp = mono->header.stamp = info->header.stamp = stamp;
  s.colour_pub.publish(colour);
  s.mono_pub.publish(mono);
  s.info_pub.publish(info);
}

}  // namespace

int main(int argc, char** argv) {
  ros::init(argc, argv, "stereo_pair_publisher");
  ros::NodeHandle nh, pnh("~");
  Side left, right;
  if (!load(nh, pnh, "left", left) || !load(nh, pnh, "right", right)) return 1;
  double rate_hz = 2.0;
  pnh.param("rate", rate_hz, rate_hz);
  if (!(rate_hz > 0)) {
    ROS_FATAL("parameter ~rate: %g is not positive", rate_hz);
    return 1;
  }
  ROS_INFO("publishing a %ux%u stereo pair at %g Hz", left.info->width, left.info->height, rate_hz);
  ros::Rate rate(rate_hz);
  while (ros::ok()) {
    const ros::Time stamp = ros::Time::now();
    publish(left, stamp);
    publish(right, stamp);
    ros::spinOnce();
    rate.sleep();
  }
  return 0;
}
