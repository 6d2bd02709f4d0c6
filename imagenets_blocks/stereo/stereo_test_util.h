// A synthetic rectified pair for the stereo tests (from the SyntheticStereoPair block).
#pragma once

#include <sensor_msgs/CameraInfo.h>

#include "imagenets/blocks/block_harness.h"

namespace imagenets {
namespace blocks {
namespace test {

// 320x240, fx 300 px, baseline 0.1 m: the wall at 2.5 m has disparity 12 px, the 0.6 m board
// at 1.25 m has 24 px.
inline BlockHarness syntheticPair() {
  BlockHarness pair("imagenets/SyntheticStereoPair");
  pair.set("width", 320).set("height", 240).set("focal_length", 300.0).set("baseline", 0.1);
  pair.set("far_depth", 2.5).set("near_depth", 1.25).set("near_size", 0.6).set("texture_scale", 0.012);
  pair.run();
  return pair;
}

}  // namespace test
}  // namespace blocks
}  // namespace imagenets
