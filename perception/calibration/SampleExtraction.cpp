#include "perception/calibration/SampleExtraction.h"

#include <array>
#include <cmath>
#include <cstdio>
#include <numbers>

#include <opencv2/imgproc.hpp>

#include "perception/calibration/CalibrationCost.h"
#include "perception/vision/GoalBoxDetector.h"
#include "perception/vision/VisionPipeline.h"
#include "robot/Error.h"

namespace nao::calibration {
namespace {

std::string fmt(const char* format, double a, double b = 0, double c = 0, double d = 0) {
  char buf[200];
  std::snprintf(buf, sizeof buf, format, a, b, c, d);
  return buf;
}

std::optional<Eigen::Vector2d> intersectLines(const ImageSegment& a, const ImageSegment& b) {
  const Eigen::Vector2d da = a.direction(), db = b.direction();
  const double det = da.x() * db.y() - da.y() * db.x();
  if (std::abs(det) < 1e-9) return std::nullopt;
  const Eigen::Vector2d r = b.from - a.from;
  return a.from + (r.x() * db.y() - r.y() * db.x()) / det * da;
}

double sinBetween(const ImageSegment& a, const ImageSegment& b) {
  const Eigen::Vector2d da = a.direction(), db = b.direction();
  return std::max(0.2, std::abs(da.x() * db.y() - da.y() * db.x()));
}


// Moves the end of an image edge that lies nearer the horizon so that the whole edge lies at
// least minDepression below the (uncalibrated) horizon: the solver moves the horizon by a few
// degrees, and a point near it would leave the ground. The line is the same; only the two
// points that stand for it change. False if too little is left.
bool clipBelowHorizon(const CameraMatrix& cm, ImageLine& e, double minDepression, double minLengthPx) {
  auto depression = [&](const Eigen::Vector2d& p) {
    const Eigen::Vector3d r = cm.pixelRay(p);
    return std::atan2(-r.z(), std::hypot(r.x(), r.y()));
  };
  const double da = depression(e.from), db = depression(e.to);
  if (da >= minDepression && db >= minDepression) return true;
  if (da < minDepression && db < minDepression) return false;
  Eigen::Vector2d& far = da < db ? e.from : e.to;
  const Eigen::Vector2d near = da < db ? e.to : e.from;
  double lo = 0, hi = 1;  // fraction from near to far: lo passes, hi fails
  for (int i = 0; i < 40; ++i) {
    const double mid = (lo + hi) / 2;
    if (depression(near + mid * (far - near)) >= minDepression) lo = mid;
    else hi = mid;
  }
  far = near + lo * (far - near);
  return (far - near).norm() >= minLengthPx;
}

// Each edge of a measured line kept below the (uncalibrated) horizon; false with the reason if
// too little of it is left.
bool keepBelowHorizon(LineMeasurement& line, int role, const CameraMatrix& coarse, const ExtractionOptions& o,
                      double longDepressionDeg, std::string& reason) {
  const double minDepressionDeg = role == ShortLine ? o.minDepressionDeg : longDepressionDeg;
  const double minDepression = minDepressionDeg * std::numbers::pi / 180;
  if (clipBelowHorizon(coarse, line.edgeA, minDepression, o.minClippedLengthPx) &&
      clipBelowHorizon(coarse, line.edgeB, minDepression, o.minClippedLengthPx))
    return true;
  reason = std::string("implausible ") + kLineRoleNames[role] + " line: " +
           fmt("less than %.0f px of it lies %.0f deg below the horizon", o.minClippedLengthPx, minDepressionDeg);
  return false;
}

// Step 4: does the sample look like the goal box on the ground, with the offsets used so far?
bool plausible(const CalibrationSample& sample, const CameraCalibration& current, const ExtractionOptions& o,
               std::string& reason) {
  CostOptions co;
  co.goalBoxDepth = o.goalBoxDepth;
  const CalibrationCost cost({sample}, co);
  const SampleResiduals r = cost.sampleResiduals(current.toArray(), 0);
  if (!r.projected) {
    reason = "implausible: a goal box line does not reach the ground";
    return false;
  }
  if (std::abs(r.angle1Deg) > o.maxAngleErrorDeg || std::abs(r.angle2Deg) > o.maxAngleErrorDeg) {
    reason = fmt("implausible: the lines meet at %.1f and %.1f deg from a right angle on the ground (at most %.0f)",
                 r.angle1Deg, r.angle2Deg, o.maxAngleErrorDeg);
    return false;
  }
  const double ratio = (r.depthErrorM + o.goalBoxDepth) / o.goalBoxDepth;
  if (ratio < o.minDepthRatio || ratio > o.maxDepthRatio) {
    reason = fmt("implausible: the long lines are %.2f m apart on the ground (goal box: %.2f m, accepted %.2f-%.2f m)",
                 r.depthErrorM + o.goalBoxDepth, o.goalBoxDepth, o.minDepthRatio * o.goalBoxDepth,
                 o.maxDepthRatio * o.goalBoxDepth);
    return false;
  }
  return true;
}

// A painted line measured by the vision's sub-pixel centre line instead of its edges: the two
// edges half a line's width either side of it on the ground (with the coarse matrix), so that
// their bisector on the ground, which the cost takes, is the vision's line.
std::optional<LineMeasurement> edgesAroundCentre(const ImageSegment& centre, const CameraMatrix& coarse, double lineWidth) {
  const auto g0 = coarse.pixelToGround(centre.from), g1 = coarse.pixelToGround(centre.to);
  if (!g0 || !g1 || (*g1 - *g0).norm() < 1e-6) return std::nullopt;
  const Eigen::Vector2d d = (*g1 - *g0).normalized(), n(-d.y(), d.x());
  LineMeasurement m;
  const auto a0 = coarse.projectGround(*g0 + lineWidth / 2 * n), a1 = coarse.projectGround(*g1 + lineWidth / 2 * n);
  const auto b0 = coarse.projectGround(*g0 - lineWidth / 2 * n), b1 = coarse.projectGround(*g1 - lineWidth / 2 * n);
  if (!a0 || !a1 || !b0 || !b1) return std::nullopt;
  m.edgeA = {*a0, *a1};
  m.edgeB = {*b0, *b1};
  return m;
}

// Steps 3 and 4 for one candidate: the sample, or nullopt with the reason.
// proto: the sample's capture data (camera, intrinsics, joints and IMU or a recorded pose).
std::optional<CalibrationSample> measure(const GoalBoxSideDetection& det, const GradientImage& gradients,
                                         const CameraMatrix& coarse, const CalibrationSample& proto,
                                         const CameraCalibration& current, const ExtractionOptions& o,
                                         double longDepressionDeg, std::string& reason) {
  // 3: refine each line away from the junctions.
  const double s1 = sinBetween(det.shortLine, det.longLine1), s2 = sinBetween(det.shortLine, det.longLine2);
  const double ws = det.shortLine.widthPx, w1 = det.longLine1.widthPx, w2 = det.longLine2.widthPx;
  const double m = o.junctionMarginPx;
  const std::vector<Exclusion> shortExcl = {{det.junction1, (w1 / 2 + ws) / s1 + m}, {det.junction2, (w2 / 2 + ws) / s2 + m}};
  const std::vector<Exclusion> long1Excl = {{det.junction1, (ws / 2 + w1) / s1 + m}};
  const std::vector<Exclusion> long2Excl = {{det.junction2, (ws / 2 + w2) / s2 + m}};
  // The short line defines the junctions: it must be seen whole, from end to end; a worn
  // stretch between its ends may break the paint (hall-d's side line: 42-53 % coverage with
  // a 15 cm gap mid-line). A long line may be partly hidden (a goal post) as long as a good
  // stretch of it is measured.
  HoughRefinerOptions shortOpts = o.hough, longOpts = o.hough;
  shortOpts.minCoverage = std::max(o.hough.minCoverage, 0.7);
  shortOpts.minCoverageSpanned = std::min(shortOpts.minCoverageSpanned, 0.4);
  longOpts.minCoverage = std::min(o.hough.minCoverage, 0.4);
  const RefinedLine refined[3] = {refineLine(gradients, det.shortLine, shortExcl, shortOpts),
                                  refineLine(gradients, det.longLine1, long1Excl, longOpts),
                                  refineLine(gradients, det.longLine2, long2Excl, longOpts)};
  CalibrationSample sample = proto;
  for (int l = 0; l < 3; ++l) {
    if (!refined[l].ok) {
      reason = std::string("occluded or unclear ") + kLineRoleNames[l] + " line: " + refined[l].reason;
      return std::nullopt;
    }
    if (refined[l].measurement.rmsPx > o.maxFitRmsPx) {
      reason = std::string("implausible ") + kLineRoleNames[l] + " line: " +
               fmt("its edge points scatter by %.2f px (at most %.2f)", refined[l].measurement.rmsPx, o.maxFitRmsPx);
      return std::nullopt;
    }
    sample.lines[l] = refined[l].measurement;
    if (!keepBelowHorizon(sample.lines[l], l, coarse, o, longDepressionDeg, reason)) return std::nullopt;
  }
  if (!plausible(sample, current, o, reason)) return std::nullopt;
  return sample;
}

}  // namespace

LineSource lineSourceFromName(const std::string& name, const std::string& where) {
  if (name == "lsd") return LineSource::Lsd;
  if (name == "vision") return LineSource::Vision;
  if (name == "lsd+vision") return LineSource::LsdThenVision;
  throw Error(where, "must be lsd, vision or lsd+vision, not '" + name + "'");
}

cv::Mat greenness(const CameraImage& image) {
  cv::Mat y(image.height, image.width, CV_32F), u(image.height, image.width, CV_32F), v(image.height, image.width, CV_32F);
  for (int r = 0; r < image.height; ++r)
    for (int x = 0; x < image.width; ++x) {
      y.at<float>(r, x) = image.y(x, r);
      u.at<float>(r, x) = image.u(x, r) - 128.f;
      v.at<float>(r, x) = image.v(x, r) - 128.f;
    }
  // A little smoothing: in deep shadow the chroma is a few units, comparable to the noise.
  for (cv::Mat* m : {&y, &u, &v}) cv::blur(*m, *m, cv::Size(3, 3));
  cv::Mat out(image.height, image.width, CV_32F);
  for (int r = 0; r < image.height; ++r)
    for (int x = 0; x < image.width; ++x) {
      // BT.601 full range back to RGB; only differences matter, so Y cancels.
      const float uu = u.at<float>(r, x), vv = v.at<float>(r, x);
      const float red = 1.402f * vv, green = -0.344f * uu - 0.714f * vv, blue = 1.772f * uu;
      out.at<float>(r, x) = (green - std::max(red, blue)) / std::max(y.at<float>(r, x), 10.f);
    }
  return out;
}

cv::Mat grayFromYuyv(const CameraImage& image) {
  cv::Mat gray(image.height, image.width, CV_8U);
  for (int y = 0; y < image.height; ++y) {
    std::uint8_t* row = gray.ptr<std::uint8_t>(y);
    const std::uint8_t* src = image.yuyv.data() + static_cast<std::size_t>(y) * image.width * 2;
    for (int x = 0; x < image.width; ++x) row[x] = src[2 * x];
  }
  return gray;
}

namespace {

// Steps 1-4 with the coarse camera matrix (for the horizon and the plausibility checks) and the
// capture data every sample of this image carries.
ExtractionResult extract(const CameraImage& image, const CameraMatrix& coarse, const CalibrationSample& proto,
                         const CameraCalibration& current, const ExtractionOptions& o,
                         const std::vector<LinesPercept::Line>* visionLines) {
  ExtractionResult out;
  const cv::Mat gray = grayFromYuyv(image);

  GradientImage gradients = GradientImage::sobel(gray);
  gradients.greenness = greenness(image);
  // What each source tried, for the second pass.
  struct Attempt {
    const char* source;
    std::vector<ImageSegment> segments;
    std::vector<GoalBoxSideDetection> candidates;
  };
  std::vector<Attempt> attempts;
  // Measures an attempt's candidates, best first, until one gives a sample; without one the
  // reason kept is the first candidate's of the first source.
  auto measureCandidates = [&](const Attempt& a, double longDepressionDeg) {
    for (std::size_t c = 0; c < a.candidates.size() && c < static_cast<std::size_t>(o.maxCandidates); ++c) {
      std::string reason;
      auto sample = measure(a.candidates[c], gradients, coarse, proto, current, o, longDepressionDeg, reason);
      if (sample) {
        out.segments = a.segments;
        out.detection = a.candidates[c];
        out.sample = sample;
        out.source = a.source;
        out.reason.clear();
        return true;
      }
      if (c == 0 && (out.reason.empty() || out.reason.rfind("goal box not found", 0) == 0)) {
        out.segments = a.segments;
        out.detection = a.candidates[c];
        out.reason = reason;
      }
    }
    return false;
  };
  auto tryCandidates = [&](const char* source, const std::vector<ImageSegment>& segments,
                           std::vector<GoalBoxSideDetection> candidates) {
    for (auto& c : findGoalBoxSideCandidates(segments, image.width, image.height, o.finder)) candidates.push_back(c);
    if (candidates.empty() && out.reason.empty()) {
      out.reason = "goal box not found: no short line joining two long lines";
      out.segments = segments;
    }
    attempts.push_back({source, segments, std::move(candidates)});
    return measureCandidates(attempts.back(), o.minDepressionDeg);
  };

  // 1, 2: segments and the goal box side, image-only. The vision pipeline's lines (and its
  // goal box finder) first, when asked for; OpenCV's LSD if they give no sample; for
  // LsdThenVision LSD first, then the vision's lines, then both.
  const bool lsdFirst = o.source == LineSource::LsdThenVision;
  std::optional<std::vector<ImageSegment>> lsd;
  if (lsdFirst) {
    lsd = paintLineSegments(gray, coarse.horizon(), o.segments);
    if (tryCandidates("lsd", *lsd, {})) return out;
  }
  std::vector<ImageSegment> visionSegments;
  if (visionLines || o.source != LineSource::Lsd) {
    VisionGeometry geometry;
    geometry.lineWidth = o.lineWidth;
    const std::vector<LinesPercept::Line> lines = visionLines ? *visionLines : runVision(image, coarse, geometry).lines.lines;
    const std::vector<ImageSegment> segments = segmentsFromLinesPercept(lines, coarse, o.lineWidth);
    visionSegments = segments;
    std::vector<GoalBoxSideDetection> theirs;
    if (const auto gb = detectGoalBoxSide(lines, image.width, image.height); gb.found) {
      GoalBoxSideDetection d;
      d.shortLine = segments[gb.shortLine];
      d.longLine1 = segments[gb.longLine1];
      d.longLine2 = segments[gb.longLine2];
      const auto j1 = intersectLines(d.shortLine, d.longLine1), j2 = intersectLines(d.shortLine, d.longLine2);
      if (j1 && j2) {
        d.found = true;
        d.junction1 = *j1;
        d.junction2 = *j2;
        theirs.push_back(d);
      }
    }
    if (tryCandidates("vision", segments, theirs)) return out;
  }
  if (!lsd) {
    lsd = paintLineSegments(gray, coarse.horizon(), o.segments);
    if (tryCandidates("lsd", *lsd, {})) return out;
  }
  if (lsdFirst && !visionSegments.empty()) {
    std::vector<ImageSegment> both = visionSegments;
    both.insert(both.end(), lsd->begin(), lsd->end());
    if (tryCandidates("vision+lsd", both, {})) return out;
  }
  // No sample: the same candidates, in the same order, with the long lines allowed nearer the
  // horizon. Last, so that every first-pass sample stays as it was. The reason kept is the
  // first pass's.
  const ExtractionResult refusedFirst = out;
  if (o.longLinesFallbackDepressionDeg < o.minDepressionDeg)
    for (const Attempt& a : attempts)
      if (measureCandidates(a, o.longLinesFallbackDepressionDeg)) return out;
  // Still none: the vision's own lines as the measurement, where their edges could not be
  // measured (a short line 3-5 m away, too little of it clear of the junctions) or their
  // junction is flatter than the finder takes (the box seen along the goal line), or the vision
  // saw only a piece of the short line (a validated line all the same). The vision's
  // lines are sub-pixel centre lines (LineDetector's refinement); the checks are those above.
  if (o.visionCentreLines && !visionSegments.empty()) {
    FinderOptions flat = o.finder;
    flat.minAngleDeg = std::min(flat.minAngleDeg, o.visionCentreMinAngleDeg);
    flat.minShortLengthPx = std::min(flat.minShortLengthPx, o.visionCentreMinShortPx);
    std::vector<GoalBoxSideDetection> candidates = findGoalBoxSideCandidates(visionSegments, image.width, image.height, flat);
    for (std::size_t c = 0; c < candidates.size() && c < static_cast<std::size_t>(o.maxCandidates); ++c) {
      const GoalBoxSideDetection& d = candidates[c];
      // The box's short side spans its junctions, however little of it the vision saw.
      if ((d.junction1 - d.junction2).norm() < o.finder.minShortLengthPx) continue;
      CalibrationSample sample = proto;
      const ImageSegment* segs[3] = {&d.shortLine, &d.longLine1, &d.longLine2};
      std::string reason;
      bool ok = true;
      for (int l = 0; l < 3 && ok; ++l) {
        const auto m = edgesAroundCentre(*segs[l], coarse, o.lineWidth);
        ok = m.has_value();
        if (ok) sample.lines[l] = *m;
        ok = ok && keepBelowHorizon(sample.lines[l], l, coarse, o, o.longLinesFallbackDepressionDeg, reason);
      }
      if (ok && plausible(sample, current, o, reason)) {
        out.segments = visionSegments;
        out.detection = d;
        out.sample = sample;
        out.source = "vision centre lines";
        out.reason.clear();
        return out;
      }
    }
  }
  return refusedFirst;
}

ExtractionResult refused(std::string reason) {
  ExtractionResult out;
  out.reason = std::move(reason);
  return out;
}

}  // namespace

ExtractionResult extractSample(const CameraImage& image, const JointArray& joints, const Eigen::Vector2d& imuAngle,
                               const CameraIntrinsics& intrinsicsIn, const CameraCalibration& current,
                               const ExtractionOptions& o, const std::vector<LinesPercept::Line>* visionLines) {
  if (!image.valid()) return refused("invalid image");
  CalibrationSample proto;
  proto.camera = image.camera;
  proto.intrinsics = intrinsicsIn;
  if (proto.intrinsics.width != image.width || proto.intrinsics.height != image.height)
    proto.intrinsics = CameraIntrinsics::fromFovY(image.width, image.height, intrinsicsIn.fovY());
  proto.joints = joints;
  proto.imuAngle = imuAngle;
  const CameraMatrix coarse = computeCameraMatrix(joints, imuAngle, image.camera, current, proto.intrinsics);
  return extract(image, coarse, proto, current, o, visionLines);
}

ExtractionResult extractSample(const CameraImage& image, const CameraMatrix& recorded, const ExtractionOptions& o,
                               const std::vector<LinesPercept::Line>* visionLines) {
  if (!image.valid()) return refused("invalid image");
  if (recorded.intrinsics.width != image.width || recorded.intrinsics.height != image.height)
    return refused("the camera matrix is for another image size");
  CalibrationSample proto;
  proto.camera = image.camera;
  proto.intrinsics = recorded.intrinsics;
  proto.cameraPose = recorded.pose;
  return extract(image, recorded, proto, CameraCalibration{}, o, visionLines);
}

}  // namespace nao::calibration
