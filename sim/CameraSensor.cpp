#include "sim/CameraSensor.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>

#include <nlohmann/json.hpp>
#include <opencv2/imgproc.hpp>

#include "robot/Error.h"
#include "robot/InputFiles.h"
#include "sim/Lighting.h"

namespace nao::sim {

namespace {

// 65536 standard normal values (Box-Muller on a fixed seed): the per-pixel noise looks them up
// with 16 random bits, four draws per 64-bit number.
const std::array<float, 65536>& gaussTable() {
  static const std::array<float, 65536> table = [] {
    std::array<float, 65536> t{};
    std::mt19937_64 g(0x6e616f);
    auto uniform = [&g] { return (static_cast<double>(g() >> 11) + 0.5) * 0x1.0p-53; };
    for (std::size_t i = 0; i < t.size(); i += 2) {
      const double r = std::sqrt(-2 * std::log(uniform())), a = 2 * std::numbers::pi * uniform();
      t[i] = static_cast<float>(r * std::cos(a));
      t[i + 1] = static_cast<float>(r * std::sin(a));
    }
    return t;
  }();
  return table;
}

// xorshift64*: fast, seeded from the caller's rng once per image.
struct FastRng {
  std::uint64_t s;
  std::uint64_t next() {
    s ^= s >> 12;
    s ^= s << 25;
    s ^= s >> 27;
    return s * 0x2545F4914F6CDD1DULL;
  }
};

// How far a colour's tint G / sqrt(R B) lies from that of a black body with the same R / B
// (the light's colours of sim/Lighting, 2200-12000 K; below 2200 K its fit loses the blue;
// bluer than 12000 K: that of 12000 K); infinite outside R / B 0.4-6. Grey surfaces under any
// such light lie on the curve; a greenish grey (carpet showing through worn paint, a line's
// edge blurred into the carpet, a sheen on the carpet) lies above it and must not steer the
// white balance, or the whites turn magenta.
float offBlackBody(float r, float g, float b) {
  struct Point {
    float logRb, tint;
  };
  static const std::vector<Point> locus = [] {
    std::vector<Point> l;
    for (double t = 12000; t >= 2200; t -= 100) {
      Lighting light;
      light.temperature = t;
      const Eigen::Vector3d c = light.colour();
      l.push_back({static_cast<float>(std::log(c.x() / c.z())), static_cast<float>(c.y() / std::sqrt(c.x() * c.z()))});
    }
    return l;
  }();
  const float rb = r / b, x = std::log(rb), tint = g / std::sqrt(r * b);
  if (!(rb > 0.4f && rb < 6.0f)) return std::numeric_limits<float>::infinity();
  if (x <= locus.front().logRb) return std::abs(tint - locus.front().tint);
  const auto hi = std::lower_bound(locus.begin(), locus.end(), x, [](const Point& p, float v) { return p.logRb < v; });
  const auto lo = hi - 1;
  return std::abs(tint - (lo->tint + (hi->tint - lo->tint) * (x - lo->logRb) / (hi->logRb - lo->logRb)));
}

constexpr float kAwbTintTolerance = 0.1f;  // a grey's tint off the black-body curve

inline float clamp255(float v) { return v < 0 ? 0 : (v > 255 ? 255 : v); }
inline std::uint8_t toByte(float v) { return static_cast<std::uint8_t>(clamp255(v) + 0.5f); }

}  // namespace

CameraSensorParams CameraSensorParams::load(const std::string& file) {
  using nlohmann::json;
  json root;
  try {
    root = json::parse(readInputFile(file));
  } catch (const json::exception& e) {
    std::string reason = e.what();
    std::replace(reason.begin(), reason.end(), '\n', ' ');
    throw Error(file, "invalid JSON: " + reason);
  }
  if (!root.is_object()) throw Error(file, "top level: must be an object");
  CameraSensorParams p;
  struct Number {
    const char* key;
    double* value;
    double lo, hi;
  };
  const std::array<Number, 14> numbers{{{"target_luma", &p.targetLuma, 10, 245},
                                        {"nominal_exposure_ms", &p.nominalExposureMs, 0.1, 100},
                                        {"min_exposure_ms", &p.minExposureMs, 0.01, 100},
                                        {"max_exposure_ms", &p.maxExposureMs, 0.1, 100},
                                        {"max_gain", &p.maxGain, 1, 32},
                                        {"ae_rate", &p.aeRate, 0.01, 1},
                                        {"awb_rate", &p.awbRate, 0.01, 1},
                                        {"awb_max_gain", &p.awbMaxGain, 1, 8},
                                        {"vignetting_top", &p.vignettingTop, 0.1, 1},
                                        {"vignetting_bottom", &p.vignettingBottom, 0.1, 1},
                                        {"defocus_sigma_px", &p.defocusSigmaPx, 0, 5},
                                        {"readout_ms", &p.readoutMs, 0, 100},
                                        {"shot_noise", &p.shotNoise, 0, 5},
                                        {"latency_images", nullptr, 0, 10}}};
  struct Switch {
    const char* key;
    bool* value;
  };
  const std::array<Switch, 6> switches{{{"enabled", &p.enabled},
                                        {"auto_exposure", &p.autoExposure},
                                        {"auto_white_balance", &p.autoWhiteBalance},
                                        {"vignetting", &p.vignetting},
                                        {"defocus", &p.defocus},
                                        {"motion", &p.motion}}};
  for (const auto& [key, value] : root.items()) {
    if (!key.empty() && key[0] == '_') continue;  // comments
    auto n = std::find_if(numbers.begin(), numbers.end(), [&k = key](const Number& x) { return k == x.key; });
    if (n != numbers.end()) {
      if (!value.is_number()) throw Error(file, key + ": must be a number");
      const double v = value.get<double>();
      if (!std::isfinite(v) || v < n->lo || v > n->hi)
        throw Error(file, key + ": must be in [" + json(n->lo).dump() + ", " + json(n->hi).dump() + "], got " +
                              value.dump());
      if (n->value) {
        *n->value = v;
      } else {
        if (v != std::floor(v)) throw Error(file, key + ": must be a whole number, got " + value.dump());
        p.latencyImages = static_cast<int>(v);
      }
      continue;
    }
    auto s = std::find_if(switches.begin(), switches.end(), [&k = key](const Switch& x) { return k == x.key; });
    if (s != switches.end()) {
      if (!value.is_boolean()) throw Error(file, key + ": must be true or false");
      *s->value = value.get<bool>();
      continue;
    }
    throw Error(file, key + ": unknown key");
  }
  if (p.minExposureMs > p.maxExposureMs)
    throw Error(file, "min_exposure_ms: must not exceed max_exposure_ms");
  return p;
}

const std::vector<float>& CameraSensor::vignetteMap(int width, int height, double corner) {
  if (width == vignetteWidth_ && height == vignetteHeight_ && corner == vignetteCorner_) return vignette_;
  vignette_.resize(static_cast<std::size_t>(width) * height);
  const double cx = (width - 1) / 2.0, cy = (height - 1) / 2.0, r2max = cx * cx + cy * cy;
  for (int r = 0; r < height; ++r)
    for (int c = 0; c < width; ++c) {
      // cos^4-like fall-off, fitted by its corner value: 1 at the centre, `corner` at a corner.
      const double rho2 = ((c - cx) * (c - cx) + (r - cy) * (r - cy)) / r2max;
      vignette_[static_cast<std::size_t>(r) * width + c] = static_cast<float>(1 - (1 - corner) * rho2);
    }
  vignetteWidth_ = width;
  vignetteHeight_ = height;
  vignetteCorner_ = corner;
  return vignette_;
}

CameraSensor::Metering CameraSensor::meter(const cv::Mat& rgb, const Eigen::Vector3d& renderedGains,
                                         const Eigen::Vector3d& gains) const {
  // Every 4th pixel of every 4th row: the image as it comes out at `gains` (clipped, vignetted)
  // for the exposure, and the bright, nearly grey pixels of the scene for the white balance.
  // "Nearly grey": near the tint of a black body of the same R / B (offBlackBody: G / sqrt(R B)
  // from 1.0 at 6500 K to 1.33 at 2300 K); the carpet (about 2.6) and greenish greys are out.
  Metering m;
  m.brightness = gains[1];
  const Eigen::Vector3f scale = gains.cwiseQuotient(renderedGains).cast<float>();
  const Eigen::Vector3f toScene = renderedGains.cwiseInverse().cast<float>();
  double sumY = 0, sumScene = 0;
  int n = 0, clipped = 0;
  // The metered luminance per cell of the exposure weights' grid (robot/ExposureWeights.h).
  std::array<double, ExposureWeights::kRows * ExposureWeights::kCols> cellY{};
  std::array<int, ExposureWeights::kRows * ExposureWeights::kCols> cellN{};
  struct Candidate {
    float r, g, b, y;
  };
  std::vector<Candidate> candidates;
  for (int r = 2; r < rgb.rows; r += 4) {
    const std::uint8_t* row = rgb.ptr<std::uint8_t>(r);
    const float* vig = vignette_.data() + static_cast<std::size_t>(r) * rgb.cols;
    const int cellRow = r * ExposureWeights::kRows / rgb.rows * ExposureWeights::kCols;
    for (int c = 2; c < rgb.cols; c += 4) {
      const std::uint8_t* px = row + 3 * c;
      const float v = vig[c];
      const float yOut = 0.299f * clamp255(px[0] * scale[0]) * v + 0.587f * clamp255(px[1] * scale[1]) * v +
                         0.114f * clamp255(px[2] * scale[2]) * v;
      sumY += yOut;
      ++n;
      const int cell = cellRow + c * ExposureWeights::kCols / rgb.cols;
      cellY[static_cast<std::size_t>(cell)] += yOut;
      ++cellN[static_cast<std::size_t>(cell)];
      const float R = px[0] * toScene[0], G = px[1] * toScene[1], B = px[2] * toScene[2];
      const float y = 0.299f * R + 0.587f * G + 0.114f * B;
      sumScene += y;
      if (px[0] >= 250 || px[1] >= 250 || px[2] >= 250) {
        ++clipped;
        continue;
      }
      if (px[0] > 8 && px[2] > 4) {
        if (offBlackBody(R, G, B) < kAwbTintTolerance) candidates.push_back({R, G, B, y});
      }
    }
  }
  if (n == 0) return m;
  m.luma = sumY / n;
  if (!weights_.uniform()) {  // the cells' mean luminances, weighted
    double weighted = 0, weightSum = 0;
    for (std::size_t k = 0; k < cellY.size(); ++k)
      if (cellN[k] > 0) {
        weighted += weights_.cell[k] * cellY[k] / cellN[k];
        weightSum += weights_.cell[k];
      }
    if (weightSum > 0) m.luma = weighted / weightSum;
  }
  m.clipped = static_cast<double>(clipped) / n;
  const double meanScene = sumScene / n;
  Eigen::Vector3d white = Eigen::Vector3d::Zero();
  for (const Candidate& k : candidates)
    if (k.y >= 1.2 * meanScene) {
      white += Eigen::Vector3d(k.r, k.g, k.b);
      ++m.whiteCount;
    }
  if (m.whiteCount > 0) m.white = white / m.whiteCount;
  return m;
}

double CameraSensor::brightness(const CameraSensorParams& p) const {
  return state_.exposureMs / p.nominalExposureMs * state_.gain;
}

void CameraSensor::setBrightness(double b, const CameraSensorParams& p) {
  if (!p.autoExposure) {
    state_.exposureMs = p.nominalExposureMs;
    state_.gain = 1;
    return;
  }
  const double wanted = b * p.nominalExposureMs;  // exposure x gain, ms
  state_.exposureMs = std::clamp(wanted, p.minExposureMs, p.maxExposureMs);
  state_.gain = std::clamp(wanted / state_.exposureMs, 1.0, p.maxGain);
}

void CameraSensor::update(const Metering& m, const CameraSensorParams& p, double aeRate, double awbRate) {
  if (p.autoExposure && m.luma > 0) {
    const double now = brightness(p), wanted = m.brightness * p.targetLuma / std::max(m.luma, 1.0);
    setBrightness(std::exp(std::log(now) + aeRate * (std::log(wanted) - std::log(now))), p);
  }
  if (p.autoWhiteBalance && m.whiteCount >= 8) {
    const double lo = 1 / p.awbMaxGain, hi = p.awbMaxGain;
    const Eigen::Vector3d wanted(std::clamp(m.white[1] / m.white[0], lo, hi), 1.0,
                                 std::clamp(m.white[1] / m.white[2], lo, hi));
    for (int k = 0; k < 3; ++k)
      state_.whiteBalance[k] =
          std::exp(std::log(state_.whiteBalance[k]) + awbRate * (std::log(wanted[k]) - std::log(state_.whiteBalance[k])));
  }
}

bool CameraSensor::needsSettling(const CameraSensorParams& p) const {
  return p.enabled && (p.autoExposure || p.autoWhiteBalance) && !settled_;
}

Eigen::Vector3d CameraSensor::lightGains(const CameraSensorParams& p) const {
  if (!p.enabled) return Eigen::Vector3d::Ones();
  const Eigen::Vector3d wb = p.autoWhiteBalance ? state_.whiteBalance : Eigen::Vector3d::Ones();
  return (p.autoExposure ? brightness(p) : 1.0) * wb;
}

bool CameraSensor::settle(const cv::Mat& rgb, const Eigen::Vector3d& renderedGains, const CameraSensorParams& p,
                         CameraId camera) {
  vignetteMap(rgb.cols, rgb.rows, p.vignetting ? (camera == CameraId::Top ? p.vignettingTop : p.vignettingBottom) : 1.0);
  if (renderedGains == Eigen::Vector3d::Ones()) {
    setBrightness(1, p);
    state_.whiteBalance = Eigen::Vector3d::Ones();
  }
  const Metering first = meter(rgb, renderedGains, renderedGains);
  for (int i = 0; i < 8; ++i) update(i == 0 ? first : meter(rgb, renderedGains, lightGains(p)), p, 1.0, 1.0);
  settled_ = true;
  pending_.clear();
  // Settled on clipped or nearly black pixels: the settled gains differ much from the rendered.
  const double ratio = lightGains(p)[1] / renderedGains[1];
  return (first.clipped > 0.01 && ratio < 0.9) || (first.luma < 25 && ratio > 2);
}

CameraImage CameraSensor::process(const cv::Mat& rgbIn, const CameraSensorParams& p, double readNoise,
                                 const Eigen::Vector2d& imageVelocity, CameraId camera, double timestamp,
                                 std::mt19937_64& rng) {
  const int w = rgbIn.cols, h = rgbIn.rows;
  if (w % 2 != 0) throw Error("camera model", "YUYV needs an even image width, got " + std::to_string(w));
  CameraImage image;
  image.camera = camera;
  image.width = w;
  image.height = h;
  image.timestamp = timestamp;
  image.yuyv.resize(static_cast<std::size_t>(w) * h * 2);
  if (!p.enabled) {
    for (int r = 0; r < h; ++r) {
      const std::uint8_t* in = rgbIn.ptr<std::uint8_t>(r);
      std::uint8_t* out = image.yuyv.data() + static_cast<std::size_t>(r) * w * 2;
      for (int c = 0; c < w; c += 2, in += 6, out += 4) yuyvPairFromRgb(in, out);
    }
    addSensorNoise(image, readNoise, rng);
    return image;
  }
  const double corner = p.vignetting ? (camera == CameraId::Top ? p.vignettingTop : p.vignettingBottom) : 1.0;
  const std::vector<float>& vig = vignetteMap(w, h, corner);
  if (!p.autoExposure) setBrightness(1, p);
  if (!p.autoWhiteBalance) state_.whiteBalance = Eigen::Vector3d::Ones();
  const Eigen::Vector3d renderedGains = lightGains(p);

  // Rolling shutter: row r was exposed (r - centre) * readout / (h - 1) after the centre row, when
  // the scene stood imageVelocity * that time further on. Then the blur of the exposure time.
  cv::Mat rgb = rgbIn;
  if (p.motion) {
    const double readout = p.readoutMs / 1000, exposure = state_.exposureMs / 1000;
    const double maxShift = imageVelocity.norm() * readout / 2;
    if (maxShift > 0.25) {
      cv::Mat mapX(h, w, CV_32FC1), mapY(h, w, CV_32FC1);
      for (int r = 0; r < h; ++r) {
        const double dt = (r - (h - 1) / 2.0) / std::max(1, h - 1) * readout;
        const float dx = static_cast<float>(imageVelocity.x() * dt), dy = static_cast<float>(imageVelocity.y() * dt);
        float* mx = mapX.ptr<float>(r);
        float* my = mapY.ptr<float>(r);
        for (int c = 0; c < w; ++c) {
          mx[c] = static_cast<float>(c) - dx;
          my[c] = static_cast<float>(r) - dy;
        }
      }
      cv::Mat shifted;
      cv::remap(rgb, shifted, mapX, mapY, cv::INTER_LINEAR, cv::BORDER_REPLICATE);
      rgb = shifted;
    }
    // A box along u and one along v: exact for motion along an axis (head yaw or pitch), a
    // rectangle instead of a line for diagonal motion.
    const int kx = std::max(1, static_cast<int>(std::lround(std::abs(imageVelocity.x()) * exposure)));
    const int ky = std::max(1, static_cast<int>(std::lround(std::abs(imageVelocity.y()) * exposure)));
    if (kx > 1 || ky > 1) {
      cv::Mat blurred;
      cv::blur(rgb, blurred, cv::Size(kx, ky), cv::Point(-1, -1), cv::BORDER_REPLICATE);
      rgb = blurred;
    }
  }
  if (p.defocus && p.defocusSigmaPx > 0) {
    const double sigma = p.defocusSigmaPx * w / 640.0;
    cv::Mat blurred;
    cv::GaussianBlur(rgb, blurred, cv::Size(0, 0), sigma, sigma, cv::BORDER_REPLICATE);
    rgb = blurred;
  }

  // Vignetting, YUYV, noise: one pass (exposure and white balance came with the lights).
  // Noise in Y units: read noise amplified by the gain, shot noise of the collected light.
  // A lighting without noise (noise=0) is a noiseless sensor: no shot noise either.
  std::array<float, 256> sigmaY{};
  if (readNoise > 0)
    for (int y = 0; y < 256; ++y)
      sigmaY[y] = static_cast<float>(
          std::sqrt(state_.gain * state_.gain * readNoise * readNoise + state_.gain * p.shotNoise * y));
  const auto& gauss = gaussTable();
  FastRng fast{rng() | 1};
  for (int r = 0; r < h; ++r) {
    const std::uint8_t* in = rgb.ptr<std::uint8_t>(r);
    const float* vrow = vig.data() + static_cast<std::size_t>(r) * w;
    std::uint8_t* out = image.yuyv.data() + static_cast<std::size_t>(r) * w * 2;
    for (int c = 0; c < w; c += 2, in += 6, out += 4) {
      const float v0 = vrow[c], v1 = vrow[c + 1];
      const float r0 = in[0] * v0, g0 = in[1] * v0, b0 = in[2] * v0;
      const float r1 = in[3] * v1, g1 = in[4] * v1, b1 = in[5] * v1;
      const float ra = (r0 + r1) * 0.5f, ga = (g0 + g1) * 0.5f, ba = (b0 + b1) * 0.5f;
      const float y0 = 0.299f * r0 + 0.587f * g0 + 0.114f * b0, y1 = 0.299f * r1 + 0.587f * g1 + 0.114f * b1;
      const float u = 128 - 0.168736f * ra - 0.331264f * ga + 0.5f * ba;
      const float vv = 128 + 0.5f * ra - 0.418688f * ga - 0.081312f * ba;
      const std::uint64_t bits = fast.next();
      const float s0 = sigmaY[static_cast<int>(y0)], s1 = sigmaY[static_cast<int>(y1)],
                  suv = 0.5f * sigmaY[static_cast<int>((y0 + y1) * 0.5f)];
      out[0] = toByte(y0 + gauss[bits & 0xffff] * s0);
      out[1] = toByte(u + gauss[(bits >> 16) & 0xffff] * suv);
      out[2] = toByte(y1 + gauss[(bits >> 32) & 0xffff] * s1);
      out[3] = toByte(vv + gauss[bits >> 48] * suv);
    }
  }

  // The loops see this image latencyImages frames from now.
  pending_.push_back(meter(rgbIn, renderedGains, renderedGains));
  state_.meteredLuma = pending_.back().luma;
  while (static_cast<int>(pending_.size()) > p.latencyImages) {
    update(pending_.front(), p, p.aeRate, p.awbRate);
    pending_.pop_front();
  }
  return image;
}

void addSensorNoise(CameraImage& image, double sigma, std::mt19937_64& rng) {
  if (!(sigma > 0)) return;
  const auto& gauss = gaussTable();
  FastRng fast{rng() | 1};
  const float sy = static_cast<float>(sigma), suv = sy / 2;
  std::uint8_t* p = image.yuyv.data();
  for (std::size_t i = 0; i + 3 < image.yuyv.size(); i += 4) {
    const std::uint64_t bits = fast.next();
    p[i] = toByte(p[i] + gauss[bits & 0xffff] * sy);
    p[i + 1] = toByte(p[i + 1] + gauss[(bits >> 16) & 0xffff] * suv);
    p[i + 2] = toByte(p[i + 2] + gauss[(bits >> 32) & 0xffff] * sy);
    p[i + 3] = toByte(p[i + 3] + gauss[bits >> 48] * suv);
  }
}

}  // namespace nao::sim
