// What the grab blocks (GrabStereoPair, GrabImage) share: images taken after the robot has
// settled. Waits until joint_states report no motion for `settle_time`, then (optionally) triggers
// the camera (NS/trigger, std_srvs/Trigger), and takes the first set of images -- one image and
// camera_info per camera, all with one stamp -- stamped after that moment. The properties are
// declared once here for both blocks.
#pragma once

#include <string>
#include <vector>

#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>

#include "imagenets/block.h"

namespace imagenets {
namespace blocks {
namespace hardware {

// The properties: `camera` (the namespace NS, default `camera`, described by `camera_doc`),
// joint_states, settle_time, still_velocity, trigger, retrigger, timeout.
std::vector<PropertySpec> settledGrabProperties(const std::string& camera, const std::string& camera_doc);

struct GrabbedImage {
  sensor_msgs::ImageConstPtr image;
  sensor_msgs::CameraInfoConstPtr info;
};
// One image per camera of `cameras` (sub-namespaces of the property `camera`: "left", "right";
// "" the namespace itself), in that order, with equal stamps. Throws BlockError naming the topics
// and the property when the robot does not settle or a camera stays silent within `timeout`.
std::vector<GrabbedImage> grabSettled(Context& ctx, const std::vector<std::string>& cameras);

}  // namespace hardware
}  // namespace blocks
}  // namespace imagenets
