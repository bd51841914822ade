#pragma once
// Camera images in and out: RGB <-> YUYV (BT.601 full range, as the NAO's camera delivers),
// PNG writing and reading of PNG/JPEG or raw YUYV files for `perceive`.
#include <opencv2/core.hpp>
#include <string>

#include "robot/CameraImage.h"

namespace nao::sim {

// CV_8UC3 RGB (even width) -> CV_8UC2 YUYV: per pixel pair Y0 U Y1 V, U/V averaged over the pair.
cv::Mat yuyvFromRgb(const cv::Mat& rgb);
// CV_8UC2 YUYV -> CV_8UC3 RGB (each pixel uses its pair's U/V).
cv::Mat rgbFromYuyv(const cv::Mat& yuyv);

CameraImage cameraImageFromRgb(const cv::Mat& rgb, CameraId camera = CameraId::Top, double timestamp = 0);
cv::Mat rgbFromCameraImage(const CameraImage& image);  // CV_8UC3, RGB order

// Writes the image as an RGB PNG. Throws nao::Error(path, ...) on an invalid image or a write failure.
void writePng(const std::string& path, const CameraImage& image);
void writePng(const std::string& path, const cv::Mat& rgb);  // CV_8UC3 in RGB order

// Reads a PNG/JPEG (any colour depth; an odd width loses its last column) or a raw YUYV file
// (extension .yuv, .yuyv or .raw) of width x height; for raw files a size of 0 x 0 means
// "infer from the file size" among 1280x960, 640x480 and 320x240. Throws nao::Error(path, ...)
// on a missing, truncated or corrupt file.
CameraImage readImage(const std::string& path, int width = 0, int height = 0, CameraId camera = CameraId::Top);

}  // namespace nao::sim
