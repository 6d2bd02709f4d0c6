// libapriltag wrapper (see apriltag_marker.h).
#include "imagenets/vision/apriltag_marker.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <stdexcept>

#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

extern "C" {
#include <apriltag/apriltag.h>
#include <apriltag/apriltag_pose.h>
#include <apriltag/common/matd.h>
#include <apriltag/tag16h5.h>
#include <apriltag/tag25h9.h>
#include <apriltag/tag36h11.h>
#include <apriltag/tagStandard41h12.h>
}

namespace imagenets {
namespace marker {

namespace {

struct Family {
  apriltag_family_t* (*create)();
  void (*destroy)(apriltag_family_t*);
};

Family familyByName(const std::string& name) {
  if (name == "tag36h11") return {tag36h11_create, tag36h11_destroy};
  if (name == "tag25h9") return {tag25h9_create, tag25h9_destroy};
  if (name == "tag16h5") return {tag16h5_create, tag16h5_destroy};
  if (name == "tagStandard41h12") return {tagStandard41h12_create, tagStandard41h12_destroy};
  throw std::invalid_argument("AprilTag family '" + name + "' is not supported (tag36h11, tag25h9, tag16h5, tagStandard41h12)");
}

Eigen::Isometry3d fromAprilPose(const apriltag_pose_t& p) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) T.linear()(r, c) = MATD_EL(p.R, r, c);
    T.translation()(r) = MATD_EL(p.t, r, 0);
  }
  // libapriltag's tag frame: x right, y down, z into the tag. Ours: y up, z out of the face.
  T.linear() = T.linear() * Eigen::Vector3d(1, -1, -1).asDiagonal();
  return T;
}

}  // namespace

struct AprilTagDetector::Impl {
  Family family;
  apriltag_family_t* tf = nullptr;
  apriltag_detector_t* td = nullptr;
};

AprilTagDetector::AprilTagDetector(const AprilTagOptions& options) : options_(options), impl_(new Impl) {
  if (!(options.size > 0)) throw std::invalid_argument("AprilTag size must be > 0 metres");
  impl_->family = familyByName(options.family);
  impl_->tf = impl_->family.create();
  impl_->td = apriltag_detector_create();
  apriltag_detector_add_family(impl_->td, impl_->tf);
  impl_->td->quad_decimate = static_cast<float>(options.quad_decimate);
  impl_->td->quad_sigma = static_cast<float>(options.quad_sigma);
  impl_->td->refine_edges = options.refine_edges;
  impl_->td->nthreads = options.threads;
}

AprilTagDetector::~AprilTagDetector() {
  apriltag_detector_destroy(impl_->td);
  impl_->family.destroy(impl_->tf);
}

Detection AprilTagDetector::detect(const cv::Mat& gray, const render::CameraModel& camera) const {
  if (gray.empty() || gray.type() != CV_8UC1) throw std::invalid_argument("gray image must be a non-empty mono8 image");
  if (gray.cols != camera.width || gray.rows != camera.height) {
    throw std::invalid_argument("image is " + std::to_string(gray.cols) + "x" + std::to_string(gray.rows) +
                                " but camera_info says " + std::to_string(camera.width) + "x" +
                                std::to_string(camera.height));
  }
  image_u8_t im{gray.cols, gray.rows, static_cast<int32_t>(gray.step), const_cast<uint8_t*>(gray.data)};
  zarray_t* dets = apriltag_detector_detect(impl_->td, &im);
  Detection result;
  result.candidates = zarray_size(dets);
  apriltag_detection_t* chosen = nullptr;
  for (int i = 0; i < zarray_size(dets); ++i) {
    apriltag_detection_t* det;
    zarray_get(dets, i, &det);
    if (options_.id >= 0 && det->id != options_.id) continue;
    if (!chosen || det->id < chosen->id) chosen = det;
  }
  if (chosen) {
    // Undistort the corners into an ideal pinhole image with the same K, and recompute the
    // homography from the tag's corner coordinates (which corner is which: from libapriltag's H).
    std::vector<cv::Point2d> px, ideal;
    for (int i = 0; i < 4; ++i) px.emplace_back(chosen->p[i][0], chosen->p[i][1]);
    if (!camera.D.empty()) {
      cv::undistortPoints(px, ideal, cv::Mat(camera.K), cv::Mat(camera.D), cv::noArray(), cv::Mat(camera.K),
                          cv::TermCriteria(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, 30, 1e-12));
    } else {
      ideal = px;
    }
    cv::Matx33d H0;
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) H0(r, c) = MATD_EL(chosen->H, r, c);
    const cv::Matx33d H0inv = H0.inv();
    std::vector<cv::Point2f> tag, img;
    for (int i = 0; i < 4; ++i) {
      const cv::Vec3d t = H0inv * cv::Vec3d(px[i].x, px[i].y, 1.0);
      tag.emplace_back(t[0] / t[2] > 0 ? 1.f : -1.f, t[1] / t[2] > 0 ? 1.f : -1.f);
      img.emplace_back(ideal[i]);
    }
    const cv::Mat H = cv::getPerspectiveTransform(tag, img);
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) MATD_EL(chosen->H, r, c) = H.at<double>(r, c);
    for (int i = 0; i < 4; ++i) chosen->p[i][0] = ideal[i].x, chosen->p[i][1] = ideal[i].y;

    apriltag_detection_info_t info{chosen, options_.size, camera.K(0, 0), camera.K(1, 1), camera.K(0, 2), camera.K(1, 2)};
    apriltag_pose_t pose{nullptr, nullptr};
    const double err = estimate_tag_pose(&info, &pose);  // the better of libapriltag's two solutions
    if (pose.R) {
      result.found = true;
      result.pose = result.alt_pose = fromAprilPose(pose);  // Debian's build exports only this one
      result.reprojection_error = result.alt_reprojection_error = err;  // libapriltag's object-space error
      result.confidence = std::min(1.0, std::max(0.0, chosen->decision_margin / 100.0));
      // Corners TL TR BR BL of our marker frame (y up): tag coords (-1,+1) (+1,+1) (+1,-1) (-1,-1)
      // in libapriltag's y-down tag frame are (-1,-1) (1,-1) (1,1) (-1,1).
      const double order[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
      for (int j = 0; j < 4; ++j) {
        for (int i = 0; i < 4; ++i) {
          if (tag[i].x == order[j][0] && tag[i].y == order[j][1]) result.points[j] = px[i];
        }
      }
    }
    // matd_t is one calloc'd block (Debian's libapriltag does not export matd_destroy).
    std::free(pose.R);
    std::free(pose.t);
  }
  apriltag_detections_destroy(dets);
  return result;
}

render::Plane aprilTagPlane(const AprilTagOptions& options, int id, double margin, const Eigen::Isometry3d& pose,
                            int pixels_per_cell) {
  const Family family = familyByName(options.family);
  apriltag_family_t* tf = family.create();
  if (id < 0 || id >= static_cast<int>(tf->ncodes)) {
    family.destroy(tf);
    throw std::invalid_argument("AprilTag id " + std::to_string(id) + " is not in family " + options.family);
  }
  image_u8_t* code = apriltag_to_image(tf, id);
  const int total = code->width, border_cells = tf->width_at_border;
  const int pad = (total - border_cells) / 2;  // the white cells libapriltag already draws
  cv::Mat cells(code->height, code->width, CV_8UC1, code->buf, code->stride);
  cells = cells.clone();
  image_u8_destroy(code);
  family.destroy(tf);
  // Extra white quiet zone (in cells) so the physical layout matches markerPlane().
  const double cell_m = options.size / border_cells;
  const int margin_cells = std::max(0, static_cast<int>(std::lround(margin * options.size / cell_m)) - pad);
  cv::copyMakeBorder(cells, cells, margin_cells, margin_cells, margin_cells, margin_cells, cv::BORDER_CONSTANT,
                     cv::Scalar(255));
  render::Plane plane;
  cv::resize(cells, plane.texture, cv::Size(), pixels_per_cell, pixels_per_cell, cv::INTER_NEAREST);
  plane.width = plane.height = cells.cols * cell_m;
  plane.pose = pose;
  return plane;
}

}  // namespace marker
}  // namespace imagenets
