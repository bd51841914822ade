#include "sim/CameraRenderer.h"

#include <mujoco/mujoco.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <map>
#include <cmath>
#include <numbers>
#include <vector>

#include "robot/Error.h"
#include "sim/GlContext.h"

namespace nao::sim {

namespace {

constexpr double kSunStrength = 0.75;  // diffuse sun at intensity 1 (white surfaces facing it ~0.75)
constexpr double kSunSpecular = 0.15;  // a little gloss on the ball and the posts
constexpr double kSunDistance = 15.0;  // m: the sun's (shadow camera's) distance from the field centre
constexpr int kMaxSceneGeoms = 20000;

const char* const kWhere = "renderer";

}  // namespace

void applyLighting(mjModel* m, mjData* d, const Lighting& lighting, const Eigen::Vector3d& gains) {
  const Eigen::Vector3d c = lighting.colour().cwiseProduct(gains);
  const double el = lighting.elevation * std::numbers::pi / 180, az = lighting.azimuth * std::numbers::pi / 180;
  // Direction of travel of the sunlight: from azimuth/elevation towards the field.
  const Eigen::Vector3d dir(-std::cos(el) * std::cos(az), -std::cos(el) * std::sin(az), -std::sin(el));
  for (int k = 0; k < 3; ++k) {
    m->vis.headlight.ambient[k] = static_cast<float>(lighting.ambient * lighting.intensity * c[k]);
    m->vis.headlight.diffuse[k] = 0;
    m->vis.headlight.specular[k] = 0;
  }
  m->vis.headlight.active = 1;
  const int sun = mj_name2id(m, mjOBJ_LIGHT, "sun");
  if (sun < 0) return;
  for (int k = 0; k < 3; ++k) {
    m->light_diffuse[3 * sun + k] = static_cast<float>(kSunStrength * lighting.intensity * c[k]);
    m->light_specular[3 * sun + k] = static_cast<float>(kSunSpecular * lighting.intensity * c[k]);
    m->light_ambient[3 * sun + k] = 0;
    m->light_dir[3 * sun + k] = dir[k];
    m->light_pos[3 * sun + k] = -kSunDistance * dir[k];
    // A world light's frame is its model frame; write it so no mj_forward is needed.
    if (d && m->light_bodyid[sun] == 0) {
      d->light_xdir[3 * sun + k] = dir[k];
      d->light_xpos[3 * sun + k] = -kSunDistance * dir[k];
    }
  }
  m->light_directional[sun] = 1;
  m->light_active[sun] = 1;
  m->light_castshadow[sun] = lighting.shadows ? 1 : 0;
}

struct CameraRenderer::Impl {
  std::unique_ptr<GlContext> gl;
  const mjModel* model = nullptr;
  std::array<int, 4> modelSize{};  // ngeom, nmesh, ntex, nmat: tells a new model at an old address
  bool haveContext = false;
  mjrContext con;
  mjvScene scene;
  mjvOption option;
  mjvCamera camera;
  std::vector<std::uint8_t> pixels;
  RenderStages stages;
  std::map<int, CameraSensor> cameras;  // per MuJoCo camera id
  cv::Mat rgb;                         // the last image, top-down

  // OpenGL rows run bottom-up: the read pixels into out with row 0 at the top.
  void flipInto(cv::Mat& out, int width, int height) const {
    out.create(height, width, CV_8UC3);
    const std::size_t rowBytes = static_cast<std::size_t>(width) * 3;
    for (int r = 0; r < height; ++r)
      std::copy_n(pixels.data() + (height - 1 - r) * rowBytes, rowBytes, out.ptr<std::uint8_t>(r));
  }

  void bind(const mjModel* m) {
    const std::array<int, 4> size{m->ngeom, m->nmesh, m->ntex, m->nmat};
    const int width = std::max(1, m->vis.global.offwidth), height = std::max(1, m->vis.global.offheight);
    gl->makeCurrent(width, height);
    if (m == model && size == modelSize && haveContext) return;
    if (haveContext) {
      mjr_freeContext(&con);
      mjv_freeScene(&scene);
    }
    mjr_defaultContext(&con);
    mjr_makeContext(m, &con, mjFONTSCALE_100);
    mjr_setBuffer(mjFB_OFFSCREEN, &con);
    if (con.currentBuffer != mjFB_OFFSCREEN) throw Error(kWhere, "no offscreen framebuffer (OpenGL too old?)");
    mjv_defaultScene(&scene);
    mjv_makeScene(m, &scene, kMaxSceneGeoms);
    model = m;
    modelSize = size;
    haveContext = true;
  }

  ~Impl() {
    if (haveContext) {
      gl->makeCurrent(1, 1);
      mjr_freeContext(&con);
      mjv_freeScene(&scene);
    }
  }
};

const RenderStages& CameraRenderer::lastStages() const { return impl_->stages; }
std::string CameraRenderer::glVendor() const { return impl_->gl->vendor(); }
std::string CameraRenderer::glRenderer() const { return impl_->gl->renderer(); }
std::string CameraRenderer::glPlatform() const { return impl_->gl->platform(); }

CameraRenderer::CameraRenderer(const mjModel* m) : impl_(std::make_unique<Impl>()) {
  Impl& I = *impl_;
  I.gl = std::make_unique<GlContext>();
  // Only what a camera would see: no sites, joints, tendons, rangefinder rays, contact markers;
  // geom groups 0-2 (groups 3-5 hold collision-only geoms).
  mjv_defaultOption(&I.option);
  for (int g = 0; g < mjNGROUP; ++g) {
    I.option.sitegroup[g] = 0;
    I.option.geomgroup[g] = g < 3;
  }
  for (int f : {mjVIS_JOINT, mjVIS_CAMERA, mjVIS_ACTUATOR, mjVIS_LIGHT, mjVIS_TENDON, mjVIS_RANGEFINDER,
                mjVIS_CONSTRAINT, mjVIS_INERTIA, mjVIS_PERTFORCE, mjVIS_PERTOBJ, mjVIS_CONTACTPOINT, mjVIS_CONTACTFORCE,
                mjVIS_TRANSPARENT, mjVIS_AUTOCONNECT, mjVIS_COM, mjVIS_SELECT})
    I.option.flags[f] = 0;
  I.option.flags[mjVIS_TEXTURE] = 1;
  I.option.flags[mjVIS_STATIC] = 1;
  mjv_defaultCamera(&I.camera);
  I.bind(m);
}

CameraRenderer::~CameraRenderer() = default;

void CameraRenderer::drawAndRead(mjModel* m, mjData* d, int mjCameraId, int width, int height,
                                 const Lighting& lighting, const Eigen::Vector3d& gains) {
  Impl& I = *impl_;
  if (mjCameraId < 0 || mjCameraId >= m->ncam)
    throw Error(kWhere,
                "camera id " + std::to_string(mjCameraId) + " out of range (" + std::to_string(m->ncam) + " cameras)");
  I.bind(m);
  if (width <= 0 || height <= 0 || width > I.con.offWidth || height > I.con.offHeight)
    throw Error(kWhere, "image size " + std::to_string(width) + "x" + std::to_string(height) +
                            " exceeds the offscreen buffer " + std::to_string(I.con.offWidth) + "x" +
                            std::to_string(I.con.offHeight) + " (SceneSpec camera resolutions)");
  using Clock = std::chrono::steady_clock;
  auto t = Clock::now();
  auto lap = [&t](double& ms) {
    const auto now = Clock::now();
    ms = std::chrono::duration<double, std::milli>(now - t).count();
    t = now;
  };
  applyLighting(m, d, lighting, gains);
  I.camera.type = mjCAMERA_FIXED;
  I.camera.fixedcamid = mjCameraId;
  mjv_updateScene(m, d, &I.option, nullptr, &I.camera, mjCAT_ALL, &I.scene);
  I.scene.flags[mjRND_SHADOW] = lighting.shadows ? 1 : 0;
  I.scene.flags[mjRND_REFLECTION] = 0;
  I.scene.flags[mjRND_SKYBOX] = 1;
  I.scene.flags[mjRND_FOG] = 0;
  I.scene.flags[mjRND_HAZE] = 0;
  I.scene.flags[mjRND_WIREFRAME] = 0;
  I.scene.flags[mjRND_SEGMENT] = 0;
  I.scene.flags[mjRND_IDCOLOR] = 0;
  I.scene.flags[mjRND_CULL_FACE] = 1;  // a camera inside its head geom sees out, not the head's inside
  const mjrRect viewport{0, 0, width, height};
  lap(I.stages.scene);
  mjr_setBuffer(mjFB_OFFSCREEN, &I.con);
  mjr_render(viewport, &I.scene, &I.con);
  lap(I.stages.draw);
  I.pixels.resize(static_cast<std::size_t>(width) * height * 3);
  mjr_readPixels(I.pixels.data(), nullptr, viewport, &I.con);
  lap(I.stages.read);
}

cv::Mat CameraRenderer::renderRgb(mjModel* m, mjData* d, int mjCameraId, int width, int height,
                                  const Lighting& lighting) {
  Impl& I = *impl_;
  drawAndRead(m, d, mjCameraId, width, height, lighting);
  cv::Mat rgb;
  I.flipInto(rgb, width, height);
  return rgb;
}

CameraImage CameraRenderer::renderImage(mjModel* m, mjData* d, int mjCameraId, int width, int height,
                                        const Lighting& lighting, CameraId camera, double timestamp,
                                        std::mt19937_64& rng, const ExposureWeights& metering) {
  if (width % 2 != 0) throw Error(kWhere, "YUYV needs an even image width, got " + std::to_string(width));
  Impl& I = *impl_;
  CameraSensor& model = I.cameras[mjCameraId];
  model.setMeteringWeights(metering);
  if (model.needsSettling(lighting.camera)) {
    Eigen::Vector3d gains = Eigen::Vector3d::Ones();
    for (int look = 0; look < 3; ++look) {
      drawAndRead(m, d, mjCameraId, width, height, lighting, gains);
      I.flipInto(I.rgb, width, height);
      if (!model.settle(I.rgb, gains, lighting.camera, camera)) break;
      gains = model.lightGains(lighting.camera);
    }
  }
  // Exposure and white balance act before the sensor clips: they scale the lights.
  drawAndRead(m, d, mjCameraId, width, height, lighting, model.lightGains(lighting.camera));
  const auto t0 = std::chrono::steady_clock::now();
  I.flipInto(I.rgb, width, height);
  const cv::Mat& rgb = I.rgb;
  // How the scene moves in the image from the camera's rotation (MuJoCo camera axes: x right,
  // y up, looking along -z): turning about y moves it along u, about x along v.
  Eigen::Vector2d imageVelocity = Eigen::Vector2d::Zero();
  if (lighting.camera.enabled && lighting.camera.motion && d) {
    mjtNum velocity[6];
    mj_objectVelocity(m, d, mjOBJ_CAMERA, mjCameraId, velocity, 1);
    const double f = height / 2.0 / std::tan(m->cam_fovy[mjCameraId] * std::numbers::pi / 360);
    imageVelocity = Eigen::Vector2d(f * velocity[1], f * velocity[0]);
  }
  CameraImage image = model.process(rgb, lighting.camera, lighting.noise, imageVelocity, camera, timestamp, rng);
  I.stages.sensor = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  return image;
}

void CameraRenderer::resetCameraSensors() { impl_->cameras.clear(); }

CameraExposure CameraRenderer::cameraExposure(int mjCameraId) const {
  auto it = impl_->cameras.find(mjCameraId);
  return it == impl_->cameras.end() ? CameraExposure{} : it->second.exposure();
}

}  // namespace nao::sim
