// `imagenets repeatability`: the repeatability study of the paper (5.2, Fig. 5.3, Table 5.1)
// against the simulator: the calibration is run R times for each redundancy N, and the spread of
// the fixed points, the time per calibration and the error of their mean against the simulator's
// true fixed point are tabulated. Needs friend_sim and friend_calibration_node running (see
// launch/repeatability.launch, which starts both and this command).
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <map>
#include <sstream>

#include <opencv2/imgproc.hpp>

#include "calibration_client.h"
#include "imagenets/tool/command.h"
#include "study_files.h"
#include "imagenets_calibration/calibration.h"
#include "imagenets/vision/frames.h"
#include <ros/ros.h>

namespace imagenets {
namespace tool {
namespace {

struct Row {
  std::string method;
  int redundancy = 0, run = 0;
  CalibrationRun r;
  bool real_speed = false;  // one of the extra runs with the motion at real speed (not in the statistics)
};

// The simulator reads its time scale live: the study runs fast, a few runs per row at real speed
// give the time a calibration takes on the robot.
void setSimTimeScale(double scale) {
  ros::param::set("/friend_sim/time_scale", scale);
  ros::Duration(0.3).sleep();  // the simulator's next ticks pick it up
}

double stdOf(const std::vector<double>& v) {
  if (v.size() < 2) return 0;
  double m = 0;
  for (double x : v) m += x;
  m /= v.size();
  double s = 0;
  for (double x : v) s += (x - m) * (x - m);
  return std::sqrt(s / (v.size() - 1));
}

// Fig. 5.3-style 3D scatter: fixed points relative to the true one (mm), oblique projection,
// one colour per redundancy.
void drawScatter(const std::vector<Row>& rows, const std::string& method, const std::string& path) {
  const int w = 1000, h = 800;
  cv::Mat img(h, w, CV_8UC3, cv::Scalar(255, 255, 255));
  std::vector<Eigen::Vector3d> pts;
  double range = 0.5;
  for (const auto& row : rows) {
    if (row.method != method || row.real_speed || !row.r.response.success || !row.r.have_truth) continue;
    const Eigen::Vector3d d = (row.r.fixed_point.translation() - row.r.truth.translation()) * 1000;
    range = std::max(range, d.cwiseAbs().maxCoeff());
  }
  range = std::ceil(range * 1.1 * 2) / 2;
  // Oblique projection: x to the lower left, y to the right, z up.
  const double scale = 260 / range;
  const cv::Point2d origin(w * 0.5, h * 0.55);
  auto project = [&](const Eigen::Vector3d& p) {
    return cv::Point2d(origin.x + scale * (p.y() - 0.55 * p.x()), origin.y - scale * (p.z() - 0.35 * p.x()));
  };
  const cv::Scalar grey(150, 150, 150), black(0, 0, 0);
  const char* names[3] = {"x", "y", "z"};
  for (int a = 0; a < 3; ++a) {
    Eigen::Vector3d e = Eigen::Vector3d::Zero();
    e[a] = range;
    cv::line(img, project(-e), project(e), grey, 1, cv::LINE_AA);
    char label[64];
    std::snprintf(label, sizeof label, "%s +%.1f mm", names[a], range);
    cv::putText(img, label, project(e) + cv::Point2d(5, -5), cv::FONT_HERSHEY_SIMPLEX, 0.5, black, 1, cv::LINE_AA);
  }
  const std::map<int, cv::Scalar> colours{{1, cv::Scalar(40, 40, 220)}, {3, cv::Scalar(200, 120, 20)}, {5, cv::Scalar(30, 160, 30)}};
  std::map<int, int> counts;
  for (const auto& row : rows) {
    if (row.method != method || row.real_speed || !row.r.response.success || !row.r.have_truth) continue;
    const Eigen::Vector3d d = (row.r.fixed_point.translation() - row.r.truth.translation()) * 1000;
    const auto it = colours.find(row.redundancy);
    const cv::Scalar c = it != colours.end() ? it->second : cv::Scalar(120, 0, 120);
    // A thin drop line to the x-y plane helps reading depth in a single view.
    cv::line(img, project(d), project(Eigen::Vector3d(d.x(), d.y(), 0)), c * 0.3 + cv::Scalar(170, 170, 170), 1);
    cv::circle(img, project(d), 4, c, cv::FILLED, cv::LINE_AA);
    ++counts[row.redundancy];
  }
  cv::drawMarker(img, project(Eigen::Vector3d::Zero()), black, cv::MARKER_CROSS, 18, 2);
  cv::putText(img, "true fixed point", project(Eigen::Vector3d::Zero()) + cv::Point2d(10, 18), cv::FONT_HERSHEY_SIMPLEX,
              0.5, black, 1, cv::LINE_AA);
  cv::putText(img, "PTH fixed points relative to the simulator's truth (mm), method: " + method, cv::Point(20, 35),
              cv::FONT_HERSHEY_SIMPLEX, 0.7, black, 2, cv::LINE_AA);
  int y = 70;
  for (const auto& kv : counts) {
    const auto it = colours.find(kv.first);
    cv::circle(img, cv::Point(30, y - 5), 6, it != colours.end() ? it->second : cv::Scalar(120, 0, 120), cv::FILLED);
    cv::putText(img, std::to_string(kv.first) + " loop(s), " + std::to_string(kv.second) + " runs", cv::Point(45, y),
                cv::FONT_HERSHEY_SIMPLEX, 0.55, black, 1, cv::LINE_AA);
    y += 25;
  }
  writePngAtomically(path, img);
}

void declare(Flags& f) {
  f.add()("runs", po::value<int>()->default_value(100), "calibrations per row (>= 2)")
      ("redundancy", po::value<std::string>()->default_value("1,3,5"), "the loop counts, a row each")
      ("method", po::value<std::string>()->default_value("both"), "paper, joint or both")
      ("real-speed-runs", po::value<int>()->default_value(2), "more runs per row with the motion at real speed")
      ("output-dir", po::value<std::string>()->default_value("out/repeatability"), "where runs.csv, table.md, scatter_*.png go")
      ("wait", po::value<double>()->default_value(60), "seconds to wait for the calibration node");
  f.acceptRosArguments();
}

struct Study {
  int runs = 100;
  std::vector<int> redundancies;
  std::vector<std::string> methods;
  std::string out;
  double time_scale = 1.0;   // the simulator's, for the study's runs
  int real_speed_runs = 2;
  double reflections = 0;    // the simulator's probability of a spurious reflection
};

Study study(const Options& o) {
  Study s;
  s.runs = o["runs"].as<int>();
  s.redundancies = parseCounts("--redundancy", o["redundancy"].as<std::string>());
  const std::string m = o["method"].as<std::string>();
  s.methods = m == "both" ? std::vector<std::string>{"paper", "joint"} : std::vector<std::string>{m};
  s.out = o["output-dir"].as<std::string>();
  s.real_speed_runs = o["real-speed-runs"].as<int>();
  if (s.runs < 2) throw UsageError("--runs must be >= 2");
  if (s.real_speed_runs < 0) throw UsageError("--real-speed-runs must be >= 0");
  return s;
}

std::string csvLine(const Row& row, double time_scale) {
  const auto& res = row.r.response;
  const Eigen::Vector3d t = row.r.fixed_point.translation();
  const Eigen::Vector3d rpy = robot_description::rpyOf(row.r.fixed_point.rotation()) * 180 / M_PI;
  char line[512];
  std::snprintf(line, sizeof line, "%s,%d,%d,%d,%.6f,%.6f,%.6f,%.5f,%.5f,%.5f,%.4f,%.5f,%.4f,%.5f,%d,%d,%.5f,%.4f,%.1f,",
                row.method.c_str(), row.redundancy, row.run, res.success ? 1 : 0, t.x(), t.y(), t.z(), rpy.x(), rpy.y(),
                rpy.z(), row.r.error_mm, row.r.error_deg, row.r.effective_error_mm, row.r.effective_error_deg,
                res.samples_used, res.samples_rejected, res.compute_time, res.total_time,
                row.real_speed ? 1.0 : time_scale);
  return line + csvQuoted(res.message) + "\n";
}

// Every calibration of the study, in order; runs.csv written.
std::vector<Row> calibrateAll(CalibrationClient& client, const Study& s) {
  std::vector<Row> rows;
  std::ostringstream csv;
  csv << "method,redundancy,run,success,x,y,z,roll_deg,pitch_deg,yaw_deg,error_mm,error_deg,effective_error_mm,"
         "effective_error_deg,samples_used,samples_rejected,compute_time_s,total_time_s,time_scale,message\n";
  const int per_row = s.runs + s.real_speed_runs;
  const int total = static_cast<int>(s.methods.size() * s.redundancies.size()) * per_row;
  for (const auto& method : s.methods) {
    for (int n : s.redundancies) {
      for (int k = 0; k < per_row; ++k) {
        const bool real_speed = k >= s.runs;
        if (real_speed && k == s.runs) setSimTimeScale(1.0);
        Row row{method, n, k, client.calibrate(n, method), real_speed};
        if (real_speed && k + 1 == per_row) setSimTimeScale(s.time_scale);
        const auto& res = row.r.response;
        std::fprintf(stderr, "\r[%3d%%] %s, %d loop(s): run %d/%d%s %s (%.2f mm, %.3f deg)      ",
                     static_cast<int>(rows.size() + 1) * 100 / total, method.c_str(), n, k + 1, per_row,
                     real_speed ? " (real speed)" : "", res.success ? "ok" : "FAILED", row.r.error_mm, row.r.error_deg);
        if (!res.success) std::fprintf(stderr, "\n  %s\n", res.message.c_str());
        csv << csvLine(row, s.time_scale);
        rows.push_back(row);
      }
    }
  }
  std::fprintf(stderr, "\n");
  writeFileAtomically(s.out + "/runs.csv", csv.str());
  return rows;
}

// One row of the table: the spread of the fixed points of one method and loop count, the times,
// the error of their mean.
std::string tableRow(const std::vector<Row>& rows, const std::string& method, int n) {
  std::vector<Eigen::Isometry3d> x;
  std::vector<double> total_time, compute, real_speed_time;
  Eigen::Isometry3d truth = Eigen::Isometry3d::Identity(), effective = Eigen::Isometry3d::Identity();
  for (const auto& row : rows) {
    if (row.method != method || row.redundancy != n || !row.r.response.success) continue;
    if (row.real_speed) {
      real_speed_time.push_back(row.r.response.total_time);
      continue;
    }
    x.push_back(row.r.fixed_point);
    total_time.push_back(row.r.response.total_time);
    compute.push_back(row.r.response.compute_time);
    truth = row.r.truth;
    effective = row.r.effective;
  }
  if (x.size() < 2) return "| " + method + " | " + std::to_string(n) + " | " + std::to_string(x.size()) + " | (too few successful runs) |\n";
  std::vector<Eigen::Quaterniond> q;
  Eigen::Vector3d mean_t = Eigen::Vector3d::Zero();
  for (const auto& f : x) {
    q.emplace_back(f.rotation());
    mean_t += f.translation();
  }
  mean_t /= x.size();
  const Eigen::Quaterniond mean_q = frames::meanRotation(q);
  std::vector<double> ax[3], rot[3];
  for (const auto& f : x) {
    const Eigen::AngleAxisd aa(mean_q.toRotationMatrix().transpose() * f.rotation());
    const Eigen::Vector3d rv = aa.axis() * aa.angle();
    for (int a = 0; a < 3; ++a) {
      ax[a].push_back(f.translation()[a] * 1000);
      rot[a].push_back(rv[a] * 180 / M_PI);
    }
  }
  Eigen::Isometry3d mean = Eigen::Isometry3d::Identity();
  mean.linear() = mean_q.toRotationMatrix();
  mean.translation() = mean_t;
  auto average = [](const std::vector<double>& v) {
    double sum = 0;
    for (double x : v) sum += x;
    return v.empty() ? 0.0 : sum / v.size();
  };
  const double tt = average(total_time), ct = average(compute);
  char buf[1024];
  std::snprintf(buf, sizeof buf,
                "| %s | %d | %zu | %.3f | %.3f | %.3f | %.4f | %.4f | %.4f | %.2f | %.2f | %.1f | %.1f | %.3f | "
                "%.4f | %.3f | %.4f |\n",
                method.c_str(), n, x.size(), stdOf(ax[0]), stdOf(ax[1]), stdOf(ax[2]), stdOf(rot[0]), stdOf(rot[1]),
                stdOf(rot[2]), real_speed_time.empty() ? tt : average(real_speed_time), tt, ct * 1000, ct * 1000 / n,
                (mean.translation() - truth.translation()).norm() * 1000,
                imagenets_calibration::angleBetween(mean, truth) * 180 / M_PI,
                (mean.translation() - effective.translation()).norm() * 1000,
                imagenets_calibration::angleBetween(mean, effective) * 180 / M_PI);
  return buf;
}

std::string table(const std::vector<Row>& rows, const Study& s) {
  std::ostringstream table;
  char buf[1024];
  std::snprintf(buf, sizeof buf,
                "Repeatability (paper Table 5.1) against the simulator: %d runs per row, simulator default noise, "
                "%.0f %% spurious-reflection outliers, motion at %.1fx real speed; %d more runs per row with the motion "
                "at real speed give the time per calibration on the robot.\n\n",
                s.runs, s.reflections * 100, s.time_scale, s.real_speed_runs);
  table << buf;
  table << "| method | loops | ok | std X mm | std Y mm | std Z mm | std rot x deg | std rot y deg | std rot z deg | "
           "time/calib s at real speed | time/calib s at the study's speed | compute ms/calib | compute ms/loop | "
           "mean error mm | mean error deg | mean error vs effective mm | deg |\n";
  table << "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const auto& method : s.methods) {
    for (int n : s.redundancies) table << tableRow(rows, method, n);
  }
  table << "\nPaper (5 loops, real FRIEND): std 0.88 / 0.58 / 2.10 mm, 0.12 / 0.11 / 0.73 deg.\n"
           "'effective' = the true mount with the pan encoder's zero offset folded in (indistinguishable from the "
           "mount's yaw for any calibration of this frame).\n";
  return table.str();
}

int repeatability(const Options& o) {
  Study s = study(o);
  std::filesystem::create_directories(s.out);
  CalibrationClient client("imagenets_repeatability", o["wait"].as<double>());
  ros::param::get("/friend_sim/time_scale", s.time_scale);
  if (s.time_scale == 1.0) s.real_speed_runs = 0;  // every run is at real speed already
  ros::param::get("/friend_sim/faults/reflection_probability", s.reflections);
  const std::vector<Row> rows = calibrateAll(client, s);
  const std::string text = table(rows, s);
  writeFileAtomically(s.out + "/table.md", text);
  std::cout << text;
  for (const auto& method : s.methods) drawScatter(rows, method, s.out + "/scatter_" + method + ".png");
  std::cout << "written: " << s.out << "/runs.csv, " << s.out << "/table.md, " << s.out << "/scatter_*.png\n";
  return 0;
}

}  // namespace

IMAGENETS_TOOL_COMMAND(repeatability, "repeatability",
                       "repeatability [--runs 100] [--redundancy 1,3,5] [--method paper|joint|both] [--real-speed-runs 2] [--output-dir DIR]",
                       "the paper's repeatability study (Table 5.1, Fig. 5.3) against the running simulator + calibration node",
                       declare, repeatability);

}  // namespace tool
}  // namespace imagenets

// A program of its own, `imagenets-NAME`, run as `imagenets NAME`.
int main(int argc, char** argv) { return imagenets::tool::runCommandLine(argc, argv); }
