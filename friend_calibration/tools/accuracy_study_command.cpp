// `imagenets accuracy-study`: the calibration's accuracy over many random TRUE robots,
// against the simulator. For each seed the simulator is switched live to another true robot
// (friend_sim/set_true_robot: the random error of true_error.yaml's magnitudes times --magnitude),
// the calibration node calibrates it, and the result is compared with the simulator's truth (the
// effective fixed point, and the identifiable one: friend_hw_sim/true_robot.h) and with the 3-sigma
// bound the calibration reported. Other loop counts per robot
// (--pose-sweep) give the error over the number of poses. Needs friend_sim and
// friend_calibration_node running (launch/accuracy_study.launch starts both and this command).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <limits>
#include <sstream>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <ros/ros.h>

#include "calibration_client.h"
#include "imagenets/tool/command.h"
#include "imagenets_calibration/calibration.h"
#include "imagenets/vision/plot.h"
#include "robot_description/robot_model.h"
#include "study_files.h"

namespace imagenets {
namespace tool {
namespace {

struct Run {
  int seed = 0, loops = 0;
  CalibrationRun r;
  double mount_offset_mm = 0, mount_offset_deg = 0;  // how far this true robot's head mount is off the nominal one
  bool usable() const { return r.response.success || r.refused; }
  // Is the error (against the effective or the identifiable fixed point) inside the reported 3-sigma bound?
  bool within(bool identifiable = false) const {
    const double mm = identifiable ? r.identifiable_error_mm : r.effective_error_mm;
    const double deg = identifiable ? r.identifiable_error_deg : r.effective_error_deg;
    return usable() && r.bound3_mm > 0 && mm <= r.bound3_mm && deg <= r.bound3_deg;
  }
  std::string status() const { return r.response.success ? "ok" : r.refused ? "refused" : "FAILED"; }
};

// Nearest-rank percentile (the smallest value with at least p of the values at or below it).
double percentile(std::vector<double> v, double p) {
  if (v.empty()) return std::numeric_limits<double>::quiet_NaN();
  std::sort(v.begin(), v.end());
  const size_t rank = static_cast<size_t>(std::ceil(p * v.size()));
  return v[std::clamp<size_t>(rank, 1, v.size()) - 1];
}

std::string csvRow(const Run& run, double magnitude, double reflections, const std::string& method) {
  const auto& res = run.r.response;
  const Eigen::Vector3d t = run.r.fixed_point.translation();
  const Eigen::Vector3d rpy = robot_description::rpyOf(run.r.fixed_point.rotation()) * 180 / M_PI;
  char line[768];
  std::snprintf(line, sizeof line,
                "%d,%.3f,%.3f,%s,%d,%s,%.3f,%.4f,%.6f,%.6f,%.6f,%.5f,%.5f,%.5f,%.4f,%.5f,%.4f,%.5f,%.4f,%.5f,%.4f,%.5f,"
                "%d,%d,%d,%d,%.5f,%.5f,%.4f,",
                run.seed, magnitude, reflections, method.c_str(), run.loops, run.status().c_str(), run.mount_offset_mm,
                run.mount_offset_deg, t.x(), t.y(), t.z(), rpy.x(), rpy.y(), rpy.z(), run.r.error_mm, run.r.error_deg,
                run.r.effective_error_mm, run.r.effective_error_deg, run.r.identifiable_error_mm,
                run.r.identifiable_error_deg, run.r.bound3_mm, run.r.bound3_deg, run.within() ? 1 : 0,
                run.within(true) ? 1 : 0, res.samples_used, res.samples_rejected, res.compute_time, res.detection_cpu_time,
                res.total_time);
  return line + csvQuoted(res.message) + "\n";
}
const char* const kCsvHeader =
    "seed,magnitude,reflection_probability,method,loops,status,head_mount_offset_mm,head_mount_offset_deg,x,y,z,"
    "roll_deg,pitch_deg,yaw_deg,error_mm,error_deg,effective_error_mm,effective_error_deg,identifiable_error_mm,"
    "identifiable_error_deg,bound3_mm,bound3_deg,within_3sigma,identifiable_within_3sigma,samples_used,samples_rejected,"
    "compute_time_s,detection_cpu_time_s,total_time_s,message\n";

// Picture 1: per robot, the error against the effective fixed point (dot: green inside the reported
// 3-sigma bound, red outside) and the bound itself (bar from 0), in mm above and degrees below.
cv::Mat errorPerRobotPicture(const std::vector<Run>& runs, const std::string& caption) {
  std::vector<cv::Mat> panels;
  for (int unit = 0; unit < 2; ++unit) {
    auto error = [&](const Run& r) { return unit == 0 ? r.r.effective_error_mm : r.r.effective_error_deg; };
    auto bound = [&](const Run& r) { return unit == 0 ? r.r.bound3_mm : r.r.bound3_deg; };
    plot::Series bars{{}, {}, "reported 3-sigma bound (bar)", cv::Scalar(200, 140, 60), false, false};
    plot::Series inside{{}, {}, "error, within the bound", cv::Scalar(40, 150, 40), false, true};
    plot::Series outside{{}, {}, "error, OUTSIDE the bound", cv::Scalar(30, 30, 220), false, true};
    plot::Series failed{{}, {}, "no result (failed)", cv::Scalar(0, 0, 0), false, true};
    plot::Series ident{{}, {}, "error against the identifiable fixed point", cv::Scalar(170, 40, 150), false, true};
    // Invisible: keeps 0 on the axis, and room above the data for the legend.
    plot::Series zero{{}, {}, "", cv::Scalar(), false, false};
    double top = 0;
    for (const auto& r : runs) {
      if (r.usable()) top = std::max({top, error(r), bound(r)});
    }
    for (const auto& r : runs) {
      zero.x.push_back(r.seed);
      zero.y.push_back(0);
      zero.x.push_back(r.seed);
      zero.y.push_back(1.9 * top);  // room for the legend's lines
      if (!r.usable()) {
        failed.x.push_back(r.seed);
        failed.y.push_back(0);
        continue;
      }
      bars.x.push_back(r.seed);
      bars.y.push_back(bound(r));
      plot::Series& s = r.within() ? inside : outside;
      s.x.push_back(r.seed);
      s.y.push_back(error(r));
      ident.x.push_back(r.seed + 0.25);  // beside the other dot
      ident.y.push_back(unit == 0 ? r.r.identifiable_error_mm : r.r.identifiable_error_deg);
    }
    plot::Options o;
    o.width = 1000;
    o.height = 420;
    o.title = unit == 0 ? "Error of the fixed point per true robot, mm (effective fixed point)"
                        : "Error of the fixed point per true robot, deg (effective fixed point)";
    o.note = caption;
    o.x_label = "true robot (seed)";
    o.y_label = unit == 0 ? "mm" : "deg";
    std::vector<plot::Series> series{zero, bars, inside, outside, ident};
    if (!failed.x.empty()) series.push_back(failed);
    plot::Axes axes;
    cv::Mat img = plot::plotSeries(series, o, &axes);
    // The bars under the dots: drawn, then the dots again on top.
    for (size_t i = 0; i < bars.x.size(); ++i) {
      const cv::Point2d a = axes.toPixel(bars.x[i], 0), b = axes.toPixel(bars.x[i], bars.y[i]);
      cv::line(img, a, b, bars.color, 5);
      cv::line(img, b + cv::Point2d(-7, 0), b + cv::Point2d(7, 0), bars.color, 2);
    }
    for (const auto* s : {&inside, &outside, &failed, &ident}) {
      for (size_t i = 0; i < s->x.size(); ++i) cv::circle(img, axes.toPixel(s->x[i], s->y[i]), 5, s->color, cv::FILLED, cv::LINE_AA);
    }
    panels.push_back(img);
  }
  cv::Mat out;
  cv::vconcat(panels, out);
  return out;
}

// Picture 2: error against the number of poses: one grey line per robot, the median and the 95th
// percentile over the robots, and the median reported 3-sigma bound.
cv::Mat errorVersusPosesPicture(const std::vector<Run>& runs, const std::vector<int>& loops, int poses_per_loop,
                                const std::string& caption) {
  std::vector<int> seeds;
  for (const auto& r : runs) {
    if (std::find(seeds.begin(), seeds.end(), r.seed) == seeds.end()) seeds.push_back(r.seed);
  }
  std::vector<cv::Mat> panels;
  for (int unit = 0; unit < 2; ++unit) {
    auto error = [&](const Run& r) { return unit == 0 ? r.r.effective_error_mm : r.r.effective_error_deg; };
    auto bound = [&](const Run& r) { return unit == 0 ? r.r.bound3_mm : r.r.bound3_deg; };
    std::vector<plot::Series> series;
    for (int seed : seeds) {
      plot::Series s{{}, {}, series.empty() ? "one robot (grey)" : "", cv::Scalar(190, 190, 190), true, true};
      for (int n : loops) {
        for (const auto& r : runs) {
          if (r.seed != seed || r.loops != n || !r.usable()) continue;
          s.x.push_back(n * poses_per_loop);
          s.y.push_back(error(r));
        }
      }
      series.push_back(s);
    }
    plot::Series median{{}, {}, "median over the robots", cv::Scalar(160, 80, 0), true, true};
    plot::Series p95{{}, {}, "95th percentile", cv::Scalar(30, 30, 220), true, true};
    plot::Series bounds{{}, {}, "median reported 3-sigma bound", cv::Scalar(40, 150, 40), true, true};
    plot::Series ident95{{}, {}, "95th percentile, identifiable fixed point", cv::Scalar(170, 40, 150), true, true};
    plot::Series zero{{}, {}, "", cv::Scalar(), false, false};  // 0 on the axis, room for the legend
    double top = 0;
    for (const auto& r : runs) {
      if (r.usable()) top = std::max(top, error(r));
    }
    const double room = 1.9 * top;  // the legend's five lines above the data
    std::string off_chart;  // bounds far above every error would flatten the errors: named, not drawn
    for (int n : loops) {
      std::vector<double> e, b, a;
      for (const auto& r : runs) {
        if (r.loops != n || !r.usable()) continue;
        e.push_back(error(r));
        a.push_back(unit == 0 ? r.r.identifiable_error_mm : r.r.identifiable_error_deg);
        if (bound(r) > 0) b.push_back(bound(r));  // runs without a covariance report no bound
      }
      if (e.empty()) continue;
      for (auto* s : {&median, &p95, &ident95, &zero, &zero}) s->x.push_back(n * poses_per_loop);
      ident95.y.push_back(percentile(a, 0.95));
      median.y.push_back(percentile(e, 0.5));
      p95.y.push_back(percentile(e, 0.95));
      zero.y.push_back(0);
      zero.y.push_back(room);
      if (b.empty()) continue;
      const double m = percentile(b, 0.5);
      if (m > room) {
        char t[96];
        std::snprintf(t, sizeof t, "%s%d poses (%.3g)", off_chart.empty() ? "" : ", ", n * poses_per_loop, m);
        off_chart += t;
        continue;
      }
      bounds.x.push_back(n * poses_per_loop);
      bounds.y.push_back(m);
    }
    series.push_back(zero);
    series.push_back(bounds);
    series.push_back(median);
    series.push_back(p95);
    series.push_back(ident95);
    plot::Options o;
    o.width = 1000;
    o.height = 420;
    o.title = unit == 0 ? "Error of the fixed point over the number of poses, mm" : "Error of the fixed point over the number of poses, deg";
    o.note = caption;
    if (!off_chart.empty()) o.note += "; median 3-sigma bound off the chart at " + off_chart;
    o.x_label = "poses planned (loops x " + std::to_string(poses_per_loop) + ")";
    o.y_label = unit == 0 ? "mm" : "deg";
    panels.push_back(plot::plotSeries(series, o));
  }
  cv::Mat out;
  cv::vconcat(panels, out);
  return out;
}

void declare(Flags& f) {
  f.add()("true-robots", po::value<int>()->default_value(20), "random true robots to calibrate")
      ("first-seed", po::value<int>()->default_value(1), "the first robot's seed (>= 1)")
      ("magnitude", po::value<double>()->default_value(1.0), "times true_error.yaml's `random` magnitudes")
      ("reflections", po::value<double>(), "spurious-reflection outliers in percent (default: the simulator's)")
      ("method", po::value<std::string>()->default_value("joint"), "joint or paper")
      ("loops", po::value<int>()->default_value(5), "loops of the main calibration (odd)")
      ("pose-sweep", po::value<std::string>()->default_value("3,7"), "other loop counts per robot (odd), or none")
      ("output-dir", po::value<std::string>()->default_value("out/accuracy"), "where the CSVs, table and pictures go")
      ("wait", po::value<double>()->default_value(60), "seconds to wait for the calibration node");
  f.acceptRosArguments();
}

struct Study {
  int robots = 20, first_seed = 1, loops = 5;
  double magnitude = 1.0, reflections_percent = -1;  // -1: the simulator's
  std::string method, out;
  std::vector<int> sweep;      // other loop counts
  std::vector<int> all_loops;  // sweep and loops, sorted
  double reflections = 0;      // the rate the study runs with
  int poses_per_loop = 2;
};

Study study(const Options& o) {
  Study s;
  s.robots = o["true-robots"].as<int>();
  s.first_seed = o["first-seed"].as<int>();
  s.magnitude = o["magnitude"].as<double>();
  if (o.count("reflections")) s.reflections_percent = o["reflections"].as<double>();
  s.method = o["method"].as<std::string>();
  s.loops = o["loops"].as<int>();
  const std::string sweep = o["pose-sweep"].as<std::string>();
  s.sweep = sweep == "none" ? std::vector<int>{} : parseCounts("--pose-sweep", sweep);
  s.out = o["output-dir"].as<std::string>();
  if (s.robots < 1) throw UsageError("--true-robots must be >= 1, not " + std::to_string(s.robots));
  if (s.first_seed < 1) throw UsageError("--first-seed must be >= 1 (seed 0 is the file's explicit error), not " + std::to_string(s.first_seed));
  if (!(s.magnitude > 0)) throw UsageError("--magnitude must be positive");
  if (o.count("reflections") && !(s.reflections_percent >= 0 && s.reflections_percent <= 100)) {
    throw UsageError("--reflections is a percentage 0..100");
  }
  if (s.method != "joint" && s.method != "paper") throw UsageError("--method must be joint or paper, not '" + s.method + "'");
  // The calibration plan takes odd loop counts only (the paper's per-axis median needs a middle value).
  if (s.loops < 1 || s.loops % 2 == 0) throw UsageError("--loops must be odd and >= 1, not " + std::to_string(s.loops));
  for (int n : s.sweep) {
    if (n % 2 == 0) throw UsageError("--pose-sweep: loop counts must be odd, not " + std::to_string(n));
  }
  s.all_loops = s.sweep;
  if (std::find(s.all_loops.begin(), s.all_loops.end(), s.loops) == s.all_loops.end()) s.all_loops.push_back(s.loops);
  std::sort(s.all_loops.begin(), s.all_loops.end());
  return s;
}

// The simulator's true robot and reflection rate, to leave it as found.
struct SimulatorState {
  int seed = -1;
  double magnitude = 1.0, reflections = 0;
};

SimulatorState simulatorState() {
  SimulatorState sim;
  ros::param::get("/friend_sim/seed", sim.seed);
  ros::param::get("/friend_sim/magnitude", sim.magnitude);
  ros::param::get("/friend_sim/faults/reflection_probability", sim.reflections);
  return sim;
}

Run calibrateOne(CalibrationClient& client, int seed, int loops, const std::string& method) {
  const robot_description::RobotModel& nominal = client.nominal();  // the robot the simulator runs
  Run run;
  run.seed = seed;
  run.loops = loops;
  run.r = client.calibrate(loops, method);
  if (!run.usable()) {  // no fixed point: nothing to compare
    run.r.error_mm = run.r.error_deg = run.r.effective_error_mm = run.r.effective_error_deg =
        run.r.identifiable_error_mm = run.r.identifiable_error_deg = std::numeric_limits<double>::quiet_NaN();
  }
  if (run.r.have_truth) {
    run.mount_offset_mm = (run.r.truth.translation() - nominal.headBase().translation()).norm() * 1000;
    run.mount_offset_deg = imagenets_calibration::angleBetween(run.r.truth, nominal.headBase()) * 180 / M_PI;
  }
  if (!run.r.have_truth && run.r.response.success) {
    throw std::runtime_error("no ground truth from the simulator (/friend_sim/ground_truth/head_base): the study "
                             "needs friend_sim");
  }
  std::fprintf(stderr, "  %d loop(s): %s, %.3f mm, %.4f deg (3-sigma %.3f mm, %.4f deg; identifiable %.3f mm, %.4f deg)\n",
               loops, run.status().c_str(), run.r.effective_error_mm, run.r.effective_error_deg, run.r.bound3_mm,
               run.r.bound3_deg, run.r.identifiable_error_mm, run.r.identifiable_error_deg);
  if (!run.usable()) std::fprintf(stderr, "    %s\n", run.r.response.message.c_str());
  return run;
}

std::string reportHeader(const Study& s) {
  char buf[1024];
  std::snprintf(buf, sizeof buf,
                "Accuracy over %d random true robots (seeds %d..%d, %.1f x the `random` magnitudes of true_error.yaml), "
                "%.0f %% spurious-reflection outliers, method %s, %d loop(s) = %d poses planned; error against the "
                "effective fixed point; 3-sigma bound = 3 sqrt(trace) of the reported covariance.\n\n",
                s.robots, s.first_seed, s.first_seed + s.robots - 1, s.magnitude, s.reflections * 100, s.method.c_str(),
                s.loops, s.loops * s.poses_per_loop);
  return std::string(buf) +
         "| seed | mount off nominal mm / deg | error mm | error deg | 3-sigma mm | 3-sigma deg | within 3 sigma | "
         "identifiable error mm / deg | poses used / rejected | time s | status |\n"
         "|---|---|---|---|---|---|---|---|---|---|---|\n";
}

// The main run's row of the per-robot table.
std::string robotRow(const Run& run) {
  const auto& res = run.r.response;
  char buf[1024];
  if (run.usable()) {
    std::snprintf(buf, sizeof buf,
                  "| %d | %.1f / %.2f | %.3f | %.4f | %.3f | %.4f | %s | %.3f / %.4f | %d / %d | %.1f | %s |\n", run.seed,
                  run.mount_offset_mm, run.mount_offset_deg, run.r.effective_error_mm, run.r.effective_error_deg,
                  run.r.bound3_mm, run.r.bound3_deg, run.r.bound3_mm > 0 ? (run.within() ? "yes" : "NO") : "NO (no bound reported)",
                  run.r.identifiable_error_mm, run.r.identifiable_error_deg, res.samples_used, res.samples_rejected,
                  res.total_time, run.status().c_str());
  } else {
    std::snprintf(buf, sizeof buf, "| %d | %.1f / %.2f | - | - | - | - | - | - | %d / %d | %.1f | FAILED: %.200s |\n",
                  run.seed, run.mount_offset_mm, run.mount_offset_deg, res.samples_used, res.samples_rejected,
                  res.total_time, res.message.c_str());
  }
  return buf;
}

struct Runs {
  std::vector<Run> main, all;  // main: the --loops run of each robot
  std::string robots_csv = kCsvHeader, runs_csv = kCsvHeader;
};

// Every robot calibrated, the main run first (the one the table is about), then the fewer-loop
// runs; the per-robot rows go to `report` and stdout as they come.
Runs calibrateRobots(CalibrationClient& client, const Study& s, std::ostringstream& report) {
  Runs runs;
  std::vector<int> order{s.loops};
  for (int n : s.all_loops) {
    if (n != s.loops) order.push_back(n);
  }
  for (int k = 0; k < s.robots; ++k) {
    const int seed = s.first_seed + k;
    const std::string sim_message = client.setTrueRobot(seed, s.magnitude);
    std::fprintf(stderr, "[%d/%d] %s\n", k + 1, s.robots, sim_message.c_str());
    for (int n : order) {
      const Run run = calibrateOne(client, seed, n, s.method);
      runs.runs_csv += csvRow(run, s.magnitude, s.reflections, s.method);
      runs.all.push_back(run);
      if (n != s.loops) continue;
      runs.robots_csv += csvRow(run, s.magnitude, s.reflections, s.method);
      runs.main.push_back(run);
      report << robotRow(run);
      std::cout << robotRow(run) << std::flush;
    }
  }
  return runs;
}

// The percentiles of the main runs' errors, the 3-sigma coverage and the compute time per pose.
std::string percentileTable(const std::vector<Run>& main_runs, int robots) {
  std::vector<double> mm, deg, id_mm, id_deg, compute_ms, cpu_ms;  // compute: per pose
  int within = 0, within_mm = 0, within_deg = 0, within_id = 0, failed = 0, refused = 0;
  for (const auto& r : main_runs) {
    if (!r.usable()) {
      ++failed;
      continue;
    }
    refused += r.r.refused ? 1 : 0;
    mm.push_back(r.r.effective_error_mm);
    deg.push_back(r.r.effective_error_deg);
    id_mm.push_back(r.r.identifiable_error_mm);
    id_deg.push_back(r.r.identifiable_error_deg);
    within += r.within() ? 1 : 0;
    within_id += r.within(true) ? 1 : 0;
    within_mm += r.r.bound3_mm > 0 && r.r.effective_error_mm <= r.r.bound3_mm ? 1 : 0;
    within_deg += r.r.bound3_deg > 0 && r.r.effective_error_deg <= r.r.bound3_deg ? 1 : 0;
    const int poses = r.r.response.poses_taken;
    if (poses > 0) {
      compute_ms.push_back(1000 * r.r.response.compute_time / poses);
      cpu_ms.push_back(1000 * r.r.response.detection_cpu_time / poses);
    }
  }
  const int n = static_cast<int>(mm.size());
  auto pct = [&](int k) { return n > 0 ? 100.0 * k / n : 0.0; };
  std::ostringstream table;
  char buf[1024];
  table << "\n| over " << n << " robots with a result | error mm | error deg | identifiable error mm | "
           "identifiable error deg |\n|---|---|---|---|---|\n";
  for (const auto& [name, p] : std::vector<std::pair<std::string, double>>{
           {"median", 0.5}, {"90th percentile", 0.9}, {"95th percentile", 0.95}, {"max", 1.0}}) {
    std::snprintf(buf, sizeof buf, "| %s | %.3f | %.4f | %.3f | %.4f |\n", name.c_str(), percentile(mm, p),
                  percentile(deg, p), percentile(id_mm, p), percentile(id_deg, p));
    table << buf;
  }
  std::snprintf(buf, sizeof buf,
                "\n3-sigma coverage: %d of %d = %.0f %% (translation alone %.0f %%, rotation alone %.0f %%; against "
                "the identifiable fixed point %.0f %%); failures: %d of %d; refused by the node's ~max_uncertainty "
                "(result computed, not saved): %d. Percentiles: nearest rank. 'identifiable': the effective fixed "
                "point with arm joint 1's zero offset folded in as well (images of the arm's marker cannot tell it "
                "from a turn of the head mount about that joint's axis).\n",
                within, n, pct(within), pct(within_mm), pct(within_deg), pct(within_id), failed, robots, refused);
  table << buf;
  // Wall time moves with whatever else the machine does; the detecting threads' CPU time much less.
  std::snprintf(buf, sizeof buf,
                "Compute per pose (image processing and solve, no motion; wall time): median %.1f ms, max %.1f ms; "
                "of it the marker detection's CPU time (the larger of a pose's two images): median %.1f ms, max "
                "%.1f ms.\n",
                percentile(compute_ms, 0.5), percentile(compute_ms, 1.0), percentile(cpu_ms, 0.5),
                percentile(cpu_ms, 1.0));
  table << buf;
  return table.str();
}

// The error over the number of poses: the same robots calibrated with each loop count.
std::string poseSweepTable(const std::vector<Run>& all_runs, const Study& s) {
  std::ostringstream table;
  table << "\nError over the number of poses (the same robots, each also calibrated with other loop counts):\n\n"
           "| loops | poses planned | with result | median mm | 95th mm | max mm | median deg | 95th deg | max deg | "
           "median 3-sigma mm | 3-sigma coverage | identifiable 95th mm / deg |\n"
           "|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (int l : s.all_loops) {
    std::vector<double> e_mm, e_deg, b_mm, a_mm, a_deg;
    int in = 0;
    for (const auto& r : all_runs) {
      if (r.loops != l || !r.usable()) continue;
      a_mm.push_back(r.r.identifiable_error_mm);
      a_deg.push_back(r.r.identifiable_error_deg);
      e_mm.push_back(r.r.effective_error_mm);
      e_deg.push_back(r.r.effective_error_deg);
      b_mm.push_back(r.r.bound3_mm);
      in += r.within() ? 1 : 0;
    }
    char buf[1024];
    std::snprintf(buf, sizeof buf,
                  "| %d | %d | %zu | %.3f | %.3f | %.3f | %.4f | %.4f | %.4f | %.3f | %.0f %% | %.3f / %.4f |\n", l,
                  l * s.poses_per_loop, e_mm.size(), percentile(e_mm, 0.5), percentile(e_mm, 0.95),
                  percentile(e_mm, 1.0), percentile(e_deg, 0.5), percentile(e_deg, 0.95), percentile(e_deg, 1.0),
                  percentile(b_mm, 0.5), e_mm.empty() ? 0.0 : 100.0 * in / e_mm.size(), percentile(a_mm, 0.95),
                  percentile(a_deg, 0.95));
    table << buf;
  }
  return table.str();
}

void writeResults(const Study& s, const Runs& runs, const std::string& report) {
  writeFileAtomically(s.out + "/robots.csv", runs.robots_csv);
  writeFileAtomically(s.out + "/runs.csv", runs.runs_csv);
  writeFileAtomically(s.out + "/table.md", report);
  char buf[1024];
  std::snprintf(buf, sizeof buf, "magnitude %.1f, %.0f %% reflections, %s method, %d loops (%d poses), %d robots",
                s.magnitude, s.reflections * 100, s.method.c_str(), s.loops, s.loops * s.poses_per_loop, s.robots);
  writePngAtomically(s.out + "/error_per_robot.png", errorPerRobotPicture(runs.main, buf));
  std::snprintf(buf, sizeof buf, "magnitude %.1f, %.0f %% reflections, %s, %d robots", s.magnitude, s.reflections * 100,
                s.method.c_str(), s.robots);
  writePngAtomically(s.out + "/error_vs_poses.png", errorVersusPosesPicture(runs.all, s.all_loops, s.poses_per_loop, buf));
  std::cout << "written: " << s.out << "/robots.csv (one row per robot), " << s.out << "/runs.csv (every run), " << s.out
            << "/table.md, " << s.out << "/error_per_robot.png, " << s.out << "/error_vs_poses.png\n";
}

int accuracyStudy(const Options& o) {
  Study s = study(o);
  std::filesystem::create_directories(s.out);
  CalibrationClient client("imagenets_accuracy_study", o["wait"].as<double>());
  const SimulatorState sim = simulatorState();
  s.reflections = s.reflections_percent >= 0 ? s.reflections_percent / 100 : sim.reflections;
  if (s.reflections_percent >= 0) CalibrationClient::setSimParam("faults/reflection_probability", s.reflections);
  ros::param::get("/friend_calibration/poses_per_loop", s.poses_per_loop);
  if (s.method == "paper") s.poses_per_loop = 1;

  std::ostringstream report;
  report << reportHeader(s);
  std::cout << report.str() << std::flush;
  const Runs runs = calibrateRobots(client, s, report);
  // Back to the simulator's own true robot and reflection rate.
  client.setTrueRobot(sim.seed, sim.magnitude);
  if (s.reflections_percent >= 0) CalibrationClient::setSimParam("faults/reflection_probability", sim.reflections);

  const std::string tables = percentileTable(runs.main, s.robots) + (s.sweep.empty() ? "" : poseSweepTable(runs.all, s));
  report << tables;
  std::cout << tables;
  writeResults(s, runs, report.str());
  return 0;
}

}  // namespace

IMAGENETS_TOOL_COMMAND(accuracy_study, "accuracy-study",
                       "accuracy-study [--true-robots 20] [--first-seed 1] [--magnitude 1] [--reflections PERCENT] "
                       "[--method joint|paper] [--loops 5] [--pose-sweep 3,7|none] [--output-dir DIR] [--wait S]",
                       "calibrate many random true robots of the running simulator; error percentiles, 3-sigma "
                       "coverage, CSV and pictures",
                       declare, accuracyStudy);

}  // namespace tool
}  // namespace imagenets

// A program of its own, `imagenets-NAME`, run as `imagenets NAME`.
int main(int argc, char** argv) { return imagenets::tool::runCommandLine(argc, argv); }
