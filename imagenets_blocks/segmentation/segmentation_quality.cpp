#include <std_msgs/Float64.h>

#include "imagenets/blocks/image.h"
#include "imagenets/register_block.h"

namespace imagenets {
namespace blocks {

// How well a binary segmentation separates the gray image into two classes: the between-class
// variance over the total variance (Otsu's separability, 0..1; 1 = two clean gray levels). A
// score for feedback on a threshold until a task-specific score (a marker's confidence) exists.
class SegmentationQuality : public Block {
 public:
  SegmentationQuality() {
    addInput<sensor_msgs::Image>("gray", "mono8 image that was segmented");
    addInput<sensor_msgs::Image>("binary", "mono8 segmentation of it (0 = background, else foreground)");
    addOutput<std_msgs::Float64>("score", "between-class / total variance, 0..1");
  }

  void process(Context& ctx) override {
    cv::Mat gray = inputImage(ctx, "gray", {"mono8"});
    cv::Mat binary = inputImage(ctx, "binary", {"mono8"});
    if (gray.size() != binary.size()) {
      throw BlockError("inputs 'gray' (" + std::to_string(gray.cols) + "x" + std::to_string(gray.rows) +
                       ") and 'binary' (" + std::to_string(binary.cols) + "x" + std::to_string(binary.rows) +
                       ") differ in size");
    }
    double n[2] = {0, 0}, sum[2] = {0, 0}, sum_sq = 0;
    for (int y = 0; y < gray.rows; ++y) {
      const uint8_t* g = gray.ptr<uint8_t>(y);
      const uint8_t* b = binary.ptr<uint8_t>(y);
      for (int x = 0; x < gray.cols; ++x) {
        const int cls = b[x] ? 1 : 0;
        n[cls] += 1;
        sum[cls] += g[x];
        sum_sq += static_cast<double>(g[x]) * g[x];
      }
    }
    const double total = n[0] + n[1];
    const double mean = (sum[0] + sum[1]) / total;
    const double variance = sum_sq / total - mean * mean;
    double between = 0;
    for (int c = 0; c < 2; ++c) {
      if (n[c] > 0) between += n[c] / total * std::pow(sum[c] / n[c] - mean, 2);
    }
    auto score = boost::make_shared<std_msgs::Float64>();
    score->data = variance > 0 ? between / variance : 0.0;
    ctx.output("score", score);
  }
};

}  // namespace blocks
}  // namespace imagenets

IMAGENETS_REGISTER_BLOCK(imagenets::blocks::SegmentationQuality, "imagenets/SegmentationQuality", "segmentation",
                         "Scores a binary segmentation by class separability (Otsu)");
