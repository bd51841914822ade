#pragma once
// Cognition, the fast percept mode (--percepts oracle): the current image's percepts from what
// the simulator says the camera truly shows (CameraImage::oracle, robot/OracleView.h) instead of
// from pixels, with the errors the real vision makes: detection rates by distance, pixel noise,
// false balls and lines per image. The pixels are projected with the robot's own camera matrix
// at exposure, as the vision projects them, so a wrong calibration misleads both alike. The
// error model is fitted from `eval perception` (its --fit-oracle writes
// config/parameters/OracleVision.json; the file names the command). Selected in place of
// CameraVision (providers: CameraPercepts); on a NAO there is no oracle and nothing is seen.
#include <random>
#include <string>
#include <vector>

#include "representations/infrastructure/CurrentImage.h"
#include "representations/perception/CameraPercepts.h"
#include "representations/perception/ImageCameraMatrix.h"
#include "robot/Module.h"
#include "robot/OracleView.h"
#include "robot/Parameters.h"

namespace nao::modules {

class OracleVision
    : public Module<OracleVision, Requires<CurrentImage, ImageCameraMatrix>, Provides<CameraPercepts>, Cadence::Cognition> {
 public:
  struct Params {
    std::string fittedBy;  // the command whose figures these are
    // Upper edges (m, ground distance from the camera) of the distance bins of every table
    // below; beyond the last edge nothing is detected.
    std::vector<double> distanceBins{1, 2, 3, 4, 5, 6};
    struct Ball {
      std::vector<double> detection{0.99, 0.99, 0.99, 0.98, 0.95, 0.8};  // per bin
      double minInImage = 0.75;      // share of the disc in the image to be detected at all
      double sigmaPerRadius = 0.08;  // centre noise per axis, px per px of the ball's radius
      double minSigmaPx = 0.5;
      double falsePerImage = 0.001;
    } ball;
    struct Lines {
      std::vector<double> detection{0.98, 0.97, 0.96, 0.93, 0.8, 0.5};       // stretches >= longLength
      std::vector<double> detectionShort{0.8, 0.7, 0.5, 0.3, 0.1, 0.0};      // minLength .. longLength
      double minLength = 0.2, longLength = 0.5;  // m of the visible stretch
      double sigmaPx = 1.0;                      // each end, across the line
      double falsePerImage = 0.02;
    } lines;
    struct Spot {
      std::vector<double> detection{0.9, 0.9, 0.8, 0.0, 0.0, 0.0};  // per bin of the spot's distance
      double sigma = 0.05;                                          // m per axis on the ground
      double falsePerImage = 0.0;
    } circle, penaltyMark;
  };

  explicit OracleVision(const ModuleContext& context = {});

  // One image's percepts from its oracle view: the module's work, also what `eval perception
  // --percepts oracle` scores against the vision's figures.
  // circleRadius: the field's centre circle (m, to the line's centre).
  static CameraPercepts perceive(const OracleView& view, const CameraMatrix& cm, const Params& params,
                                 double circleRadius, std::mt19937_64& rng);
  // A parameter set whose tables do not match its bins: the reason (empty: fine).
  static std::string check(const Params& params);
  // The table entry for a distance (0 beyond the last bin).
  static double rate(const std::vector<double>& table, const std::vector<double>& bins, double distance);

 private:
  void update() override;

  Params params_;
  double circleRadius_ = 0.75;
  std::mt19937_64 rng_;
};

template <class V>
void describe(V& v, OracleVision::Params::Ball& p) {
  v("detection", p.detection, 0.0, 1.0);
  v("minInImage", p.minInImage, 0.0, 1.0);
  v("sigmaPerRadius", p.sigmaPerRadius, 0.0, 1.0);
  v("minSigmaPx", p.minSigmaPx, 0.0, 50.0);
  v("falsePerImage", p.falsePerImage, 0.0, 10.0);
}
template <class V>
void describe(V& v, OracleVision::Params::Lines& p) {
  v("detection", p.detection, 0.0, 1.0);
  v("detectionShort", p.detectionShort, 0.0, 1.0);
  v("minLength", p.minLength, 0.0, 5.0);
  v("longLength", p.longLength, 0.0, 5.0);
  v("sigmaPx", p.sigmaPx, 0.0, 50.0);
  v("falsePerImage", p.falsePerImage, 0.0, 10.0);
}
template <class V>
void describe(V& v, OracleVision::Params::Spot& p) {
  v("detection", p.detection, 0.0, 1.0);
  v("sigma", p.sigma, 0.0, 2.0);
  v("falsePerImage", p.falsePerImage, 0.0, 10.0);
}
template <class V>
void describe(V& v, OracleVision::Params& p) {
  v("fittedBy", p.fittedBy);
  v("distanceBins", p.distanceBins, 0.0, 20.0);
  v("ball", p.ball);
  v("lines", p.lines);
  v("circle", p.circle);
  v("penaltyMark", p.penaltyMark);
}

}  // namespace nao::modules
