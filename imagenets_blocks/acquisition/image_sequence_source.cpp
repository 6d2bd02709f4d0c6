#include <algorithm>

#include <boost/filesystem.hpp>
#include <opencv2/imgcodecs.hpp>

#include "imagenets/blocks/image.h"
#include "imagenets/register_block.h"
#include "imagenets/time.h"

namespace imagenets {
namespace blocks {

// One image of a folder of images, sorted by file name: `index` selects it, so stepping through a
// sequence is a property change (the executor re-runs only what depends on it).
class ImageSequenceSource : public Block {
 public:
  ImageSequenceSource() {
    addOutput<sensor_msgs::Image>("image", "image number `index` of the folder");
    addProperty<std::string>("folder", "", "folder of images; relative to the net file").path();
    addProperty<std::string>("extensions", ".png,.jpg,.jpeg,.bmp,.tif,.tiff,.pgm,.ppm",
                             "comma-separated file extensions to include (case-insensitive)");
    addProperty<int>("index", 0, "which image, 0-based, in file-name order").range(0, 1000000);
    addProperty<bool>("wrap", false, "an index past the end wraps around instead of failing");
    addProperty<std::string>("encoding", "bgr8", "bgr8: colour, mono8: gray").choices({"bgr8", "mono8"});
    addProperty<std::string>("frame_id", "camera", "frame_id of the image header");
  }

  void process(Context& ctx) override {
    namespace fs = boost::filesystem;
    const auto folder = ctx.property<std::string>("folder");
    if (folder.empty()) throw BlockError("property 'folder' is empty");
    boost::system::error_code ec;
    if (!fs::is_directory(folder, ec)) throw BlockError("property 'folder': '" + folder + "' is not a folder");
    const std::string extensions = "," + lower(ctx.property<std::string>("extensions")) + ",";
    std::vector<std::string> files;
    for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec)) {
      if (!fs::is_regular_file(it->path(), ec)) continue;
      const std::string ext = lower(it->path().extension().string());
      if (!ext.empty() && extensions.find("," + ext + ",") != std::string::npos) files.push_back(it->path().string());
    }
    if (files.empty()) throw BlockError("property 'folder': no images in '" + folder + "'");
    std::sort(files.begin(), files.end());
    size_t index = static_cast<size_t>(ctx.property<int>("index"));
    if (index >= files.size()) {
      if (!ctx.property<bool>("wrap")) {
        throw BlockError("property 'index': " + std::to_string(index) + " is past the last of " +
                         std::to_string(files.size()) + " images in '" + folder + "'");
      }
      index %= files.size();
    }
    const bool mono = ctx.property<std::string>("encoding") == "mono8";
    cv::Mat image = cv::imread(files[index], mono ? cv::IMREAD_GRAYSCALE : cv::IMREAD_COLOR);
    if (image.empty()) throw BlockError("cannot read image '" + files[index] + "'");
    std_msgs::Header header;
    header.stamp = now();
    header.frame_id = ctx.property<std::string>("frame_id");
    header.seq = static_cast<uint32_t>(index);
    ctx.output("image", toImageMsg(image, mono ? "mono8" : "bgr8", header));
  }

 private:
  static std::string lower(std::string s) {
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
    return s;
  }
};

}  // namespace blocks
}  // namespace imagenets

IMAGENETS_REGISTER_BLOCK(imagenets::blocks::ImageSequenceSource, "imagenets/ImageSequenceSource", "acquisition",
                         "Reads image number `index` of a folder (file-name order)");
