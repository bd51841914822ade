#pragma once
// Real NAO camera images (HULKs dataset, CC BY 4.0; ../shared/data/real-nao-images/) with
// their segmentation masks, each run once through the vision with the very same parameters
// as in simulation; shared by real_images_test (lines, field colour) and
// real_images_ball_test (balls).
//
// The photos come without the robot's joint angles. The camera is taken to be a standing
// NAO's top camera, pitched so that the masked ball (the largest one, if any) has its true
// size at its place: what the robot would know from its head joints. Without a ball, the
// pitch at which the mask's lines have the width of field lines (pitchFromLines); without a
// mask 20 deg (the horizon above the image, as in these photos).
//
// NAO_VISION_DOCS=DIR writes the annotated images (docs/vision/real/ holds them).
#include <string>
#include <vector>

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "perception/CameraModel.h"
#include "perception/vision/VisionPipeline.h"
#include "robot/CameraImage.h"

namespace nao::test {

std::string realImagesDir();

struct MaskBall {
  Eigen::Vector2d centre;
  double radius;  // px, from the component's width (it may be cut by the image border)
  double across;  // px
};

struct Mask {
  cv::Mat field;  // CV_8U, 255 on field pixels
  cv::Mat line;   // CV_8U, 255 on line pixels
  cv::Mat ball;   // CV_8U, 255 on ball pixels (balls of any size)
  std::vector<MaskBall> balls;  // those at least 15 px across
};

Mask loadMask(const std::string& path);

// A standing NAO's top camera with this head pitch, intrinsics for this image size.
CameraMatrix photoCamera(double headPitchDeg, int width, int height);

// One image: its mask, the estimated camera and what the vision made of it.
struct Evaluated {
  std::string stem;  // NNNNN
  bool masked = false;
  CameraImage image;
  Mask mask;
  double pitch = 20;  // deg, estimated
  CameraMatrix cm;
  VisionResult result;
};

// Every real image through the vision once (empty when the directory is missing).
const std::vector<Evaluated>& evaluatedRealImages();

}  // namespace nao::test
