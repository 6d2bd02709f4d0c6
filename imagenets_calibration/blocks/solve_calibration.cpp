// The FRIEND calibration's solve (paper 4.1-4.2 and beyond): per sample the reprojection gate,
// stereo fusion and the chain to the fixed point; outlier rejection against the robust centre;
// then the mean rotation + per-axis median (method paper) or the joint least squares (joint).
// It calls imagenets_calibration's calibrate() (calibration.h); the properties are its limits.
#include <cmath>

#include <boost/make_shared.hpp>
#include <geometry_msgs/TransformStamped.h>
#include <imagenets_calibration_msgs/CalibrationResult.h>
#include <imagenets_calibration_msgs/CalibrationSamples.h>

#include "calibration_ports.h"
#include "imagenets_calibration/calibration_msgs.h"
#include "imagenets/vision/frames.h"
#include "imagenets/register_block.h"

namespace imagenets_calibration {
namespace blocks {

class SolveCalibration : public imagenets::Block {
 public:
  SolveCalibration() {
    addInput<imagenets_calibration_msgs::CalibrationSamples>("samples", "the raw samples (a repeated sample sub-net's `sample_all`)");
    addInput<imagenets_calibration_msgs::CalibrationPlan>("plan", "the plan (its method)");
    addOutput<imagenets_calibration_msgs::CalibrationResult>("result", "fixed point, spread, used / rejected samples, residuals");
    addOutput<geometry_msgs::TransformStamped>("fixed_point", "base -> pth_fixed_point; only on success");
    const FusionLimits f;
    const CombineOptions c;
    addProperty<double>("max_position_difference", f.max_position_difference, "m: left and right must agree within")
        .range(0.0, 1.0);
    addProperty<double>("max_angle_difference", f.max_angle_difference, "rad: ... and within").range(0.0, M_PI);
    addProperty<double>("max_reprojection_error", f.max_reprojection_error, "px: a detection fitting worse is not used")
        .range(0.0, 100.0);
    addProperty<double>("relative_reprojection_error", f.relative_reprojection_error,
                        "tighten the limit to this x the median reprojection error (0 = off)")
        .range(0.0, 100.0);
    addProperty<double>("min_reprojection_error", f.min_reprojection_error, "px: floor of the tightened limit")
        .range(0.0, 100.0);
    addProperty<double>("outlier_translation_floor", c.outlier_translation_floor, "m").range(0.0, 1.0);
    addProperty<double>("outlier_rotation_floor", c.outlier_rotation_floor, "rad").range(0.0, M_PI);
    addProperty<double>("outlier_sigmas", c.outlier_sigmas, "robust sigmas from the centre to an outlier")
        .range(0.0, 100.0);
    addProperty<double>("min_valid_fraction", 0.5, "fewer valid samples (after rejection) fail the calibration")
        .range(0.0, 1.0);
    addProperty<std::string>("child_frame_id", "pth_fixed_point", "the fixed point's frame");
    addProperty<std::string>("description", "", "robot description YAML (required)").path();
    addPropertySpec(calibrationCameraProperty());
  }

  void process(imagenets::Context& ctx) override {
    const RobotModel& model =
        robotModel(ctx.property<std::string>("description"), ctx.property<std::string>("calibration_camera"));
    const auto plan = ctx.input<imagenets_calibration_msgs::CalibrationPlan>("plan");
    const auto in = ctx.input<imagenets_calibration_msgs::CalibrationSamples>("samples");
    std::vector<Sample> samples;
    for (const auto& s : in->samples) samples.push_back(fromMsg(s));
    FusionLimits limits;
    limits.max_position_difference = ctx.property<double>("max_position_difference");
    limits.max_angle_difference = ctx.property<double>("max_angle_difference");
    limits.max_reprojection_error = ctx.property<double>("max_reprojection_error");
    limits.relative_reprojection_error = ctx.property<double>("relative_reprojection_error");
    limits.min_reprojection_error = ctx.property<double>("min_reprojection_error");
    CombineOptions combine;
    combine.outlier_translation_floor = ctx.property<double>("outlier_translation_floor");
    combine.outlier_rotation_floor = ctx.property<double>("outlier_rotation_floor");
    combine.outlier_sigmas = ctx.property<double>("outlier_sigmas");
    combine.min_valid_samples =
        std::max(1, static_cast<int>(std::ceil(ctx.property<double>("min_valid_fraction") * samples.size())));
    Result r;
    try {
      r = calibrate(model, std::move(samples), plan->method, limits, combine);
    } catch (const std::invalid_argument& e) {
      throw imagenets::BlockError(std::string("input 'plan': ") + e.what());
    }
    const std::string base = model.description().base_frame, child = ctx.property<std::string>("child_frame_id");
    auto result = boost::make_shared<imagenets_calibration_msgs::CalibrationResult>(toMsg(r, base, child));
    if (!in->samples.empty()) result->fixed_point.header.stamp = ros::Time(in->samples.back().stamp);
    ctx.output("result", result);
    if (r.success) ctx.output("fixed_point", boost::make_shared<geometry_msgs::TransformStamped>(result->fixed_point));
  }
};

}  // namespace blocks
}  // namespace imagenets_calibration

IMAGENETS_REGISTER_BLOCK(imagenets_calibration::blocks::SolveCalibration, "imagenets/SolveCalibration", "calibration",
                         "FRIEND calibration from samples: gate, fusion, chain, outliers, median (paper) or joint solve");
