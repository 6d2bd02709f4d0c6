#include "imagenets_calibration/bag_samples.h"

#include <algorithm>
#include <functional>
#include <cmath>
#include <cstdio>
#include <map>
#include <mutex>
#include <set>
#include <sstream>
#include <stdexcept>

#include <boost/filesystem.hpp>
#include <boost/make_shared.hpp>
#include <rosbag/bag.h>
#include <rosbag/view.h>

#include "robot_description/robot_model.h"

namespace imagenets_calibration {
namespace {

// "/stereo/left/image_raw" and "stereo/left/image_raw" are one topic: a bag stores resolved names.
std::string absoluteTopic(const std::string& name) { return name.empty() || name[0] == '/' ? name : "/" + name; }

// A message's time: its header stamp, else (stamp 0) when the bag received it.
ros::Time stampOf(const std_msgs::Header& header, const rosbag::MessageInstance& m) {
  return header.stamp.isZero() ? m.getTime() : header.stamp;
}

struct Reading {
  double t;
  double position;
};

// Index of the element of sorted `times` nearest to t (-1 when empty).
template <class T, class Time>
int nearest(const std::vector<T>& v, double t, Time time) {
  if (v.empty()) return -1;
  auto it = std::lower_bound(v.begin(), v.end(), t, [&](const T& a, double b) { return time(a) < b; });
  int i = static_cast<int>(it - v.begin());
  if (i == static_cast<int>(v.size())) return i - 1;
  if (i > 0 && t - time(v[i - 1]) <= time(v[i]) - t) return i - 1;
  return i;
}

std::string seconds(double t) {
  char b[32];
  std::snprintf(b, sizeof b, "%.3f", t);
  return b;
}

// Why images were skipped: count and the first one's time per reason.
struct Skips {
  std::map<std::string, std::pair<int, double>> by_reason;
  void add(const std::string& reason, double t) {
    auto it = by_reason.find(reason);
    if (it == by_reason.end()) {
      by_reason[reason] = {1, t};
    } else {
      ++it->second.first;
    }
  }
};

using CameraInfos = std::vector<std::pair<double, sensor_msgs::CameraInfoConstPtr>>;

// A left image that has its right image and every joint's reading, taken while the joints stood still.
struct Candidate {
  double left, right;
  std::vector<double> q;
};

// Reading a bag into calibration samples, in named steps: check the topics, read the joint
// readings, image stamps and camera_info (pass 1), find the still candidates and group them into
// still periods, then read the chosen images (pass 2).
class BagSampleReader {
 public:
  BagSampleReader(const std::string& file, const std::vector<std::string>& joints, const BagSampleSettings& s)
      : file_(file), joints_(joints), s_(s) {
    try {
      bag_.open(file, rosbag::bagmode::Read);
    } catch (const std::exception& e) {
      throw std::runtime_error(file + ": cannot read the bag: " + e.what());
    }
  }

  std::shared_ptr<const BagSamples> read() {
    requireTopics();
    readJointStates();
    lefts_ = imageStamps(s_.imageTopic("left"));
    rights_ = imageStamps(s_.imageTopic("right"));
    left_infos_ = cameraInfos(s_.infoTopic("left"));
    right_infos_ = cameraInfos(s_.infoTopic("right"));
    findCandidates();
    groupStillPeriods();
    auto out = chosenSamples();
    out->report = report(*out);
    return out;
  }

 private:
  static std::function<bool(const rosbag::ConnectionInfo*)> on(const std::string& topic) {
    return [topic](const rosbag::ConnectionInfo* c) { return absoluteTopic(c->topic) == topic; };
  }

  // Every topic needed must be there: named when it is not, with what the bag has instead.
  void requireTopics() {
    std::set<std::string> topics;
    rosbag::View all(bag_);
    for (const rosbag::ConnectionInfo* c : all.getConnections()) topics.insert(absoluteTopic(c->topic));
    const std::vector<std::pair<std::string, std::string>> needed{
        {s_.imageTopic("left"), "the left camera's images"},     {s_.imageTopic("right"), "the right camera's images"},
        {s_.infoTopic("left"), "the left camera's camera_info"}, {s_.infoTopic("right"), "the right camera's camera_info"},
        {s_.jointStatesTopic(), "the arm's and head's joint_states"}};
    for (const auto& n : needed) {
      if (topics.count(n.first)) continue;
      std::string have;
      for (const auto& t : topics) have += (have.empty() ? "" : ", ") + t;
      throw std::runtime_error(file_ + ": no topic '" + n.first + "' (" + n.second + "); the bag has " +
                               (have.empty() ? "no topics" : have));
    }
  }

  // Pass 1: every reading of the joints asked for, sorted by time.
  void readJointStates() {
    const std::string topic = s_.jointStatesTopic();
    for (const auto& j : joints_) readings_[j];
    rosbag::View view(bag_, on(topic));
    for (const rosbag::MessageInstance& m : view) {
      const auto js = m.instantiate<sensor_msgs::JointState>();
      if (!js) throw std::runtime_error(file_ + ": topic '" + topic + "' is " + m.getDataType() + ", not sensor_msgs/JointState");
      const double t = stampOf(js->header, m).toSec();
      for (size_t i = 0; i < js->name.size() && i < js->position.size(); ++i) {
        auto it = readings_.find(js->name[i]);
        if (it != readings_.end()) it->second.push_back({t, js->position[i]});
      }
    }
    for (auto& r : readings_) {
      std::stable_sort(r.second.begin(), r.second.end(), [](const Reading& a, const Reading& b) { return a.t < b.t; });
      if (r.second.empty()) throw std::runtime_error(file_ + ": topic '" + topic + "' never names joint '" + r.first + "'");
    }
  }

  std::vector<double> imageStamps(const std::string& topic) {
    std::vector<double> t;
    rosbag::View view(bag_, on(topic));
    for (const rosbag::MessageInstance& m : view) {
      const auto img = m.instantiate<sensor_msgs::Image>();
      if (!img) throw std::runtime_error(file_ + ": topic '" + topic + "' is " + m.getDataType() + ", not sensor_msgs/Image");
      t.push_back(stampOf(img->header, m).toSec());
    }
    std::sort(t.begin(), t.end());
    return t;
  }

  CameraInfos cameraInfos(const std::string& topic) {
    CameraInfos v;
    rosbag::View view(bag_, on(topic));
    for (const rosbag::MessageInstance& m : view) {
      const auto info = m.instantiate<sensor_msgs::CameraInfo>();
      if (!info) throw std::runtime_error(file_ + ": topic '" + topic + "' is " + m.getDataType() + ", not sensor_msgs/CameraInfo");
      v.emplace_back(stampOf(info->header, m).toSec(), info);
    }
    std::stable_sort(v.begin(), v.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    return v;
  }

  // Why the image at t cannot be a sample ("" when it can); the joints' positions go to q.
  std::string jointsAt(double t, std::vector<double>& q) {
    char b[256];
    for (const auto& j : joints_) {
      const auto& v = readings_[j];
      const int i = nearest(v, t, [](const Reading& x) { return x.t; });
      if (std::abs(v[i].t - t) > s_.max_joint_state_age) {
        std::snprintf(b, sizeof b, "without a reading of joint '%s' within %.3f s", j.c_str(), s_.max_joint_state_age);
        return b;
      }
      // Still: every reading of the joint within still_time around the image agrees.
      for (const Reading& x : v) {
        if (x.t < t - s_.still_time || x.t > t + s_.still_time) continue;
        if (std::abs(x.position - v[i].position) > s_.still_tolerance) {
          std::snprintf(b, sizeof b, "while joints moved (by more than %g within %.2f s of the image)",
                        s_.still_tolerance, s_.still_time);
          return b;
        }
      }
      q.push_back(v[i].position);
    }
    return "";
  }

  // Each left image: complete (right image, joints) and still, or skipped with a reason.
  void findCandidates() {
    for (const double t : lefts_) {
      const int r = nearest(rights_, t, [](double x) { return x; });
      if (std::abs(rights_[r] - t) > s_.max_stereo_offset) {
        char b[128];
        std::snprintf(b, sizeof b, "without a right image within %.0f ms", 1000 * s_.max_stereo_offset);
        skips_.add(b, t);
        continue;
      }
      Candidate c{t, rights_[r], {}};
      const std::string why = jointsAt(t, c.q);
      if (!why.empty()) {
        skips_.add(why, t);
        continue;
      }
      candidates_.push_back(std::move(c));
    }
  }

  // Whether candidate c continues the still period of p: the same joint positions, and readings
  // between them that show no motion (readings between them at all: two samples at one pose
  // recorded without the motion between, as the node's bag of a paper-method calibration, stay two).
  bool samePeriod(const Candidate& p, const Candidate& c) {
    for (size_t j = 0; j < joints_.size(); ++j) {
      if (std::abs(p.q[j] - c.q[j]) > s_.still_tolerance) return false;
      bool between = false;
      for (const Reading& x : readings_[joints_[j]]) {
        if (x.t < p.left || x.t > c.left) continue;
        if (std::abs(x.position - p.q[j]) > s_.still_tolerance) return false;
        if (x.t > p.left && x.t < c.left) between = true;
      }
      if (!between) return false;
    }
    return true;
  }

  void groupStillPeriods() {
    for (size_t k = 0; k < candidates_.size(); ++k) {
      if (!periods_.empty() && samePeriod(candidates_[periods_.back().back()], candidates_[k])) {
        periods_.back().push_back(k);
      } else {
        periods_.push_back({k});
      }
    }
  }

  // Pass 2: the chosen images (the middle one of each still period).
  std::shared_ptr<BagSamples> chosenSamples() {
    auto out = std::make_shared<BagSamples>();
    out->file = file_;
    const auto info_time = [](const std::pair<double, sensor_msgs::CameraInfoConstPtr>& p) { return p.first; };
    std::map<double, size_t> left_of, right_of;  // stamp -> sample
    for (const auto& period : periods_) {
      const Candidate& c = candidates_[period[period.size() / 2]];
      BagStereoSample sample;
      sample.left_info = left_infos_[nearest(left_infos_, c.left, info_time)].second;
      sample.right_info = right_infos_[nearest(right_infos_, c.right, info_time)].second;
      sample.joints = boost::make_shared<sensor_msgs::JointState>();
      sample.joints->header.stamp.fromSec(c.left);
      sample.joints->name = joints_;
      sample.joints->position = c.q;
      left_of.emplace(c.left, out->samples.size());
      right_of.emplace(c.right, out->samples.size());
      out->samples.push_back(sample);
    }
    readImages(s_.imageTopic("left"), left_of, *out, &BagStereoSample::left);
    readImages(s_.imageTopic("right"), right_of, *out, &BagStereoSample::right);
    for (auto& sample : out->samples) {
      // Header-less images (stamp 0) take the time the bag received them: the sample's time too.
      if (sample.left && sample.left->header.stamp.isZero()) {
        auto copy = boost::make_shared<sensor_msgs::Image>(*sample.left);
        copy->header.stamp = sample.joints->header.stamp;
        sample.left = copy;
      }
    }
    return out;
  }

  void readImages(const std::string& topic, const std::map<double, size_t>& sample_of, BagSamples& out,
                  sensor_msgs::ImageConstPtr BagStereoSample::*side) {
    rosbag::View view(bag_, on(topic));
    for (const rosbag::MessageInstance& m : view) {
      const auto img = m.instantiate<sensor_msgs::Image>();
      const auto it = sample_of.find(stampOf(img->header, m).toSec());
      if (it != sample_of.end()) out.samples[it->second].*side = img;
    }
  }

  std::string report(const BagSamples& out) const {
    std::ostringstream report;
    report << out.samples.size() << " samples (arm and head still, stereo pair complete) from " << lefts_.size()
           << " left images in " << file_;
    const size_t extra = candidates_.size() - periods_.size();
    if (extra > 0) report << "; " << extra << " further still pairs of the same still periods not used (one per period)";
    if (!skips_.by_reason.empty()) {
      report << "; skipped:";
      bool first = true;
      for (const auto& r : skips_.by_reason) {
        report << (first ? " " : ", ") << r.second.first << " " << r.first << " (first at t=" << seconds(r.second.second)
               << " s)";
        first = false;
      }
    }
    return report.str();
  }

  const std::string file_;
  const std::vector<std::string> joints_;
  const BagSampleSettings s_;
  rosbag::Bag bag_;
  std::map<std::string, std::vector<Reading>> readings_;
  std::vector<double> lefts_, rights_;
  CameraInfos left_infos_, right_infos_;
  std::vector<Candidate> candidates_;
  std::vector<std::vector<size_t>> periods_;
  Skips skips_;
};

std::shared_ptr<const BagSamples> read(const std::string& file, const std::vector<std::string>& joints,
                                       const BagSampleSettings& s) {
  return BagSampleReader(file, joints, s).read();
}

}  // namespace

std::string BagSampleSettings::imageTopic(const std::string& side) const {
  return absoluteTopic(camera + "/" + side + "/image_raw");
}
std::string BagSampleSettings::infoTopic(const std::string& side) const {
  return absoluteTopic(camera + "/" + side + "/camera_info");
}
std::string BagSampleSettings::jointStatesTopic() const { return absoluteTopic(joint_states); }

std::vector<std::string> sampleJoints(const robot_description::RobotModel& model) {
  std::vector<std::string> joints = model.description().arm.names();
  for (const auto& name : model.description().head.names()) joints.push_back(name);
  return joints;
}

std::shared_ptr<const BagSamples> readBagSamples(const std::string& file, const std::vector<std::string>& joints,
                                                 const BagSampleSettings& settings) {
  if (joints.empty()) throw std::invalid_argument("readBagSamples: no joints named");
  std::time_t modified = 0;
  try {
    modified = boost::filesystem::last_write_time(file);
  } catch (const std::exception&) {
    throw std::runtime_error(file + ": no such bag file");
  }
  std::ostringstream key;
  key.precision(17);
  key << file << '|' << modified << '|' << settings.camera << '|' << settings.joint_states << '|' << settings.still_time
      << '|' << settings.still_tolerance << '|' << settings.max_stereo_offset << '|' << settings.max_joint_state_age;
  for (const auto& j : joints) key << '|' << j;
  // The last bag read, kept: the plan counts its samples, then each repetition takes one.
  static std::mutex mutex;
  static std::string cached_key;
  static std::shared_ptr<const BagSamples> cached;
  std::lock_guard<std::mutex> lock(mutex);
  if (!cached || cached_key != key.str()) {
    cached.reset();
    cached = read(file, joints, settings);
    cached_key = key.str();
  }
  return cached;
}

}  // namespace imagenets_calibration
