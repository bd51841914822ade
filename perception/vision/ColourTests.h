#pragma once
// Pixel-level colour tests shared by the line, circle, penalty mark and ball detectors. Every
// threshold is relative to the field colour that the scan-line regions found in this image
// (B-Human 2021, section 5.2): no colour table, no per-venue values.
#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "perception/vision/VisionTypes.h"

namespace nao::vision {

// A pixel's colour (luminance, U, V; pixel centres at i + 0.5).
struct PixelColour {
  double y = 0, u = 128, v = 128;
  double sat() const { return std::hypot(u - 128, v - 128); }
};

inline bool insideImage(const CameraImage& img, double x, double y, double margin = 0) {
  return x >= margin && y >= margin && x < img.width - margin && y < img.height - margin;
}

// Bilinear interpolation between the four pixel centres around (x, y): a sample placed on a
// one-pixel line's centre reads that pixel, one between pixels averages them.
inline PixelColour sampleColour(const CameraImage& img, double x, double y) {
  const double fx = std::clamp(x - 0.5, 0.0, img.width - 1.001), fy = std::clamp(y - 0.5, 0.0, img.height - 1.001);
  const int x0 = std::min(static_cast<int>(fx), img.width - 2), y0 = std::min(static_cast<int>(fy), img.height - 2);
  const double ax = fx - x0, ay = fy - y0;
  const double w00 = (1 - ax) * (1 - ay), w10 = ax * (1 - ay), w01 = (1 - ax) * ay, w11 = ax * ay;
  PixelColour c;
  c.y = w00 * img.y(x0, y0) + w10 * img.y(x0 + 1, y0) + w01 * img.y(x0, y0 + 1) + w11 * img.y(x0 + 1, y0 + 1);
  c.u = w00 * img.u(x0, y0) + w10 * img.u(x0 + 1, y0) + w01 * img.u(x0, y0 + 1) + w11 * img.u(x0 + 1, y0 + 1);
  c.v = w00 * img.v(x0, y0) + w10 * img.v(x0 + 1, y0) + w01 * img.v(x0, y0 + 1) + w11 * img.v(x0 + 1, y0 + 1);
  return c;
}

// The luminance alone, bilinear like sampleColour.
inline double sampleLuminance(const CameraImage& img, double x, double y) {
  const double fx = std::clamp(x - 0.5, 0.0, img.width - 1.001), fy = std::clamp(y - 0.5, 0.0, img.height - 1.001);
  const int x0 = std::min(static_cast<int>(fx), img.width - 2), y0 = std::min(static_cast<int>(fy), img.height - 2);
  const double ax = fx - x0, ay = fy - y0;
  return (1 - ay) * ((1 - ax) * img.y(x0, y0) + ax * img.y(x0 + 1, y0)) +
         ay * ((1 - ax) * img.y(x0, y0 + 1) + ax * img.y(x0 + 1, y0 + 1));
}

// The field colour of this image in the units the tests need (hue in radians of
// atan2(v - 128, u - 128), chroma = |(u - 128, v - 128)|), and this image's white point: the
// chroma per unit luminance of the brightest non-field things (lines, ball, robots). The
// simulated camera, like a NAO's without a settled white balance, renders white orange in
// warm light; saturation is measured from that white point, so "less saturated" keeps its
// meaning under any colour temperature.
struct FieldReference {
  bool valid = false;
  double hueMin = 0, hueMax = 0;  // hueMin <= hueMax (may exceed pi)
  double satMin = 0;              // chroma
  double yMin = 0, yMax = 255;
  double fieldY = 0;              // median luminance of the field
  double whiteU = 0, whiteV = 0;  // chroma of white per unit luminance
  double fieldRelSatPerY = 0;     // the field's chroma from the white point, per unit luminance

  static FieldReference from(const ScanLineRegions& regions);
  // Hue in the field range (with `slack` radians) and saturated enough to be the carpet.
  bool isField(const PixelColour& c, double slack = 0.08) const {
    if (!valid) return false;
    const double s = c.sat();
    if (s < 0.6 * satMin || s < 2) return false;
    double h = std::atan2(c.v - 128, c.u - 128);
    const double mid = 0.5 * (hueMin + hueMax);
    h = mid + std::remainder(h - mid, 2 * M_PI);
    return h >= hueMin - slack && h <= hueMax + slack;
  }
  // Chroma measured from the white point at this luminance.
  double relSat(double y, double u, double v) const { return std::hypot(u - 128 - whiteU * y, v - 128 - whiteV * y); }
  double relSat(const PixelColour& c) const { return relSat(c.y, c.u, c.v); }
  // A region that is white by this image's standards: brighter than the field and much
  // closer to the white point than the field is.
  bool isWhiteRegion(const ScanRegion& r) const {
    if (r.cls == RegionClass::White) return true;
    if (r.cls != RegionClass::Other || !valid || r.colour.y <= yMax) return false;
    return relSat(r.colour.y, r.u, r.v) < 0.5 * fieldRelSatPerY * r.colour.y;
  }
};

// YHS2 hue (0..255 per full turn of atan2(v - 128, u - 128)) -> radians.
inline double hueToRadians(double h255) { return h255 / 256.0 * 2 * M_PI; }

inline FieldReference FieldReference::from(const ScanLineRegions& regions) {
  const FieldColour& fc = regions.fieldColour;
  FieldReference r;
  r.valid = fc.valid;
  r.hueMin = hueToRadians(fc.hueMin);
  r.hueMax = hueToRadians(fc.hueMax);
  if (r.hueMax < r.hueMin) r.hueMax += 2 * M_PI;  // the range wraps
  r.satMin = fc.satMin / 2.0;                     // YHS2 saturation is twice the chroma
  r.yMin = fc.yMin;
  r.yMax = fc.yMax;
  r.fieldY = fc.fieldY > 0 ? fc.fieldY : 0.5 * (fc.yMin + fc.yMax);
  // White point: length-weighted medians of (u - 128) / y and (v - 128) / y over the
  // non-field regions in the upper half of the luminance range between the field and the
  // brightest (the cores of lines and the ball; region ends blend with the field).
  double brightest = 0;
  for (const ScanLine& sl : regions.vertical)
    for (const ScanRegion& reg : sl.regions)
      if (reg.cls != RegionClass::Field) brightest = std::max<double>(brightest, reg.colour.y);
  const double least = std::max<double>(fc.yMax, 0.5 * (fc.yMax + brightest));
  std::vector<std::pair<double, double>> us, vs;
  double total = 0;
  for (const ScanLine& sl : regions.vertical)
    for (const ScanRegion& reg : sl.regions) {
      if (reg.cls == RegionClass::Field || reg.colour.y < least || reg.colour.y < 8) continue;
      const double w = reg.to - reg.from;
      us.emplace_back((reg.u - 128.0) / reg.colour.y, w);
      vs.emplace_back((reg.v - 128.0) / reg.colour.y, w);
      total += w;
    }
  auto weightedMedian = [&](std::vector<std::pair<double, double>>& xs) {
    std::sort(xs.begin(), xs.end());
    double acc = 0;
    for (const auto& [x, w] : xs)
      if ((acc += w) >= total / 2) return x;
    return 0.0;
  };
  if (total >= 12) {
    r.whiteU = weightedMedian(us);
    r.whiteV = weightedMedian(vs);
    const double m = std::hypot(r.whiteU, r.whiteV);
    if (m > 0.5) r.whiteU *= 0.5 / m, r.whiteV *= 0.5 / m;
  }
  const double fieldChroma = fc.fieldS / 2.0, fieldHue = hueToRadians(fc.fieldHue);
  r.fieldRelSatPerY = r.relSat(r.fieldY, 128 + fieldChroma * std::cos(fieldHue), 128 + fieldChroma * std::sin(fieldHue)) /
                      std::max(1.0, r.fieldY);
  return r;
}

// A comparison point on other paint (a crossing line, the circle) says nothing about the
// sample: the pair is left out rather than failed.
inline bool uninformative(const PixelColour& comparison, const FieldReference& field) {
  return comparison.y > field.yMax && !field.isField(comparison, 0.15);
}

// The paper's white test of one sample point against one comparison point beside it: the
// sample is clearly brighter (by at least minContrast) and less saturated than the comparison
// point, bright and grey enough in itself, and the comparison point is field.
inline bool whitePair(const PixelColour& sample, const PixelColour& comparison, const FieldReference& field,
                      double minContrast) {
  if (sample.y - comparison.y < minContrast) return false;
  // Saturation per unit luminance (YHS2's saturation is relative to brightness too): a line in
  // a shadow lit by the blue sky has more chroma than the dark grass beside it, but far less
  // for its luminance.
  if (field.relSat(sample) / std::max(1.0, sample.y) >= field.relSat(comparison) / std::max(1.0, comparison.y))
    return false;
  if (sample.y < field.yMin) return false;
  if (!field.isField(comparison, 0.15)) return false;
  // Sunlit grass beside a shadow is brighter, and no greyer for its luminance; it is still grass.
  if (field.isField(sample) && field.relSat(sample) > 0.5 * field.fieldRelSatPerY * sample.y) return false;
  return true;
}

// The usual contrast: 18 % of the comparison point's luminance.
inline bool whitePair(const PixelColour& sample, const PixelColour& comparison, const FieldReference& field) {
  return whitePair(sample, comparison, field, std::max(6.0, 0.18 * comparison.y));
}

}  // namespace nao::vision
