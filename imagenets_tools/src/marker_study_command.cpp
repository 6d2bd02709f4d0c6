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

int run(const Args& args) {
  marker::StudyConfig config;
  std::string out_dir = "marker_study";
  double scale_mm = 0;
  std::string from_csv;  // re-plot / re-summarise an earlier run instead of running the study
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    if (a == "--marker") config.marker = flagValue(args, i);
    else if (a == "--camera") config.camera = flagValue(args, i);
    else if (a == "--net") config.net = flagValue(args, i);
    else if (a == "--calibration-net") config.calibration_net = flagValue(args, i);
    else if (a == "--decoys") config.decoys = true;
    else if (a == "--no-targets") config.tag_target.clear(), config.board_target.clear();
    else if (a == "--tag-target") config.tag_target = flagValue(args, i);
    else if (a == "--board-target") config.board_target = flagValue(args, i);
    else if (a == "--output-dir" || a == "-o") out_dir = flagValue(args, i);
    else if (a == "--quick") marker::makeQuick(&config);  // flags after it still change the grid
    else if (a == "--pan") parseRange(flagValue(args, i), &config.pan_from, &config.pan_to, &config.pan_step);
    else if (a == "--tilt") parseRange(flagValue(args, i), &config.tilt_from, &config.tilt_to, &config.tilt_step);
    else if (a == "--threshold") config.fixed_threshold = intValue(args, i);
    else if (a == "--conditions") {
      const std::string names = flagValue(args, i);
      try {
        config.conditions = marker::selectConditions(names);
      } catch (const std::invalid_argument& e) {
        throw UsageError(std::string("--conditions: ") + e.what());
      }
    } else if (a == "--threads") config.threads = intValue(args, i);
    else if (a == "--supersampling") config.supersampling = intValue(args, i);
    else if (a == "--seed") config.seed = static_cast<unsigned>(std::stoul(flagValue(args, i)));
    else if (a == "--scale-mm") scale_mm = doubleValue(args, i);
    else if (a == "--from-csv") from_csv = flagValue(args, i);
    else throw unknownArgument(a);
  }
  boost::filesystem::create_directories(out_dir);
  std::vector<marker::StudyRow> rows;
  if (!from_csv.empty()) {
    std::ifstream in(from_csv);
    if (!in) throw std::runtime_error(from_csv + ": cannot read");
    std::stringstream text;
    text << in.rdbuf();
    rows = marker::fromCsv(text.str());
    std::vector<marker::StudyCondition> conditions;
    for (const auto& r : rows) {
      if (std::none_of(conditions.begin(), conditions.end(), [&](const auto& c) { return c.name == r.condition; })) {
        conditions.push_back(marker::selectConditions(r.condition).front());
      }
    }
    config.conditions = conditions;
  } else {
    const auto t0 = std::chrono::steady_clock::now();
    rows = marker::runStudy(config, [&](int done, int total) {
      const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      std::cerr << "\rmarker study: " << done << "/" << total << " views, " << static_cast<int>(s) << " s elapsed, ~"
                << static_cast<int>(s / done * (total - done)) << " s left   " << std::flush;
    });
    std::cerr << "\n";
  }
  const auto summary = marker::summarize(rows);
  writeAtomically(out_dir + "/study.csv", marker::toCsv(rows));
  const std::string table = marker::toMarkdown(summary, config) +
                            "\nOur nets (`detect`: the default, `calibration`) beside libapriltag, with the study's targets "
                            "(detection rate at least libapriltag's, median position error at most half of "
                            "libapriltag's):\n\n" +
                            marker::sideBySideMarkdown(summary);
  writeAtomically(out_dir + "/summary.md", table);
  if (!(scale_mm > 0)) {
    // One colour scale for every picture: up to the largest error of any method, rounded up to
    // 0.5 mm (at least 1 mm).
    for (const auto& s : summary) {
      if (std::isfinite(s.max_mm)) scale_mm = std::max(scale_mm, s.max_mm);
    }
    scale_mm = std::max(1.0, std::ceil(scale_mm * 2) / 2);
  }
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
                       run);

}  // namespace tool
}  // namespace imagenets
