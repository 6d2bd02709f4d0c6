#include "imagenets_calibration/bag_samples.h"

#include <algorithm>
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

std::shared_ptr<const BagSamples> read(const std::string& file, const std::vector<std::string>& joints,
                                       const BagSampleSettings& s) {
  rosbag::Bag bag;
  try {
    bag.open(file, rosbag::bagmode::Read);
  } catch (const std::exception& e) {
    throw std::runtime_error(file + ": cannot read the bag: " + e.what());
  }
  // Every topic needed must be there: named when it is not, with what the bag has instead.
  std::set<std::string> topics;
  {
    rosbag::View all(bag);
    for (const rosbag::ConnectionInfo* c : all.getConnections()) topics.insert(absoluteTopic(c->topic));
  }
  const std::string left_image = s.imageTopic("left"), right_image = s.imageTopic("right");
  const std::string left_info = s.infoTopic("left"), right_info = s.infoTopic("right");
  const std::string joint_topic = s.jointStatesTopic();
  const std::vector<std::pair<std::string, std::string>> needed{
      {left_image, "the left camera's images"},       {right_image, "the right camera's images"},
      {left_info, "the left camera's camera_info"},   {right_info, "the right camera's camera_info"},
      {joint_topic, "the arm's and head's joint_states"}};
  for (const auto& n : needed) {
    if (topics.count(n.first)) continue;
    std::string have;
    for (const auto& t : topics) have += (have.empty() ? "" : ", ") + t;
    throw std::runtime_error(file + ": no topic '" + n.first + "' (" + n.second + "); the bag has " +
                             (have.empty() ? "no topics" : have));
  }
  auto on = [](const std::string& topic) {
    return [topic](const rosbag::ConnectionInfo* c) { return absoluteTopic(c->topic) == topic; };
  };

  // Pass 1: every joint reading, every image's stamp, every camera_info (small).
  std::map<std::string, std::vector<Reading>> readings;
  for (const auto& j : joints) readings[j];
  {
    rosbag::View view(bag, on(joint_topic));
    for (const rosbag::MessageInstance& m : view) {
      const auto js = m.instantiate<sensor_msgs::JointState>();
      if (!js) throw std::runtime_error(file + ": topic '" + joint_topic + "' is " + m.getDataType() + ", not sensor_msgs/JointState");
      const double t = stampOf(js->header, m).toSec();
      for (size_t i = 0; i < js->name.size() && i < js->position.size(); ++i) {
        auto it = readings.find(js->name[i]);
        if (it != readings.end()) it->second.push_back({t, js->position[i]});
      }
    }
  }
  for (auto& r : readings) {
    std::stable_sort(r.second.begin(), r.second.end(), [](const Reading& a, const Reading& b) { return a.t < b.t; });
    if (r.second.empty()) throw std::runtime_error(file + ": topic '" + joint_topic + "' never names joint '" + r.first + "'");
  }
  auto stamps = [&](const std::string& topic) {
    std::vector<double> t;
    rosbag::View view(bag, on(topic));
    for (const rosbag::MessageInstance& m : view) {
      const auto img = m.instantiate<sensor_msgs::Image>();
      if (!img) throw std::runtime_error(file + ": topic '" + topic + "' is " + m.getDataType() + ", not sensor_msgs/Image");
      t.push_back(stampOf(img->header, m).toSec());
    }
    std::sort(t.begin(), t.end());
    return t;
  };
  const std::vector<double> lefts = stamps(left_image), rights = stamps(right_image);
  auto infos = [&](const std::string& topic) {
    std::vector<std::pair<double, sensor_msgs::CameraInfoConstPtr>> v;
    rosbag::View view(bag, on(topic));
    for (const rosbag::MessageInstance& m : view) {
      const auto info = m.instantiate<sensor_msgs::CameraInfo>();
      if (!info) throw std::runtime_error(file + ": topic '" + topic + "' is " + m.getDataType() + ", not sensor_msgs/CameraInfo");
      v.emplace_back(stampOf(info->header, m).toSec(), info);
    }
    std::stable_sort(v.begin(), v.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    return v;
  };
  const auto left_infos = infos(left_info), right_infos = infos(right_info);
  const auto info_time = [](const std::pair<double, sensor_msgs::CameraInfoConstPtr>& p) { return p.first; };

  // Each left image: complete (right image, joints) and still, or skipped with a reason.
  struct Candidate {
    double left, right;
    std::vector<double> q;
  };
  std::vector<Candidate> candidates;
  Skips skips;
  char b[256];
  for (const double t : lefts) {
    const int r = nearest(rights, t, [](double x) { return x; });
    if (std::abs(rights[r] - t) > s.max_stereo_offset) {
      std::snprintf(b, sizeof b, "without a right image within %.0f ms", 1000 * s.max_stereo_offset);
      skips.add(b, t);
      continue;
    }
    Candidate c{t, rights[r], {}};
    std::string why;
    for (const auto& j : joints) {
      const auto& v = readings[j];
      const int i = nearest(v, t, [](const Reading& x) { return x.t; });
      if (std::abs(v[i].t - t) > s.max_joint_state_age) {
        std::snprintf(b, sizeof b, "without a reading of joint '%s' within %.3f s", j.c_str(), s.max_joint_state_age);
        why = b;
        break;
      }
      // Still: every reading of the joint within still_time around the image agrees.
      for (const Reading& x : v) {
        if (x.t < t - s.still_time || x.t > t + s.still_time) continue;
        if (std::abs(x.position - v[i].position) > s.still_tolerance) {
          std::snprintf(b, sizeof b, "while joints moved (by more than %g within %.2f s of the image)",
                        s.still_tolerance, s.still_time);
          why = b;
          break;
        }
      }
      if (!why.empty()) break;
      c.q.push_back(v[i].position);
    }
    if (!why.empty()) {
      skips.add(why, t);
      continue;
    }
    candidates.push_back(std::move(c));
  }

  // Still periods: consecutive candidates at the same joint positions with readings between them
  // that show no motion (readings between them at all: two samples at one pose recorded without the
  // motion between, as the node's bag of a paper-method calibration, stay two).
  std::vector<std::vector<size_t>> periods;
  for (size_t k = 0; k < candidates.size(); ++k) {
    bool same = !periods.empty();
    if (same) {
      const Candidate& p = candidates[periods.back().back()];
      const Candidate& c = candidates[k];
      for (size_t j = 0; same && j < joints.size(); ++j) {
        if (std::abs(p.q[j] - c.q[j]) > s.still_tolerance) same = false;
        bool between = false;
        for (const Reading& x : readings[joints[j]]) {
          if (x.t < p.left || x.t > c.left) continue;
          if (std::abs(x.position - p.q[j]) > s.still_tolerance) same = false;
          if (x.t > p.left && x.t < c.left) between = true;
        }
        if (!between) same = false;
      }
    }
    if (same) {
      periods.back().push_back(k);
    } else {
      periods.push_back({k});
    }
  }

  // Pass 2: the chosen images (the middle one of each still period).
  auto out = std::make_shared<BagSamples>();
  out->file = file;
  std::map<double, size_t> left_of, right_of;  // stamp -> sample
  for (const auto& period : periods) {
    const Candidate& c = candidates[period[period.size() / 2]];
    BagStereoSample sample;
    sample.left_info = left_infos[nearest(left_infos, c.left, info_time)].second;
    sample.right_info = right_infos[nearest(right_infos, c.right, info_time)].second;
    sample.joints = boost::make_shared<sensor_msgs::JointState>();
    sample.joints->header.stamp.fromSec(c.left);
    sample.joints->name = joints;
    sample.joints->position = c.q;
    left_of.emplace(c.left, out->samples.size());
    right_of.emplace(c.right, out->samples.size());
    out->samples.push_back(sample);
  }
  for (const auto& side : {std::make_pair(left_image, &left_of), std::make_pair(right_image, &right_of)}) {
    rosbag::View view(bag, on(side.first));
    for (const rosbag::MessageInstance& m : view) {
      const auto img = m.instantiate<sensor_msgs::Image>();
      const auto it = side.second->find(stampOf(img->header, m).toSec());
      if (it == side.second->end()) continue;
      auto& sample = out->samples[it->second];
      (side.second == &left_of ? sample.left : sample.right) = img;
    }
  }
  for (auto& sample : out->samples) {
    // Header-less images (stamp 0) take the time the bag received them: the sample's time too.
    if (sample.left && sample.left->header.stamp.isZero()) {
      auto copy = boost::make_shared<sensor_msgs::Image>(*sample.left);
      copy->header.stamp = sample.joints->header.stamp;
      sample.left = copy;
    }
  }

  std::ostringstream report;
  report << out->samples.size() << " samples (arm and head still, stereo pair complete) from " << lefts.size()
         << " left images in " << file;
  const size_t extra = candidates.size() - periods.size();
  if (extra > 0) report << "; " << extra << " further still pairs of the same still periods not used (one per period)";
  if (!skips.by_reason.empty()) {
    report << "; skipped:";
    bool first = true;
    for (const auto& r : skips.by_reason) {
      report << (first ? " " : ", ") << r.second.first << " " << r.first << " (first at t=" << seconds(r.second.second)
             << " s)";
      first = false;
    }
  }
  out->report = report.str();
  return out;
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
