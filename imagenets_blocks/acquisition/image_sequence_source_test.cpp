#include <fstream>

#include <boost/filesystem.hpp>
#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "imagenets/blocks/block_harness.h"
#include "imagenets/blocks/image.h"

using namespace imagenets::blocks;
namespace fs = boost::filesystem;

TEST(ImageSequenceSource, ReadsImagesInNameOrder) {
  const fs::path dir = fs::temp_directory_path() / fs::unique_path("sequence-%%%%%%");
  fs::create_directories(dir);
  // Written out of order; gray level = position in name order * 10.
  for (int i : {2, 0, 1}) {
    cv::imwrite((dir / ("frame_" + std::to_string(i) + ".png")).string(), cv::Mat(8, 8, CV_8UC1, cv::Scalar(i * 10)));
  }
  std::ofstream((dir / "notes.txt").string()) << "not an image";
  BlockHarness h("imagenets/ImageSequenceSource");
  h.set("folder", dir.string()).set("encoding", "mono8").set("index", 1);
  h.run();
  auto img = h.output<sensor_msgs::Image>("image");
  ASSERT_TRUE(img);
  EXPECT_EQ(img->encoding, "mono8");
  EXPECT_EQ(img->data[0], 10);
  h.set("index", 5);
  EXPECT_NE(h.runError().find("property 'index': 5 is past the last of 3 images"), std::string::npos) << h.runError();
  EXPECT_FALSE(h.hasOutput("image"));
  h.set("wrap", true);
  h.run();
  EXPECT_EQ(h.output<sensor_msgs::Image>("image")->data[0], 20);  // 5 % 3 = 2
  fs::remove_all(dir);
  EXPECT_NE(h.runError().find("is not a folder"), std::string::npos);
}
