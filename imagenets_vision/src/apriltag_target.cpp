// AprilTag targets (target.h): libapriltag finds the tags, their black squares are located again
// on the gray image by the square marker's edge fit, and the pose is fitted to every corner.
#include <algorithm>
#include <cmath>
#include <map>
#include <mutex>

#include <opencv2/imgproc.hpp>

extern "C" {
#include <apriltag/apriltag.h>
#include <apriltag/common/image_u8.h>
#include <apriltag/common/matd.h>
#include <apriltag/tag16h5.h>
#include <apriltag/tag25h9.h>
#include <apriltag/tag36h10.h>
#include <apriltag/tag36h11.h>
#include <apriltag/tagCircle21h7.h>
#include <apriltag/tagCircle49h12.h>
#include <apriltag/tagCustom48h12.h>
#include <apriltag/tagStandard41h12.h>
#include <apriltag/tagStandard52h13.h>
}

#include "imagenets/vision/marker.h"
#include "target_internal.h"

namespace imagenets {
namespace target {
namespace detail {

namespace {

struct Family {
  const char* name;
  apriltag_family_t* (*create)();
  void (*destroy)(apriltag_family_t*);
};

const std::vector<Family>& families() {
  static const std::vector<Family> all{
      {"tag36h11", tag36h11_create, tag36h11_destroy},
      {"tag36h10", tag36h10_create, tag36h10_destroy},
      {"tag25h9", tag25h9_create, tag25h9_destroy},
      {"tag16h5", tag16h5_create, tag16h5_destroy},
      {"tagCircle21h7", tagCircle21h7_create, tagCircle21h7_destroy},
      {"tagCircle49h12", tagCircle49h12_create, tagCircle49h12_destroy},
      {"tagCustom48h12", tagCustom48h12_create, tagCustom48h12_destroy},
      {"tagStandard41h12", tagStandard41h12_create, tagStandard41h12_destroy},
      {"tagStandard52h13", tagStandard52h13_create, tagStandard52h13_destroy},
  };
  return all;
}

const Family* findFamily(const std::string& name) {
  for (const Family& f : families()) {
    if (name == f.name) return &f;
  }
  return nullptr;
}

// One family object, created when first asked for and kept (libapriltag's families are read-only
// once made; tagStandard52h13 takes a moment to build its tables).
apriltag_family_t* sharedFamily(const Family& f) {
  static std::mutex mutex;
  static std::map<std::string, apriltag_family_t*> made;  // never destroyed: process lifetime
  std::lock_guard<std::mutex> lock(mutex);
  auto& tf = made[f.name];
  if (!tf) tf = f.create();
  return tf;
}

}  // namespace

bool aprilTagFamily(const std::string& name, FamilyInfo* info, std::string* known) {
  const Family* f = findFamily(name);
  if (!f) {
    known->clear();
    for (const Family& g : families()) *known += (known->empty() ? "" : ", ") + std::string(g.name);
    return false;
  }
  apriltag_family_t* tf = sharedFamily(*f);
  info->codes = static_cast<int>(tf->ncodes);
  info->border_cells = tf->width_at_border;
  info->total_cells = tf->total_width;
  info->reversed_border = tf->reversed_border;
  return true;
}

cv::Mat aprilTagCells(const std::string& family, int id) {
  const Family* f = findFamily(family);
  if (!f) throw std::invalid_argument("AprilTag family '" + family + "' is unknown");
  apriltag_family_t* tf = sharedFamily(*f);
  if (id < 0 || id >= static_cast<int>(tf->ncodes)) {
    throw std::invalid_argument("AprilTag id " + std::to_string(id) + " is not in family " + family);
  }
  image_u8_t* code = apriltag_to_image(tf, id);
  cv::Mat cells = cv::Mat(code->height, code->width, CV_8UC1, code->buf, code->stride).clone();
  image_u8_destroy(code);
  return cells;
}

TargetDetection detectAprilTags(const cv::Mat& gray, const render::CameraModel& camera, const TargetDescription& t,
                                const TargetDetectorOptions& options) {
  const Family* f = findFamily(t.family);
  if (!f) throw std::invalid_argument(t.file + ": AprilTag family '" + t.family + "' is unknown");
  // A detector and a family per call: libapriltag's detector keeps per-detection state, and
  // adding a family to a detector builds its decode table inside the family, which destroying the
  // detector frees: a family shared by detectors in parallel (both cameras) is freed twice.
  apriltag_family_t* tf = f->create();
  apriltag_detector_t* td = apriltag_detector_create();
  apriltag_detector_add_family(td, tf);
  td->quad_decimate = static_cast<float>(options.quad_decimate);
  td->quad_sigma = static_cast<float>(options.quad_sigma);
  td->refine_edges = true;
  td->nthreads = std::max(1, options.threads);
  image_u8_t im{gray.cols, gray.rows, static_cast<int32_t>(gray.step), const_cast<uint8_t*>(gray.data)};
  zarray_t* dets = apriltag_detector_detect(td, &im);

  TargetDetection out;
  const std::map<int, Eigen::Vector3d> corners = t.corners();
  const int first = t.id, last = t.id + t.rows * t.cols - 1;
  double margin_sum = 0;
  std::map<int, const apriltag_detection_t*> seen;  // one detection per id: the strongest
  for (int i = 0; i < zarray_size(dets); ++i) {
    apriltag_detection_t* det;
    zarray_get(dets, i, &det);
    if (det->id < first || det->id > last) continue;
    auto& s = seen[det->id];
    if (!s || det->decision_margin > s->decision_margin) s = det;
  }
  for (const auto& [id, det] : seen) {
    // Which corner is which from libapriltag's homography: its tag frame has y down (row 0 of the
    // code image at y = -1), so (-1,-1) (1,-1) (1,1) (-1,1) are our TL TR BR BL.
    std::vector<cv::Point2d> quad(4);
    {
      cv::Matx33d H;
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) H(r, c) = MATD_EL(det->H, r, c);
      const cv::Matx33d Hinv = H.inv();
      for (int i = 0; i < 4; ++i) {
        const cv::Vec3d q = Hinv * cv::Vec3d(det->p[i][0], det->p[i][1], 1.0);
        const bool right = q[0] / q[2] > 0, bottom = q[1] / q[2] > 0;
        const int k = bottom ? (right ? 2 : 3) : (right ? 1 : 0);
        quad[k] = cv::Point2d(det->p[i][0], det->p[i][1]);
      }
    }
    // Small tags keep libapriltag's corners: with cells under 4 px the edge search would reach the code.
    double shortest = 1e9;
    for (int k = 0; k < 4; ++k) shortest = std::min(shortest, cv::norm(quad[k] - quad[(k + 1) % 4]));
    if (options.refine_edges && !tf->reversed_border && shortest / tf->width_at_border >= 4.0) {
      std::vector<cv::Point2d> refined;
      if (marker::refineSquareEdges(gray, camera, quad, 2, &refined)) quad = refined;
    }
    for (int k = 0; k < 4; ++k) {
      out.ids.push_back(4 * id + k);
      out.points.push_back(quad[k]);
      out.object_points.push_back(corners.at(4 * id + k));
    }
    margin_sum += det->decision_margin;
    ++out.tags;
  }
  apriltag_detections_destroy(dets);
  apriltag_detector_destroy(td);
  f->destroy(tf);

  out.confidence = out.tags ? std::min(1.0, std::max(0.0, margin_sum / out.tags / 100.0)) : 0.0;
  if (out.tags == 0) {
    out.reason = "no tag of " + t.family + " with id " + std::to_string(first) +
                 (last > first ? ".." + std::to_string(last) : "") + " found";
    return out;
  }
  if (static_cast<int>(out.points.size()) < std::max(4, options.min_corners)) {
    out.reason = std::to_string(out.points.size()) + " corners found, fewer than " + std::to_string(options.min_corners);
    return out;
  }
  out.found = fitTargetPose(camera, options, &out);
  if (!out.found) out.reason = "no pose fits the corners";
  return out;
}

}  // namespace detail
}  // namespace target
}  // namespace imagenets
