// `imagenets marker-study`: the paper's marker accuracy study (5.1, Fig. 5.2) and its harder
// conditions, see marker_study/marker_study.h. Writes study.csv, summary.md and
// error_map_<condition>.png; prints the tables (the default detection beside libapriltag with the
// targets per condition).
#include <chrono>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <sstream>
#include <algorithm>
#include <cmath>

#include <boost/filesystem.hpp>
#include <opencv2/imgcodecs.hpp>

#include "imagenets/tool/command.h"
#include "marker_study/marker_study.h"

namespace imagenets {
namespace tool {
namespace {

void writeAtomically(const std::string& path, const std::string& text) {
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp);
    out << text;
    if (!out) throw std::runtime_error(tmp + ": cannot write");
  }
  boost::filesystem::rename(tmp, path);
}

void writePng(const std::string& path, const cv::Mat& image) {
  const std::string tmp = path + ".tmp.png";
  if (!cv::imwrite(tmp, image)) throw std::runtime_error(tmp + ": cannot write");
  boost::filesystem::rename(tmp, path);
}

void parseRange(const std::string& text, double* from, double* to, double* step) {
  if (std::sscanf(text.c_str(), "%lf:%lf:%lf", from, to, step) != 3 || !(*step > 0) || *to < *from) {
    throw UsageError("range '" + text + "' is not FROM:TO:STEP with FROM <= TO, STEP > 0");
  }
}

void declare(Flags& f) {
  f.add()("output-dir,o", po::value<std::string>()->default_value("marker_study"), "where the CSV, tables and maps go")
      ("conditions", po::value<std::string>(), "paper, hard, all or NAME,... (default: the paper's)")
      ("quick", po::bool_switch(), "a coarse grid; the other flags still change it")
      ("marker", po::value<std::string>(), "the marker (M.yaml)")
      ("camera", po::value<std::string>(), "the camera (C.yaml)")
      ("net", po::value<std::string>(), "the detection net (`detect`)")
      ("calibration-net", po::value<std::string>(), "the calibration's detection net (`calibration`)")
      ("decoys", po::bool_switch(), "also views with a decoy in the marker's place: false positives")
      ("tag-target", po::value<std::string>(), "the AprilTag target libapriltag detects")
      ("board-target", po::value<std::string>(), "the ChArUco board target")
      ("no-targets", po::bool_switch(), "neither target")
      ("pan", po::value<std::string>(), "FROM:TO:STEP in degrees (e.g. 0:350:10)")
      ("tilt", po::value<std::string>(), "FROM:TO:STEP in degrees (e.g. 0:70:10)")
      ("threshold", po::value<int>(), "a fixed threshold besides the feedback (e.g. 40)")
      ("threads", po::value<int>(), "worker threads")
      ("supersampling", po::value<int>(), "rendering supersampling (e.g. 4)")
      ("seed", po::value<unsigned>(), "the noise's seed")
      ("scale-mm", po::value<double>()->default_value(0), "the error maps' colour scale (0: the largest error)")
      ("from-csv", po::value<std::string>(), "re-plot and re-summarise an earlier STUDY.csv instead of running");
}

marker::StudyConfig studyConfig(const Options& o) {
  marker::StudyConfig config;
  if (o["quick"].as<bool>()) marker::makeQuick(&config);
  auto text = [&](const char* flag, std::string* to) {
    if (o.count(flag)) *to = o[flag].as<std::string>();
  };
  text("marker", &config.marker);
  text("camera", &config.camera);
  text("net", &config.net);
  text("calibration-net", &config.calibration_net);
  config.decoys = o["decoys"].as<bool>() || config.decoys;
  if (o["no-targets"].as<bool>()) config.tag_target.clear(), config.board_target.clear();
  text("tag-target", &config.tag_target);
  text("board-target", &config.board_target);
  if (o.count("pan")) parseRange(o["pan"].as<std::string>(), &config.pan_from, &config.pan_to, &config.pan_step);
  if (o.count("tilt")) parseRange(o["tilt"].as<std::string>(), &config.tilt_from, &config.tilt_to, &config.tilt_step);
  if (o.count("threshold")) config.fixed_threshold = o["threshold"].as<int>();
  if (o.count("conditions")) {
    try {
      config.conditions = marker::selectConditions(o["conditions"].as<std::string>());
    } catch (const std::invalid_argument& e) {
      throw UsageError(std::string("--conditions: ") + e.what());
    }
  }
  if (o.count("threads")) config.threads = o["threads"].as<int>();
  if (o.count("supersampling")) config.supersampling = o["supersampling"].as<int>();
  if (o.count("seed")) config.seed = o["seed"].as<unsigned>();
  return config;
}

// The rows of an earlier run; its conditions become the config's.
std::vector<marker::StudyRow> readRows(const std::string& csv, marker::StudyConfig& config) {
  std::ifstream in(csv);
  if (!in) throw std::runtime_error(csv + ": cannot read");
  std::stringstream text;
  text << in.rdbuf();
  std::vector<marker::StudyRow> rows = marker::fromCsv(text.str());
  std::vector<marker::StudyCondition> conditions;
  for (const auto& r : rows) {
    if (std::none_of(conditions.begin(), conditions.end(), [&](const auto& c) { return c.name == r.condition; })) {
      conditions.push_back(marker::selectConditions(r.condition).front());
    }
  }
  config.conditions = conditions;
  return rows;
}

std::vector<marker::StudyRow> runWithProgress(const marker::StudyConfig& config) {
  const auto t0 = std::chrono::steady_clock::now();
  auto rows = marker::runStudy(config, [&](int done, int total) {
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::cerr << "\rmarker study: " << done << "/" << total << " views, " << static_cast<int>(s) << " s elapsed, ~"
              << static_cast<int>(s / done * (total - done)) << " s left   " << std::flush;
  });
  std::cerr << "\n";
  return rows;
}

// One colour scale for every picture: up to the largest error of any method, rounded up to
// 0.5 mm (at least 1 mm).
double errorScale(const std::vector<marker::StudySummaryRow>& summary) {
  double scale_mm = 0;
  for (const auto& s : summary) {
    if (std::isfinite(s.max_mm)) scale_mm = std::max(scale_mm, s.max_mm);
  }
  return std::max(1.0, std::ceil(scale_mm * 2) / 2);
}

int run(const Options& o) {
  marker::StudyConfig config = studyConfig(o);
  const std::string out_dir = o["output-dir"].as<std::string>();
  boost::filesystem::create_directories(out_dir);
  const std::vector<marker::StudyRow> rows =
      o.count("from-csv") ? readRows(o["from-csv"].as<std::string>(), config) : runWithProgress(config);
  const auto summary = marker::summarize(rows);
  writeAtomically(out_dir + "/study.csv", marker::toCsv(rows));
  const std::string table = marker::toMarkdown(summary, config) +
                            "\nOur nets (`detect`: the default, `calibration`) beside libapriltag, with the study's targets "
                            "(detection rate at least libapriltag's, median position error at most half of "
                            "libapriltag's):\n\n" +
                            marker::sideBySideMarkdown(summary);
  writeAtomically(out_dir + "/summary.md", table);
  const double scale_mm = o["scale-mm"].as<double>() > 0 ? o["scale-mm"].as<double>() : errorScale(summary);
  for (const auto& condition : config.conditions) {
    const std::string path = out_dir + "/error_map_" + condition.name + ".png";
    writePng(path, marker::errorMapImage(rows, condition.name, scale_mm));
    std::cout << "wrote " << path << "\n";
  }
  std::cout << "wrote " << out_dir << "/study.csv (" << rows.size() << " rows), " << out_dir << "/summary.md\n\n"
            << table;
  return 0;
}

}  // namespace

IMAGENETS_TOOL_COMMAND(marker_study, "marker-study",
                       "marker-study [--output-dir DIR] [--conditions paper|hard|all|NAME,...] [--quick] "
                       "[--marker M.yaml] [--camera C.yaml] [--net NET.yaml] [--calibration-net NET.yaml] [--decoys] "
                       "[--tag-target T.yaml] [--board-target T.yaml | --no-targets] "
                       "[--pan 0:350:10] [--tilt 0:70:10] "
                       "[--threshold 40] [--threads N] [--supersampling 4] [--seed N] [--scale-mm S] "
                       "[--from-csv STUDY.csv]",
                       "the paper's marker accuracy study (5.1, Fig. 5.2) and harder imaging (far, blur, noise, dim, "
                       "dark wall), libapriltag beside: CSV, tables, error maps; --decoys: false positives on decoys",
                       declare, run);

}  // namespace tool
}  // namespace imagenets
