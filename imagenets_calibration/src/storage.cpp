#include "imagenets_calibration/storage.h"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iomanip>
#include <limits>
#include <sstream>
#include <stdexcept>

#include <unistd.h>
#include <boost/crc.hpp>
#include <yaml-cpp/yaml.h>

#include "robot_description/urdf_writer.h"

namespace imagenets_calibration {
namespace fs = std::filesystem;
namespace {

void emitFrame(YAML::Emitter& out, const Eigen::Isometry3d& t) {
  const Eigen::Quaterniond q(t.rotation());
  const Eigen::Vector3d rpy = robot_description::rpyOf(t.rotation()) * 180.0 / M_PI;
  out << YAML::Flow << YAML::BeginMap;
  out << YAML::Key << "xyz" << YAML::Value << YAML::Flow << YAML::BeginSeq << t.translation().x()
      << t.translation().y() << t.translation().z() << YAML::EndSeq;
  out << YAML::Key << "quaternion_xyzw" << YAML::Value << YAML::Flow << YAML::BeginSeq << q.x() << q.y() << q.z()
      << q.w() << YAML::EndSeq;
  out << YAML::Key << "rpy_deg" << YAML::Value << YAML::Flow << YAML::BeginSeq << rpy.x() << rpy.y() << rpy.z()
      << YAML::EndSeq;
  out << YAML::EndMap;
}

void emitVector(YAML::Emitter& out, const Eigen::Vector3d& v) {
  out << YAML::Flow << YAML::BeginSeq << v.x() << v.y() << v.z() << YAML::EndSeq;
}

template <class T>
void emitList(YAML::Emitter& out, const std::vector<T>& v) {
  out << YAML::Flow << YAML::BeginSeq;
  for (const auto& x : v) out << x;
  out << YAML::EndSeq;
}

void emitObservation(YAML::Emitter& out, const MarkerObservation& o) {
  out << YAML::BeginMap;
  out << YAML::Key << "found" << YAML::Value << o.found;
  if (o.found) {
    out << YAML::Key << "pose" << YAML::Value;
    emitFrame(out, o.pose);
    out << YAML::Key << "confidence" << YAML::Value << o.confidence;
    out << YAML::Key << "threshold" << YAML::Value << o.threshold;
    out << YAML::Key << "reprojection_error" << YAML::Value << o.reprojection_error;
    out << YAML::Key << "points" << YAML::Value << YAML::Flow << YAML::BeginSeq;
    for (const auto& p : o.points) out << YAML::Flow << YAML::BeginSeq << p.x() << p.y() << YAML::EndSeq;
    out << YAML::EndSeq;
    // A target's corners: their ids and where they are on it (none: the square marker's 8 points).
    if (!o.point_ids.empty()) {
      out << YAML::Key << "point_ids" << YAML::Value;
      emitList(out, o.point_ids);
    }
    if (!o.object_points.empty()) {
      out << YAML::Key << "object_points" << YAML::Value << YAML::Flow << YAML::BeginSeq;
      for (const auto& p : o.object_points) out << YAML::Flow << YAML::BeginSeq << p.x() << p.y() << p.z() << YAML::EndSeq;
      out << YAML::EndSeq;
    }
  } else {
    out << YAML::Key << "reason" << YAML::Value << o.reason;
  }
  out << YAML::EndMap;
}

constexpr const char* kCrcKey = "crc32: ";

std::uint32_t crc32(const std::string& bytes) {
  boost::crc_32_type crc;
  crc.process_bytes(bytes.data(), bytes.size());
  return crc.checksum();
}

// Throws unless `text` ends with the line "crc32: 0x........" holding the CRC-32 of all before it.
void checkCrc(const std::string& path, const std::string& text) {
  const std::string file = "calibration file '" + path + "'";
  if (text.find_first_not_of(" \t\r\n") == std::string::npos) throw std::runtime_error(file + " is empty");
  const size_t at = text.rfind(std::string("\n") + kCrcKey);
  const size_t end = at == std::string::npos ? at : text.find('\n', at + 1);
  if (end == std::string::npos || end + 1 != text.size()) {
    throw std::runtime_error(file + " is incomplete: its last line is not its '" + std::string(kCrcKey) +
                             "0x...' line (cut short?)");
  }
  const std::string written = text.substr(at + 1 + std::strlen(kCrcKey), end - at - 1 - std::strlen(kCrcKey));
  char actual[16];
  std::snprintf(actual, sizeof actual, "0x%08x", crc32(text.substr(0, at + 1)));
  if (written != actual) {
    throw std::runtime_error(file + " is corrupt: it says " + kCrcKey + written + " but its content gives " + actual +
                             " (altered or damaged; calibrate again, or put back an archived copy)");
  }
}

// Writes `bytes` to `path` atomically: into a temporary file beside it, renamed over it when
// complete, so a reader sees the old file or the new one, never a part. `before_rename` runs when
// the temporary file is complete. Throws naming `what` and the path; the old file is then untouched.
void writeAtomically(const std::string& path, const std::string& bytes, const std::string& what,
                     const std::function<void()>& before_rename = {}) {
  const fs::path target(path);
  std::error_code ec;
  if (target.has_parent_path()) fs::create_directories(target.parent_path(), ec);
  if (ec) throw std::runtime_error("cannot create the directory of '" + path + "': " + ec.message());
  const std::string tmp = path + ".tmp." + std::to_string(::getpid());
  // Temporary files of a writer that died before its rename (killed, power cut): never used.
  const fs::path dir = target.parent_path().empty() ? "." : target.parent_path();
  if (fs::is_directory(dir, ec)) {
    const std::string prefix = target.filename().string() + ".tmp.";
    for (const auto& e : fs::directory_iterator(dir, ec)) {
      if (e.path().filename().string().rfind(prefix, 0) == 0) fs::remove(e.path(), ec);
    }
  }
  {
    std::ofstream f(tmp, std::ios::trunc | std::ios::binary);
    f << bytes;
    f.flush();
    if (!f) {
      fs::remove(tmp, ec);
      throw std::runtime_error("cannot write " + what + " '" + tmp + "'");
    }
  }
  try {
    if (before_rename) before_rename();
  } catch (...) {
    fs::remove(tmp, ec);
    throw;
  }
  fs::rename(tmp, target, ec);
  if (ec) {
    fs::remove(tmp, ec);
    throw std::runtime_error("cannot move the new " + what + " into place at '" + path + "': " + ec.message());
  }
}

// --- reading ---
struct Reader {
  std::string file;
  YAML::Node get(const YAML::Node& n, const std::string& key, const std::string& where) const {
    const YAML::Node v = n[key];
    if (!v) throw std::runtime_error("calibration file '" + file + "': missing key '" + where + key + "'");
    return v;
  }
  std::vector<double> numbers(const YAML::Node& n, const std::string& key, const std::string& where, size_t count) const {
    const YAML::Node v = get(n, key, where);
    std::vector<double> out;
    try {
      out = v.as<std::vector<double>>();
    } catch (const YAML::Exception&) {
      throw std::runtime_error("calibration file '" + file + "': '" + where + key + "' is not a list of numbers");
    }
    if (count && out.size() != count) {
      throw std::runtime_error("calibration file '" + file + "': '" + where + key + "' has " +
                               std::to_string(out.size()) + " values, expected " + std::to_string(count));
    }
    for (double x : out) {
      if (!std::isfinite(x)) throw std::runtime_error("calibration file '" + file + "': '" + where + key + "' is not finite");
    }
    return out;
  }
  Eigen::Isometry3d frame(const YAML::Node& n, const std::string& key, const std::string& where) const {
    const YAML::Node f = get(n, key, where);
    const auto xyz = numbers(f, "xyz", where + key + ".", 3);
    const auto q = numbers(f, "quaternion_xyzw", where + key + ".", 4);
    const Eigen::Quaterniond quat(q[3], q[0], q[1], q[2]);
    if (std::abs(quat.norm() - 1.0) > 1e-3) {
      throw std::runtime_error("calibration file '" + file + "': '" + where + key + ".quaternion_xyzw' is not a unit quaternion");
    }
    Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
    t.linear() = quat.normalized().toRotationMatrix();
    t.translation() = Eigen::Vector3d(xyz[0], xyz[1], xyz[2]);
    return t;
  }
  MarkerObservation observation(const YAML::Node& n, const std::string& key, const std::string& where) const {
    const YAML::Node o = get(n, key, where);
    const std::string w = where + key + ".";
    MarkerObservation obs;
    obs.found = get(o, "found", w).as<bool>();
    if (obs.found) {
      obs.pose = frame(o, "pose", w);
      obs.confidence = get(o, "confidence", w).as<double>();
      obs.threshold = get(o, "threshold", w).as<double>();
      obs.reprojection_error = get(o, "reprojection_error", w).as<double>();
      if (o["points"]) {
        for (const auto& p : o["points"]) {
          const auto v = p.as<std::vector<double>>();
          if (v.size() != 2) throw std::runtime_error("calibration file '" + file + "': '" + w + "points' needs [x, y] pairs");
          obs.points.emplace_back(v[0], v[1]);
        }
      }
      if (o["point_ids"]) obs.point_ids = o["point_ids"].as<std::vector<int>>();
      if (o["object_points"]) {
        for (const auto& p : o["object_points"]) {
          const auto v = p.as<std::vector<double>>();
          if (v.size() != 3) throw std::runtime_error("calibration file '" + file + "': '" + w + "object_points' needs [x, y, z] triples");
          obs.object_points.emplace_back(v[0], v[1], v[2]);
        }
      }
      if ((!obs.point_ids.empty() && obs.point_ids.size() != obs.points.size()) ||
          (!obs.object_points.empty() && obs.object_points.size() != obs.points.size())) {
        throw std::runtime_error("calibration file '" + file + "': '" + w + "point_ids' / 'object_points' do not match its " +
                                 std::to_string(obs.points.size()) + " points");
      }
    } else if (o["reason"]) {
      obs.reason = o["reason"].as<std::string>();
    }
    return obs;
  }
};

}  // namespace

std::string utcStamp(bool iso) {
  const std::time_t now = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&now, &tm);
  char b[40];
  std::strftime(b, sizeof b, iso ? "%Y-%m-%dT%H:%M:%SZ" : "%Y%m%dT%H%M%SZ", &tm);
  return b;
}

namespace {

// The estimated parameters and the samples' spread.
void emitEstimate(YAML::Emitter& out, const Result& r) {
  out << YAML::Key << "fixed_point" << YAML::Value;
  emitFrame(out, r.fixed_point);
  out << YAML::Key << "marker_offset" << YAML::Value;
  emitFrame(out, r.marker_offset);
  if (!r.arm_joint_offsets.empty()) {
    out << YAML::Key << "arm_joint_offsets" << YAML::Value;
    emitList(out, r.arm_joint_offsets);
    out << YAML::Key << "head_joint_offsets" << YAML::Value;
    emitList(out, r.head_joint_offsets);
  }
  out << YAML::Key << "std_dev_translation" << YAML::Value;
  emitVector(out, r.std_translation);
  out << YAML::Key << "std_dev_rotation" << YAML::Value;
  emitVector(out, r.std_rotation);
}

// x y z (m) and rx ry rz (rad, about the parent frame's axes).
void emitStd(YAML::Emitter& out, const char* key, const Eigen::Matrix<double, 6, 1>& std) {
  out << YAML::Key << key << YAML::Value << YAML::Flow << YAML::BeginMap;
  out << YAML::Key << "xyz" << YAML::Value;
  emitVector(out, std.head<3>());
  out << YAML::Key << "rotation" << YAML::Value;
  emitVector(out, std.tail<3>());
  out << YAML::EndMap;
}

// The pixel-level fit's uncertainty (calibration.h): row-major 6x6, (translation m, rotation rad).
void emitUncertainty(YAML::Emitter& out, const Uncertainty& u) {
  // One standard deviation per estimated parameter (0: held at its nominal value), for the reader:
  // the square roots of the covariances' diagonals, and the joint offsets' below.
  emitStd(out, "fixed_point_std_dev", u.fixedPointStd());
  emitStd(out, "marker_offset_std_dev", u.markerOffsetStd());
  out << YAML::Key << "fixed_point_covariance" << YAML::Value;
  emitList(out, std::vector<double>(u.fixed_point_covariance.data(), u.fixed_point_covariance.data() + 36));
  out << YAML::Key << "marker_offset_covariance" << YAML::Value;
  emitList(out, std::vector<double>(u.marker_offset_covariance.data(), u.marker_offset_covariance.data() + 36));
  out << YAML::Key << "arm_joint_offset_std" << YAML::Value;
  emitList(out, u.arm_joint_offset_std);
  out << YAML::Key << "head_joint_offset_std" << YAML::Value;
  emitList(out, u.head_joint_offset_std);
  out << YAML::Key << "reprojection_rms" << YAML::Value << u.reprojection_rms;
  // Which parameters the poses did not determine (observability.h); inf is written as .inf.
  out << YAML::Key << "observability" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "condition_number" << YAML::Value << u.condition_number;
  out << YAML::Key << "unobservable" << YAML::Value;
  emitList(out, u.unobservable);
  out << YAML::EndMap;
}

void emitRejections(YAML::Emitter& out, const Result& r) {
  out << YAML::Key << "used" << YAML::Value;
  emitList(out, r.used);
  out << YAML::Key << "rejected" << YAML::Value << YAML::BeginSeq;
  for (size_t i = 0; i < r.rejected.size(); ++i) {
    out << YAML::Flow << YAML::BeginMap << YAML::Key << "sample" << YAML::Value << r.rejected[i] << YAML::Key
        << "reason" << YAML::Value << (i < r.rejection_reasons.size() ? r.rejection_reasons[i] : "") << YAML::EndMap;
  }
  out << YAML::EndSeq;
}

void emitSample(YAML::Emitter& out, const Result& r, size_t i) {
  const Sample& s = r.samples[i];
  out << YAML::BeginMap;
  out << YAML::Key << "index" << YAML::Value << i;
  out << YAML::Key << "stamp" << YAML::Value << s.stamp;
  out << YAML::Key << "arm_q" << YAML::Value;
  emitList(out, s.arm_q);
  out << YAML::Key << "head_q" << YAML::Value;
  emitList(out, s.head_q);
  out << YAML::Key << "left" << YAML::Value;
  emitObservation(out, s.left);
  out << YAML::Key << "right" << YAML::Value;
  emitObservation(out, s.right);
  if (s.mono.found || !s.mono.reason.empty()) {  // (a stereo calibration's file has none)
    out << YAML::Key << "mono" << YAML::Value;
    emitObservation(out, s.mono);
  }
  out << YAML::Key << "valid" << YAML::Value << s.valid;
  out << YAML::Key << "fusion" << YAML::Value << s.fusion;
  out << YAML::Key << "reason" << YAML::Value << s.reason;
  if (s.valid) {
    out << YAML::Key << "fixed_point" << YAML::Value;
    emitFrame(out, s.fixed_point);
  }
  if (i < r.residual_translation.size() && std::isfinite(r.residual_translation[i])) {
    out << YAML::Key << "residual_translation" << YAML::Value << r.residual_translation[i];
    out << YAML::Key << "residual_rotation" << YAML::Value << r.residual_rotation[i];
  }
  out << YAML::EndMap;
}

// The whole file's text before its CRC line.
std::string calibrationYaml(const StoredCalibration& c, const std::string& path) {
  const Result& r = c.result;
  YAML::Emitter out;
  out.SetDoublePrecision(17);
  out << YAML::Comment("pan-tilt head fixed point calibration (imagenets_calibration)");
  out << YAML::BeginMap;
  out << YAML::Key << "created" << YAML::Value << (c.created.empty() ? utcStamp(true) : c.created);
  out << YAML::Key << "base_frame" << YAML::Value << c.base_frame;
  out << YAML::Key << "child_frame" << YAML::Value << c.child_frame;
  out << YAML::Key << "method" << YAML::Value << r.method;
  out << YAML::Key << "message" << YAML::Value << r.message;
  emitEstimate(out, r);
  if (r.has_covariance) emitUncertainty(out, r);
  out << YAML::Key << "compute_time" << YAML::Value << r.compute_time;
  emitRejections(out, r);
  out << YAML::Key << "samples" << YAML::Value << YAML::BeginSeq;
  for (size_t i = 0; i < r.samples.size(); ++i) emitSample(out, r, i);
  out << YAML::EndSeq;
  out << YAML::EndMap;
  if (!out.good()) throw std::runtime_error("cannot write calibration '" + path + "': " + out.GetLastError());
  return std::string(out.c_str()) + "\n";
}

// Keeps the calibration at `path` under its own time stamp (never overwriting an archive);
// returns where ("" when there was none).
std::string archivePrevious(const std::string& path) {
  const fs::path target(path);
  if (!fs::exists(target)) return "";
  const std::string stem = target.stem().string();
  const std::string base = (target.parent_path() / (stem + "." + utcStamp(false))).string();
  std::string archived = base + ".yaml";
  for (int k = 1; fs::exists(archived); ++k) archived = base + "_" + std::to_string(k) + ".yaml";
  std::error_code ec;
  fs::copy_file(target, archived, ec);
  if (ec) throw std::runtime_error("cannot archive the previous calibration to '" + archived + "'");
  return archived;
}

}  // namespace

std::string saveCalibration(const StoredCalibration& c, const std::string& path) {
  // The last line holds the CRC-32 of every byte before it: a file cut short anywhere (a full
  // disk, an interrupted copy) or altered is refused, also where the rest would still parse.
  const std::string body = calibrationYaml(c, path);
  char crc_line[40];
  std::snprintf(crc_line, sizeof crc_line, "%s0x%08x\n", kCrcKey, crc32(body));
  std::string archived;
  writeAtomically(path, body + crc_line, "calibration", [&] { archived = archivePrevious(path); });
  return archived;
}

std::string calibratedUrdf(const RobotModel& nominal, const StoredCalibration& c) {
  const Result& r = c.result;
  const RobotModel calibrated = calibratedModel(nominal, r);
  const auto& d = nominal.description();
  std::ostringstream note;
  note << std::setprecision(9);
  auto frame = [&](const Eigen::Isometry3d& t) {
    const Eigen::Vector3d rpy = robot_description::rpyOf(t.rotation()) * 180.0 / M_PI;
    note << "xyz [" << t.translation().x() << " " << t.translation().y() << " " << t.translation().z() << "] m, rpy ["
         << rpy.x() << " " << rpy.y() << " " << rpy.z() << "] deg";
  };
  // The joints as the written URDF names them (the robot's own URDF, or the generated one).
  const robot_description::UrdfJoint mount = robot_description::urdfChainMountJoint(d, d.head);
  note << "Calibrated (" << r.method << " method, " << (c.created.empty() ? utcStamp(true) : c.created)
       << ") by friend_calibration_node" << (c.file.empty() ? "" : " into " + c.file) << ":\n  joint " << mount.name
       << " (" << mount.parent << " -> " << mount.child << ", the calibrated " << c.child_frame << "): ";
  frame(r.fixed_point);
  note << "\n  joint " << robot_description::urdfFixedJoint(d, d.marker.frame).name << " (marker offset): ";
  frame(r.marker_offset);
  note << "\n  joint zero offsets, folded into the joints' origins (robot_state_publisher ignores <calibration>):";
  bool any = false;
  for (const auto& [chain, offsets] : {std::make_pair(&d.arm, &r.arm_joint_offsets), std::make_pair(&d.head, &r.head_joint_offsets)}) {
    for (size_t i = 0; i < offsets->size() && i < chain->joints.size(); ++i) {
      if ((*offsets)[i] == 0.0) continue;
      note << "\n    " << chain->joints[i].name << " " << (*offsets)[i] * 180.0 / M_PI << " deg";
      any = true;
    }
  }
  if (!any) note << " none";
  return robot_description::writeUrdf(d, calibrated.description(), d.name, note.str());
}

void saveCalibratedUrdf(const RobotModel& nominal, const StoredCalibration& c, const std::string& path) {
  writeAtomically(path, calibratedUrdf(nominal, c), "calibrated URDF");
}

std::string urdfFileBeside(const std::string& calibration_file) {
  return fs::path(calibration_file).replace_extension(".urdf").string();
}

namespace {

// Files written before the pixel-level fit have no covariance (has_covariance stays false).
void readUncertainty(const Reader& rd, const YAML::Node& root, Uncertainty& u) {
  if (!root["fixed_point_covariance"]) return;
  const auto fc = rd.numbers(root, "fixed_point_covariance", "", 36);
  const auto mc = rd.numbers(root, "marker_offset_covariance", "", 36);
  u.fixed_point_covariance = Eigen::Map<const Eigen::Matrix<double, 6, 6>>(fc.data());
  u.marker_offset_covariance = Eigen::Map<const Eigen::Matrix<double, 6, 6>>(mc.data());
  u.arm_joint_offset_std = rd.numbers(root, "arm_joint_offset_std", "", 0);
  u.head_joint_offset_std = rd.numbers(root, "head_joint_offset_std", "", 0);
  if (root["reprojection_rms"]) u.reprojection_rms = root["reprojection_rms"].as<double>();
  // Files written before the observability report have none (condition number 0 = not computed).
  if (const YAML::Node o = root["observability"]) {
    u.condition_number = rd.get(o, "condition_number", "observability.").as<double>();
    u.unobservable = rd.get(o, "unobservable", "observability.").as<std::vector<std::string>>();
  }
  u.has_covariance = true;
}

void readEstimate(const Reader& rd, const YAML::Node& root, Result& r) {
  r.fixed_point = rd.frame(root, "fixed_point", "");
  if (root["marker_offset"]) r.marker_offset = rd.frame(root, "marker_offset", "");
  if (root["arm_joint_offsets"]) r.arm_joint_offsets = rd.numbers(root, "arm_joint_offsets", "", 0);
  if (root["head_joint_offsets"]) r.head_joint_offsets = rd.numbers(root, "head_joint_offsets", "", 0);
  const auto st = rd.numbers(root, "std_dev_translation", "", 3), sr = rd.numbers(root, "std_dev_rotation", "", 3);
  r.std_translation = Eigen::Vector3d(st[0], st[1], st[2]);
  r.std_rotation = Eigen::Vector3d(sr[0], sr[1], sr[2]);
}

void readSamples(const Reader& rd, const YAML::Node& root, Result& r) {
  if (root["used"]) r.used = root["used"].as<std::vector<int>>();
  for (const auto& rej : root["rejected"]) {
    r.rejected.push_back(rej["sample"].as<int>());
    r.rejection_reasons.push_back(rej["reason"] ? rej["reason"].as<std::string>() : "");
  }
  const YAML::Node samples = root["samples"];
  for (size_t i = 0; samples && i < samples.size(); ++i) {
    const std::string w = "samples[" + std::to_string(i) + "].";
    const YAML::Node n = samples[i];
    Sample s;
    s.stamp = n["stamp"] ? n["stamp"].as<double>() : 0.0;
    s.arm_q = rd.numbers(n, "arm_q", w, 0);
    s.head_q = rd.numbers(n, "head_q", w, 0);
    s.left = rd.observation(n, "left", w);
    s.right = rd.observation(n, "right", w);
    if (n["mono"]) s.mono = rd.observation(n, "mono", w);
    s.valid = n["valid"] && n["valid"].as<bool>();
    if (n["fusion"]) s.fusion = n["fusion"].as<std::string>();
    if (n["reason"]) s.reason = n["reason"].as<std::string>();
    if (s.valid && n["fixed_point"]) s.fixed_point = rd.frame(n, "fixed_point", w);
    r.residual_translation.push_back(n["residual_translation"] ? n["residual_translation"].as<double>()
                                                               : std::numeric_limits<double>::quiet_NaN());
    r.residual_rotation.push_back(n["residual_rotation"] ? n["residual_rotation"].as<double>()
                                                         : std::numeric_limits<double>::quiet_NaN());
    r.samples.push_back(std::move(s));
  }
}

}  // namespace

StoredCalibration loadCalibration(const std::string& path) {
  StoredCalibration c;
  c.file = path;
  Reader rd{path};
  std::ifstream file(path, std::ios::binary);
  if (!file) throw std::runtime_error("calibration file '" + path + "' cannot be read");
  const std::string text((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
  checkCrc(path, text);
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::Exception& e) {
    throw std::runtime_error("calibration file '" + path + "': " + e.what());
  }
  try {
    if (root["created"]) c.created = root["created"].as<std::string>();
    if (root["base_frame"]) c.base_frame = root["base_frame"].as<std::string>();
    if (root["child_frame"]) c.child_frame = root["child_frame"].as<std::string>();
    Result& r = c.result;
    r.success = true;
    r.method = rd.get(root, "method", "").as<std::string>();
    if (root["message"]) r.message = root["message"].as<std::string>();
    readEstimate(rd, root, r);
    readUncertainty(rd, root, r);
    if (root["compute_time"]) r.compute_time = root["compute_time"].as<double>();
    readSamples(rd, root, r);
  } catch (const YAML::Exception& e) {
    throw std::runtime_error("calibration file '" + path + "': " + e.what());
  }
  return c;
}

std::string overwriteRefusal(const Result& fresh, const std::string& path, double max_uncertainty) {
  if (!(max_uncertainty > 0) || !fresh.has_covariance || 3 * fresh.sigmaTranslation() <= max_uncertainty) return "";
  Result saved;
  try {
    saved = loadCalibration(path).result;
  } catch (const std::exception&) {
    return "";  // nothing good to keep
  }
  if (saved.has_covariance && 3 * saved.sigmaTranslation() > max_uncertainty) return "";
  char b[400];
  std::snprintf(b, sizeof b,
                "calibration not saved: its uncertainty (3 sigma) %.3f mm is above ~max_uncertainty %.3f mm; the "
                "saved calibration %s (%s) and the published frame are unchanged",
                3000 * fresh.sigmaTranslation(), 1000 * max_uncertainty, path.c_str(),
                saved.has_covariance ? ("3 sigma " + std::to_string(3000 * saved.sigmaTranslation()).substr(0, 5) + " mm").c_str()
                                     : "no uncertainty recorded");
  return b;
}

}  // namespace imagenets_calibration
