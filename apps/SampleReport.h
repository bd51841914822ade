#pragma once
// What perceive and eval real say about one image's calibration sample, and how they draw it
// and an image's labelled lines (perception/RecordedCameraMatrix.h).
#include <vector>

#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>

#include "perception/RecordedCameraMatrix.h"
#include "perception/calibration/SampleExtraction.h"

namespace nao::cli {

// The camera of a recorded matrix file; a --camera given that contradicts it is refused.
CameraId recordedCamera(const RecordedCameraMatrix& recorded, const std::string& file, CameraId asked, bool askedGiven);
// Throws nao::Error(path, ...) unless the image is 640x480 or 320x240 (a NAO camera's sizes).
void requireNaoImageSize(const CameraImage& image, const std::string& path);
// The sample extraction's options as the robot program's calibrator runs it
// (config/parameters/Calibrator.json) on `field`.
calibration::ExtractionOptions robotExtractionOptions(const FieldDimensions& field);

// The image line (two points) each of a sample's three lines stands for: the midline of its
// two refined paint edges. Indexed by calibration::LineRole.
std::array<ImageLine, 3> sampleLines(const calibration::CalibrationSample& sample);

// calibration_sample: accepted, reason (when not), source (lsd or vision), lines (short, long1,
// long2: image midline and both edges, px), residuals on the ground with the sample's own
// camera matrix (right angles, parallel long lines in deg; depth in m against goalBoxDepth).
nlohmann::json calibrationSampleJson(const calibration::ExtractionResult& result, double goalBoxDepth);

// Draws the labelled lines (magenta, through the whole image, their two points as dots) and the
// sample's lines (short: red, long: orange) or, refused, the painted-line segments the finder
// worked on (light blue), its best candidate (grey) and the reason, on an RGB image scaled by `scale`.
void drawLabelledLines(cv::Mat& rgb, const std::vector<LabelledLine>& lines, int scale);
void drawSample(cv::Mat& rgb, const calibration::ExtractionResult& result, int scale);

}  // namespace nao::cli
