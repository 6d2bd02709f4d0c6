#include "imagenets_calibration/calibration_net_interface.h"

#include <algorithm>
#include <set>
#include <stdexcept>

#include "imagenets/inner_net.h"
#include "imagenets/net_port.h"
#include "imagenets/port_type.h"

namespace imagenets_calibration {
namespace {

using imagenets::NetPort;

const std::string kResultType = "imagenets_calibration_msgs/CalibrationResult";
const std::string kSampleType = "imagenets_calibration_msgs/CalibrationSample";
const std::string kImageSuffix = "_image";

std::string joined(const std::vector<std::string>& names) {
  std::string text;
  for (const auto& n : names) text += (text.empty() ? "" : ", ") + n;
  return text.empty() ? "none" : text;
}

// The nodes that `node` depends on (through its inputs, transitively).
std::set<int> ancestors(const imagenets::Net& net, int node) {
  std::set<int> found;
  std::vector<int> open{node};
  while (!open.empty()) {
    const int n = open.back();
    open.pop_back();
    for (const imagenets::Endpoint& from : net.node(n).input_links) {
      if (from.valid() && found.insert(from.node).second) open.push_back(from.node);
    }
  }
  return found;
}

// The nodes fed, directly or not, by the output `source` (that port only, not its block's others).
std::set<int> fedBy(const imagenets::Net& net, const imagenets::Endpoint& source) {
  std::set<int> found;
  for (size_t n = 0; n < net.nodes().size(); ++n) {
    for (const imagenets::Endpoint& from : net.nodes()[n].input_links) {
      if (from.node != source.node || from.port != source.port) continue;
      found.insert(static_cast<int>(n));
      for (int d : net.descendants(static_cast<int>(n))) found.insert(d);
    }
  }
  return found;
}

imagenets::InnerNet* innerNetOf(const imagenets::Net& net, const std::string& block) {
  const int node = net.findNode(block);
  return node < 0 ? nullptr : dynamic_cast<imagenets::InnerNet*>(net.node(node).block.get());
}

}  // namespace

const MarkerObservation& observationOf(const Sample& sample, const std::string& camera) {
  return camera == "right" ? sample.right : camera == "mono" ? sample.mono : sample.left;
}

CalibrationNetInterface::CalibrationNetInterface(imagenets::Executor& exec) : exec_(&exec) {
  const imagenets::Net& net = exec.net();
  for (const char* block : {"plan", "solve"}) {
    if (net.findNode(block) < 0) {
      throw std::runtime_error(net.origin() + ": no block '" + block + "' (the node sets its properties)");
    }
  }
  result_ = outputOf(net, "result", kResultType, true, "the calibration's result");
  const imagenets::InnerNet* samples = innerNetOf(net, samples_block_);
  if (!samples || !samples->innerExecutor()) {
    throw std::runtime_error(net.origin() + ": no block '" + samples_block_ +
                             "' running the sample net (an imagenets/SubNet repeated once per sample)");
  }
  const imagenets::Net& sample_net = samples->innerExecutor()->net();
  sample_ = outputOf(sample_net, "sample", kSampleType, true, "the sample of each repetition");
  findCameras(sample_net);
  if (const imagenets::Executor* until = untilNet()) {
    until_result_ = outputOf(until->net(), "result", kResultType, false, "");
  }
}

std::string CalibrationNetInterface::outputOf(const imagenets::Net& net, const std::string& port,
                                              const std::string& type, bool required, const std::string& what) {
  const int node = imagenets::findNetPort(net, NetPort::Direction::Out, port);
  if (node < 0) {
    if (!required) return "";
    throw std::runtime_error(net.origin() + ": no output '" + port + "' (" + type + ": " + what +
                             "; its outputs: " + joined(imagenets::netPortNames(net, NetPort::Direction::Out)) + ")");
  }
  const std::string block_port = net.node(node).name + ".value";
  const imagenets::Endpoint value = net.resolveOutput(block_port);
  const std::string& actual = net.node(value.node).block->outputs()[value.port].type->name;
  if (actual != type) {
    throw std::runtime_error(net.origin() + ": output '" + port + "' is " + actual + ", expected " + type);
  }
  return block_port;
}

void CalibrationNetInterface::findCameras(const imagenets::Net& sample_net) {
  const std::set<int> make_sample = ancestors(sample_net, sample_net.findNode(sample_.substr(0, sample_.find('.'))));
  for (const std::string& port : imagenets::netPortNames(sample_net, NetPort::Direction::Out)) {
    if (port.size() <= kImageSuffix.size() ||
        port.compare(port.size() - kImageSuffix.size(), kImageSuffix.size(), kImageSuffix) != 0) {
      continue;
    }
    const std::string camera = port.substr(0, port.size() - kImageSuffix.size());
    const std::string image = outputOf(sample_net, port, "sensor_msgs/Image", true, "");
    const std::string info = outputOf(sample_net, camera + "_info", "sensor_msgs/CameraInfo", true,
                                      "the camera_info of output '" + port + "'");
    // The image's processing: what its image feeds on the way to the sample (not the net's ports).
    const imagenets::Net::Node& image_node = sample_net.node(sample_net.findNode(image.substr(0, image.find('.'))));
    std::vector<std::string> blocks;
    for (int n : fedBy(sample_net, image_node.input_links.at(0))) {
      if (make_sample.count(n) && !dynamic_cast<const NetPort*>(sample_net.node(n).block.get())) {
        blocks.push_back(sample_net.node(n).name);
      }
    }
    cameras_.push_back(camera);
    image_outputs_.push_back(image);
    info_outputs_.push_back(info);
    image_blocks_.push_back(blocks);
  }
}

imagenets::Executor* CalibrationNetInterface::untilNet() const {
  const imagenets::InnerNet* inner = innerNetOf(exec_->net(), samples_block_);
  if (!inner) return nullptr;
  for (const imagenets::InnerExecutorRef& net : inner->innerExecutors()) {
    if (net.path == "until") return net.executor;
  }
  return nullptr;
}

const imagenets::Executor* CalibrationNetInterface::sampleNet() const {
  const imagenets::InnerNet* inner = innerNetOf(exec_->net(), samples_block_);
  return inner ? inner->innerExecutor() : nullptr;
}

boost::shared_ptr<const imagenets_calibration_msgs::CalibrationResult> CalibrationNetInterface::result() const {
  return exec_->output<imagenets_calibration_msgs::CalibrationResult>(result_);
}

boost::shared_ptr<const imagenets_calibration_msgs::CalibrationResult> CalibrationNetInterface::untilResult() const {
  const imagenets::Executor* until = untilNet();
  if (!until || until_result_.empty()) return nullptr;
  return until->output<imagenets_calibration_msgs::CalibrationResult>(until_result_);
}

boost::shared_ptr<const imagenets_calibration_msgs::CalibrationSample> CalibrationNetInterface::sample() const {
  const imagenets::Executor* net = sampleNet();
  return net ? net->output<imagenets_calibration_msgs::CalibrationSample>(sample_) : nullptr;
}

CameraImages CalibrationNetInterface::images() const {
  CameraImages images;
  const imagenets::Executor* net = sampleNet();
  if (!net) return images;
  for (size_t i = 0; i < cameras_.size(); ++i) {
    CameraImage c{cameras_[i], net->output<sensor_msgs::Image>(image_outputs_[i]),
                  net->output<sensor_msgs::CameraInfo>(info_outputs_[i])};
    if (c.image && c.info) images.push_back(c);
  }
  return images;
}

}  // namespace imagenets_calibration
