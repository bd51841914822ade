#include "sim/World.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <vector>

#include <mujoco/mujoco.h>

#include "robot/Backend.h"
#include "robot/Error.h"
#include "sim/SceneBuilder.h"
#include "sim/ServoModel.h"
#include "sim/Turf.h"

namespace nao::sim {

namespace {

constexpr double kGravity = 9.81;         // FSRs report N / 9.81 as kg, as LoLA does
constexpr double kStallCurrent = 2.0;     // A at stall torque: a rough current model
constexpr double kTemperature = 30.0;     // deg C, constant
constexpr double kPlaceClearance = 5e-4;  // m between the lowest sole and the carpet when placed
constexpr double kBadValue = 1e10;        // what MuJoCo's own check treats as diverged

using RowMat3 = Eigen::Matrix<double, 3, 3, Eigen::RowMajor>;

// MuJoCo camera axes -> B-Human camera axes: columns are x_cam = -z_mj, y_cam = -x_mj, z_cam = y_mj.
const Eigen::Matrix3d& mujocoToCamera() {
  static const Eigen::Matrix3d m = (Eigen::Matrix3d() << 0, -1, 0, 0, 0, 1, -1, 0, 0).finished();
  return m;
}

Eigen::Quaterniond toEigen(const mjtNum* q) { return {q[0], q[1], q[2], q[3]}; }
void fromEigen(const Eigen::Quaterniond& q, mjtNum* out) {
  out[0] = q.w();
  out[1] = q.x();
  out[2] = q.y();
  out[3] = q.z();
}

// Rx(roll) * Ry(pitch), the calibration offsets' composition (docs/conventions.md).
Eigen::Quaterniond rollPitch(double roll, double pitch) {
  return Eigen::Quaterniond(Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX())) *
         Eigen::Quaterniond(Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()));
}

Eigen::Isometry3d frame(const mjtNum* pos, const mjtNum* rowMajorMat) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.translation() = Eigen::Vector3d(pos[0], pos[1], pos[2]);
  t.linear() = Eigen::Map<const RowMat3>(rowMajorMat);
  return t;
}

}  // namespace

struct World::Impl {
  struct Robot {
    std::string prefix;
    int torso = -1;
    int rootQpos = -1, rootDof = -1;
    std::array<int, NumJoints> joint{}, qpos{}, dof{}, actuator{};
    int rHipYawPitchQpos = -1;
    std::array<ServoParams, NumJoints> servo{};
    int neck = -1;
    Eigen::Vector3d neckPos0 = Eigen::Vector3d::Zero();
    Eigen::Quaterniond neckQuat0 = Eigen::Quaterniond::Identity();
    std::array<int, kNumCameras> camera{};
    std::array<Eigen::Quaterniond, kNumCameras> cameraQuat0{};
    int imuSite = -1;
    std::array<int, 2> sole{};  // left, right
    std::array<int, 2> hand{};  // left, right (bodies)
    std::array<int, 2> soleGeom{-1, -1};  // left, right: the foot's box
    std::array<int, NumFsr> fsrSite{};
    int gyroAdr = -1, accelAdr = -1;
    double mass = 0;
    JointRequest request{};
    JointArray torque{};
    CameraCalibration miscalibration{};
    std::array<double, NumTouch> touch{};
    JointArray offset{};  // true angle = reading + offset
    // The gyro's and accelerometer's readings of the last physics steps: the IMU reports their
    // mean over one cycle (its anti-aliasing filter; a raw sample every 12 ms would alias the
    // stiff contacts' and servos' fast vibrations into a biased yaw rate, and a foot's impact
    // into a spike the cycle's velocity change does not have).
    std::vector<Eigen::Vector3d> gyroHistory, accelHistory;
    std::size_t imuNext = 0;
  };
  struct Ball {
    int body = -1, qpos = -1, dof = -1;
    double radius = 0.05;
  };

  SceneSpec spec;
  std::string modelName;  // for error messages
  FieldModel field;
  mjModel* m = nullptr;
  mjData* d = nullptr;
  int stepsPerCycle = 6;
  std::vector<Robot> robots;
  std::vector<Ball> balls;
  std::vector<int> geomRobot;  // robot owning the geom, -1 for the field and balls
  std::vector<int> geomFoot;   // 0 left foot, 1 right foot, -1 otherwise
  SensorNoise noise;
  mutable std::mt19937_64 rng;
  std::array<int, mjNWARNING> warningsSeen{};
  std::vector<World::BallContact> ballContacts;
  std::vector<std::pair<int, int>> touching, touchingBefore;  // (robot, ball) in contact this / the last step

  // Robot-ball contacts of this step; a pair not in contact in the step before is a new touch.
  void noteBallContacts() {
    touching.clear();
    for (int i = 0; i < d->ncon; ++i) {
      const mjContact& c = d->contact[i];
      for (int k = 0; k < 2; ++k) {
        const int robotGeom = k ? c.geom2 : c.geom1, other = k ? c.geom1 : c.geom2;
        if (geomRobot[robotGeom] < 0) continue;
        for (std::size_t b = 0; b < balls.size(); ++b)
          if (m->geom_bodyid[other] == balls[b].body) touching.emplace_back(geomRobot[robotGeom], static_cast<int>(b));
      }
    }
    std::sort(touching.begin(), touching.end());
    touching.erase(std::unique(touching.begin(), touching.end()), touching.end());
    for (const auto& p : touching)
      if (std::find(touchingBefore.begin(), touchingBefore.end(), p) == touchingBefore.end())
        ballContacts.push_back({p.first, p.second, d->time});
    touchingBefore.swap(touching);
  }

  ~Impl() {
    if (d) mj_deleteData(d);
    if (m) mj_deleteModel(m);
  }

  int find(mjtObj type, const std::string& name, bool required) const {
    const int id = mj_name2id(m, type, name.c_str());
    if (id < 0 && required) throw Error(modelName, "the model has no " + std::string(typeName(type)) + " '" + name + "'");
    return id;
  }
  static const char* typeName(mjtObj type) {
    switch (type) {
      case mjOBJ_BODY: return "body";
      case mjOBJ_JOINT: return "joint";
      case mjOBJ_ACTUATOR: return "actuator";
      case mjOBJ_SITE: return "site";
      case mjOBJ_CAMERA: return "camera";
      case mjOBJ_SENSOR: return "sensor";
      default: return "object";
    }
  }

  bool isDescendant(int body, int ancestor) const {
    for (int b = body; b > 0; b = m->body_parentid[b])
      if (b == ancestor) return true;
    return false;
  }

  void findRobot(int index) {
    Robot r;
    r.prefix = sim::robotPrefix(index);
    const auto name = [&](std::string_view n) { return r.prefix + std::string(n); };
    r.torso = find(mjOBJ_BODY, name("torso"), true);
    r.hand = {find(mjOBJ_BODY, name("LHand"), true), find(mjOBJ_BODY, name("RHand"), true)};
    const int root = find(mjOBJ_JOINT, name("root"), true);
    if (m->jnt_type[root] != mjJNT_FREE || m->jnt_bodyid[root] != r.torso)
      throw Error(modelName, "joint '" + name("root") + "' must be the free joint of '" + name("torso") + "'");
    r.rootQpos = m->jnt_qposadr[root];
    r.rootDof = m->jnt_dofadr[root];
    for (int j = 0; j < NumJoints; ++j) {
      const bool hand = j == LHand || j == RHand;  // hands may be left out of the model
      r.joint[j] = find(mjOBJ_JOINT, name(kJointNames[j]), !hand);
      r.qpos[j] = r.joint[j] >= 0 ? m->jnt_qposadr[r.joint[j]] : -1;
      r.dof[j] = r.joint[j] >= 0 ? m->jnt_dofadr[r.joint[j]] : -1;
      r.actuator[j] = r.joint[j] >= 0 ? find(mjOBJ_ACTUATOR, name(kJointNames[j]), !hand) : -1;
      double stall = 0;
      if (r.actuator[j] >= 0) {
        const int a = r.actuator[j];
        if (m->actuator_trntype[a] != mjTRN_JOINT || m->actuator_trnid[2 * a] != r.joint[j])
          throw Error(modelName, "actuator '" + name(kJointNames[j]) + "' must drive joint '" + name(kJointNames[j]) + "'");
        stall = std::max(std::abs(m->actuator_ctrlrange[2 * a]), std::abs(m->actuator_ctrlrange[2 * a + 1]));
        if (!m->actuator_ctrllimited[a] || !(stall > 0))
          throw Error(modelName, "actuator '" + name(kJointNames[j]) + "': ctrlrange must be the stall torque");
      }
      r.servo[j] = ServoModel::defaults(static_cast<Joint>(j), stall);
      // The model may state the no-load joint speed as the actuator's user[0] (rad/s).
      if (r.actuator[j] >= 0 && m->nuser_actuator >= 1 && m->actuator_user[r.actuator[j] * m->nuser_actuator] > 0)
        r.servo[j].noLoadSpeed = m->actuator_user[r.actuator[j] * m->nuser_actuator];
    }
    r.rHipYawPitchQpos = m->jnt_qposadr[find(mjOBJ_JOINT, name("RHipYawPitch"), true)];
    r.neck = find(mjOBJ_BODY, name("Neck"), true);
    if (m->body_parentid[r.neck] != r.torso)
      throw Error(modelName, "body '" + name("Neck") + "' must be a child of '" + name("torso") + "'");
    r.neckPos0 = Eigen::Vector3d(m->body_pos + 3 * r.neck);
    r.neckQuat0 = toEigen(m->body_quat + 4 * r.neck);
    const std::array<const char*, kNumCameras> cameras = {"CameraTop", "CameraBottom"};
    for (int c = 0; c < kNumCameras; ++c) {
      r.camera[c] = find(mjOBJ_CAMERA, name(cameras[c]), true);
      r.cameraQuat0[c] = toEigen(m->cam_quat + 4 * r.camera[c]);
    }
    r.imuSite = find(mjOBJ_SITE, name("imu"), true);
    r.sole = {find(mjOBJ_SITE, name("LSole"), true), find(mjOBJ_SITE, name("RSole"), true)};
    const std::array<const char*, NumFsr> fsrNames = {"LFsrFL", "LFsrFR", "LFsrRL", "LFsrRR",
                                                      "RFsrFL", "RFsrFR", "RFsrRL", "RFsrRR"};
    for (int i = 0; i < NumFsr; ++i) r.fsrSite[i] = find(mjOBJ_SITE, name(fsrNames[i]), true);
    const int gyro = find(mjOBJ_SENSOR, name("imu_gyro"), true);
    const int accel = find(mjOBJ_SENSOR, name("imu_accel"), true);
    if (m->sensor_type[gyro] != mjSENS_GYRO || m->sensor_type[accel] != mjSENS_ACCELEROMETER)
      throw Error(modelName, "sensors '" + name("imu_gyro") + "', '" + name("imu_accel") + "' must be a gyro and an accelerometer");
    r.gyroAdr = m->sensor_adr[gyro];
    r.accelAdr = m->sensor_adr[accel];
    for (int b = 0; b < m->nbody; ++b)
      if (m->body_rootid[b] == r.torso) r.mass += m->body_mass[b];
    for (int j = 0; j < NumJoints; ++j) r.request.stiffness[j] = 0;

    // Geoms of this robot, and which of them belong to a foot.
    const int lFoot = find(mjOBJ_BODY, name("LFoot"), true);
    const int rFoot = find(mjOBJ_BODY, name("RFoot"), true);
    for (int g = 0; g < m->ngeom; ++g) {
      const int b = m->geom_bodyid[g];
      if (m->body_rootid[b] != r.torso) continue;
      geomRobot[g] = index;
      if (isDescendant(b, lFoot)) geomFoot[g] = 0;
      if (isDescendant(b, rFoot)) geomFoot[g] = 1;
      if (geomFoot[g] >= 0 && m->geom_type[g] == mjGEOM_BOX && r.soleGeom[geomFoot[g]] < 0) r.soleGeom[geomFoot[g]] = g;
    }
    robots.push_back(r);
  }

  // The turf's rolling resistance: a ball on the carpet decelerates by kBallRollingDeceleration
  // against its direction of travel, whatever the direction (a horizontal force at its centre:
  // a solid sphere rolling without slipping decelerates by F / (1.4 m)), and its spin about the
  // vertical dies out. Near standstill the force shrinks with the speed, so the ball stops
  // instead of reversing within a step.
  void applyRollingResistance() {
    constexpr double kSpinDamping = 5.0;          // 1/s: the vertical spin's decay rate
    constexpr double kContactSlack = 0.005;       // m above resting height still on the carpet
    const double dt = m->opt.timestep;
    for (const Ball& b : balls) {
      double* f = d->xfrc_applied + 6 * b.body;
      for (int k = 0; k < 6; ++k) f[k] = 0;
      if (d->qpos[b.qpos + 2] > b.radius + kContactSlack) continue;  // in the air
      const double vx = d->qvel[b.dof], vy = d->qvel[b.dof + 1], speed = std::hypot(vx, vy);
      const double mass = m->body_mass[b.body];
      if (speed > 1e-9) {
        const double a = kBallRollingDeceleration * std::min(1.0, speed / (kBallRollingDeceleration * dt));
        f[0] = -1.4 * mass * a * vx / speed;
        f[1] = -1.4 * mass * a * vy / speed;
      }
      // A free joint's angular velocity is in the body's frame; the torque is the world's.
      const double* R = d->xmat + 9 * b.body;
      const double* w = d->qvel + b.dof + 3;
      const double spin = R[6] * w[0] + R[7] * w[1] + R[8] * w[2];
      f[5] = -kSpinDamping * 0.4 * mass * b.radius * b.radius * spin;
    }
  }

  void findBall(int index) {
    Ball b;
    const std::string name = "ball" + std::to_string(index);
    b.body = find(mjOBJ_BODY, name, true);
    const int joint = m->body_jntadr[b.body];
    if (joint < 0 || m->jnt_type[joint] != mjJNT_FREE) throw Error(modelName, "body '" + name + "' needs a free joint");
    b.qpos = m->jnt_qposadr[joint];
    b.dof = m->jnt_dofadr[joint];
    if (m->body_geomnum[b.body] > 0) b.radius = m->geom_size[3 * m->body_geomadr[b.body]];
    balls.push_back(b);
  }

  // The joint owning qpos (or qvel, when dof) index i.
  std::string jointAt(int i, bool dof) const {
    for (int j = m->njnt - 1; j >= 0; --j) {
      if ((dof ? m->jnt_dofadr[j] : m->jnt_qposadr[j]) <= i) {
        const char* n = mj_id2name(m, mjOBJ_JOINT, j);
        if (n) return n;
        const char* body = mj_id2name(m, mjOBJ_BODY, m->jnt_bodyid[j]);
        return std::string("the joint of body ") + (body ? body : std::to_string(m->jnt_bodyid[j]));
      }
    }
    return "index " + std::to_string(i);
  }

  [[noreturn]] void fail(const std::string& where, const char* what) const {
    char t[32];
    std::snprintf(t, sizeof t, "%.3f", d->time);
    throw Error("simulation", "NaN in " + where + " (" + what + ") at t = " + t + " s");
  }

  void checkFinite() const {
    for (int i = 0; i < m->nq; ++i)
      if (!(std::abs(d->qpos[i]) < kBadValue)) fail(jointAt(i, false), "qpos");
    for (int i = 0; i < m->nv; ++i)
      if (!(std::abs(d->qvel[i]) < kBadValue)) fail(jointAt(i, true), "qvel");
  }

  // MuJoCo resets the state itself when it meets a bad acceleration; report that as the error.
  void checkWarnings() {
    for (int w : {mjWARN_BADQPOS, mjWARN_BADQVEL, mjWARN_BADQACC}) {
      if (d->warning[w].number == warningsSeen[w]) continue;
      warningsSeen[w] = d->warning[w].number;
      fail(jointAt(d->warning[w].lastinfo, w != mjWARN_BADQPOS),
           w == mjWARN_BADQPOS ? "qpos" : w == mjWARN_BADQVEL ? "qvel" : "qacc");
    }
  }

  void applyServos() {
    for (Robot& r : robots) {
      for (int j = 0; j < NumJoints; ++j) {
        const int a = r.actuator[j];
        if (a < 0) continue;
        double target = r.request.position[j] + r.offset[j];
        const int jn = r.joint[j];
        if (m->jnt_limited[jn]) target = std::clamp(target, m->jnt_range[2 * jn], m->jnt_range[2 * jn + 1]);
        r.torque[j] = ServoModel::torque(r.servo[j], target, d->qpos[r.qpos[j]], d->qvel[r.dof[j]], r.request.stiffness[j]);
        d->ctrl[a] = r.torque[j];
      }
    }
  }

  void applyMiscalibration(int index) {
    Robot& r = robots[index];
    const CameraCalibration& c = r.miscalibration;
    const Eigen::Quaterniond body = rollPitch(c.bodyRoll, c.bodyPitch);
    const Eigen::Vector3d pos = body * r.neckPos0;
    for (int k = 0; k < 3; ++k) m->body_pos[3 * r.neck + k] = pos[k];
    fromEigen((body * r.neckQuat0).normalized(), m->body_quat + 4 * r.neck);
    // R_mj' = R_cam' M^T = R_mj M C M^T: the offset, written in MuJoCo's camera axes.
    const Eigen::Matrix3d& M = mujocoToCamera();
    const std::array<Eigen::Quaterniond, kNumCameras> offsets = {rollPitch(c.topRoll, c.topPitch),
                                                                 rollPitch(c.bottomRoll, c.bottomPitch)};
    for (int k = 0; k < kNumCameras; ++k) {
      const Eigen::Quaterniond inMujocoAxes(Eigen::Matrix3d(M * offsets[k].toRotationMatrix() * M.transpose()));
      fromEigen((r.cameraQuat0[k] * inMujocoAxes).normalized(), m->cam_quat + 4 * r.camera[k]);
    }
  }

  const Robot& robot(int index) const {
    if (index < 0 || index >= static_cast<int>(robots.size()))
      throw Error("World", "robot index " + std::to_string(index) + " out of range (" + std::to_string(robots.size()) + " robots)");
    return robots[index];
  }
  Robot& robot(int index) { return const_cast<Robot&>(static_cast<const Impl*>(this)->robot(index)); }
  const Ball& ball(int index) const {
    if (index < 0 || index >= static_cast<int>(balls.size()))
      throw Error("World", "ball index " + std::to_string(index) + " out of range (" + std::to_string(balls.size()) + " balls)");
    return balls[index];
  }

  double gauss(double sigma) const {
    if (sigma <= 0) return 0;
    return std::normal_distribution<double>(0.0, sigma)(rng);
  }

  void fillFsr(const Robot& r, FsrSensorData& fsr) const {
    fsr.weight.fill(0);
    const int robotIndex = static_cast<int>(&r - robots.data());
    for (int side = 0; side < 2; ++side) {
      const Eigen::Vector3d solePos(d->site_xpos + 3 * r.sole[side]);
      const RowMat3 soleRot = Eigen::Map<const RowMat3>(d->site_xmat + 9 * r.sole[side]);
      // The four sensors' positions in the sole frame give the bilinear grid.
      std::array<Eigen::Vector3d, 4> s;
      for (int k = 0; k < 4; ++k)
        s[k] = soleRot.transpose() * (Eigen::Vector3d(d->site_xpos + 3 * r.fsrSite[4 * side + k]) - solePos);
      const double xFront = (s[0].x() + s[1].x()) / 2, xRear = (s[2].x() + s[3].x()) / 2;
      const double yLeft = (s[0].y() + s[2].y()) / 2, yRight = (s[1].y() + s[3].y()) / 2;
      for (int i = 0; i < d->ncon; ++i) {
        const mjContact& c = d->contact[i];
        if (c.efc_address < 0) continue;
        int foot = -1;
        if (geomRobot[c.geom1] == robotIndex && geomFoot[c.geom1] == side && geomRobot[c.geom2] != robotIndex) foot = c.geom1;
        if (geomRobot[c.geom2] == robotIndex && geomFoot[c.geom2] == side && geomRobot[c.geom1] != robotIndex) foot = c.geom2;
        if (foot < 0) continue;
        mjtNum f[6];
        mj_contactForce(m, d, i, f);
        const Eigen::Vector3d normal(c.frame);
        const double load = std::max(0.0, f[0]) * std::abs(normal.dot(soleRot.col(2)));
        const Eigen::Vector3d p = soleRot.transpose() * (Eigen::Vector3d(c.pos) - solePos);
        const double u = std::clamp((p.x() - xRear) / (xFront - xRear), 0.0, 1.0);  // 1 = front
        const double v = std::clamp((p.y() - yRight) / (yLeft - yRight), 0.0, 1.0);  // 1 = left
        const double kg = load / kGravity;
        fsr.weight[4 * side + 0] += kg * u * v;
        fsr.weight[4 * side + 1] += kg * u * (1 - v);
        fsr.weight[4 * side + 2] += kg * (1 - u) * v;
        fsr.weight[4 * side + 3] += kg * (1 - u) * (1 - v);
      }
    }
  }
};

World::World(const SceneSpec& spec, std::uint64_t seed) : impl_(std::make_unique<Impl>()) {
  Impl& I = *impl_;
  I.spec = spec;
  I.modelName = robotModelPath(spec);
  I.rng.seed(seed);
  if (!(spec.physicsStep > 0 && spec.physicsStep <= kCycleTime))
    throw Error("SceneSpec", "physicsStep: must be in (0, 0.012] s");
  I.field = FieldModel::from(spec.field);
  I.m = compileScene(spec);
  if (!I.m) throw Error(I.modelName, "the scene did not compile");
  I.m->opt.timestep = spec.physicsStep;
  I.stepsPerCycle = std::max(1, static_cast<int>(std::lround(kCycleTime / I.m->opt.timestep)));
  I.d = mj_makeData(I.m);
  if (!I.d) throw Error("simulation", "out of memory for the MuJoCo data");
  I.geomRobot.assign(I.m->ngeom, -1);
  I.geomFoot.assign(I.m->ngeom, -1);
  for (int r = 0; r < static_cast<int>(spec.robots.size()); ++r) I.findRobot(r);
  for (int b = 0; b < static_cast<int>(spec.balls.size()); ++b) I.findBall(b);
  mj_forward(I.m, I.d);
  // Until a scenario places them with a posture, robots stand in the model's reference pose.
  for (int r = 0; r < robotCount(); ++r) {
    JointArray posture{};
    for (int j = 0; j < NumJoints; ++j) {
      const int adr = I.robots[r].qpos[j];
      posture[j] = adr >= 0 ? I.m->qpos0[adr] : 0.0;
    }
    placeRobot(r, spec.robots[r], posture);
  }
  for (int b = 0; b < ballCount(); ++b) placeBall(b, spec.balls[b]);
  for (int w = 0; w < mjNWARNING; ++w) I.warningsSeen[w] = I.d->warning[w].number;
}

World::~World() = default;

mjModel_* World::model() { return impl_->m; }
mjData_* World::data() { return impl_->d; }
const mjModel_* World::model() const { return impl_->m; }
const mjData_* World::data() const { return impl_->d; }
const SceneSpec& World::spec() const { return impl_->spec; }
const FieldModel& World::field() const { return impl_->field; }
int World::robotCount() const { return static_cast<int>(impl_->robots.size()); }
int World::ballCount() const { return static_cast<int>(impl_->balls.size()); }
double World::time() const { return impl_->d->time; }

void World::step() {
  Impl& I = *impl_;
  // Checked before the step too: MuJoCo would otherwise quietly reset a corrupted state.
  I.checkFinite();
  I.applyServos();
  I.applyRollingResistance();
  mj_step(I.m, I.d);
  I.checkWarnings();
  if (!I.balls.empty()) I.noteBallContacts();
  for (Impl::Robot& r : I.robots) {
    const Eigen::Vector3d g(I.d->sensordata + r.gyroAdr), a(I.d->sensordata + r.accelAdr);
    if (r.gyroHistory.size() < static_cast<std::size_t>(I.stepsPerCycle)) {
      r.gyroHistory.push_back(g);
      r.accelHistory.push_back(a);
    } else {
      r.gyroHistory[r.imuNext] = g;
      r.accelHistory[r.imuNext] = a;
      r.imuNext = (r.imuNext + 1) % r.gyroHistory.size();
    }
  }
}

void World::stepCycle() {
  for (int i = 0; i < impl_->stepsPerCycle; ++i) step();
  impl_->checkFinite();
}

void World::setJointRequest(int robot, const JointRequest& request) {
  Impl::Robot& r = impl_->robot(robot);
  for (int j = 0; j < NumJoints; ++j) {
    if (!std::isfinite(request.position[j]) || !std::isfinite(request.stiffness[j]))
      throw Error("JointRequest", std::string(kJointNames[j]) + ": position and stiffness must be finite");
  }
  r.request = request;
  for (double& s : r.request.stiffness) s = std::clamp(s, 0.0, 1.0);
}

SensorFrame World::sensors(int robot) const {
  const Impl& I = *impl_;
  const Impl::Robot& r = I.robot(robot);
  const mjData* d = I.d;
  SensorFrame f;
  f.time = d->time;
  for (int j = 0; j < NumJoints; ++j) {
    f.joints.position[j] = r.qpos[j] >= 0 ? d->qpos[r.qpos[j]] - r.offset[j] + I.gauss(I.noise.joint) : r.request.position[j];
    f.joints.stiffness[j] = r.request.stiffness[j];
    const double stall = r.servo[j].stallTorque;
    f.joints.current[j] = stall > 0 ? std::abs(r.torque[j]) / stall * kStallCurrent : 0.0;
    f.joints.temperature[j] = kTemperature;
  }
  // The IMU's readings in its site frame, turned into the torso frame.
  const RowMat3 torsoRot = Eigen::Map<const RowMat3>(d->xmat + 9 * r.torso);
  const RowMat3 siteRot = Eigen::Map<const RowMat3>(d->site_xmat + 9 * r.imuSite);
  const Eigen::Matrix3d siteInTorso = torsoRot.transpose() * siteRot;
  Eigen::Vector3d gyro(d->sensordata + r.gyroAdr);
  if (!r.gyroHistory.empty()) {
    gyro.setZero();
    for (const Eigen::Vector3d& g : r.gyroHistory) gyro += g;
    gyro /= static_cast<double>(r.gyroHistory.size());
  }
  Eigen::Vector3d accel(d->sensordata + r.accelAdr);
  if (!r.accelHistory.empty()) {
    accel.setZero();
    for (const Eigen::Vector3d& a : r.accelHistory) accel += a;
    accel /= static_cast<double>(r.accelHistory.size());
  }
  f.inertial.gyroscope = siteInTorso * gyro + Eigen::Vector3d(I.gauss(I.noise.gyro), I.gauss(I.noise.gyro), I.gauss(I.noise.gyro));
  f.inertial.accelerometer =
      siteInTorso * accel + Eigen::Vector3d(I.gauss(I.noise.accel), I.gauss(I.noise.accel), I.gauss(I.noise.accel));
  const double roll = std::atan2(torsoRot(2, 1), torsoRot(2, 2));
  const double pitch = std::atan2(-torsoRot(2, 0), std::hypot(torsoRot(2, 1), torsoRot(2, 2)));
  f.inertial.angle = Eigen::Vector2d(roll + I.gauss(I.noise.angle), pitch + I.gauss(I.noise.angle));
  I.fillFsr(r, f.fsr);
  f.touch = r.touch;
  f.sonar = {5.0, 5.0};  // nothing in range
  f.battery.charge = 1.0;
  f.battery.temperature = kTemperature;
  return f;
}

void World::setSensorNoise(const SensorNoise& noise) { impl_->noise = noise; }

void World::setTouch(int robot, Touch touch, double value) {
  if (touch < 0 || touch >= NumTouch) throw Error("World", "touch sensor index out of range");
  impl_->robot(robot).touch[touch] = value;
}

void World::setMiscalibration(int robot, const CameraCalibration& offsets) {
  for (double v : offsets.toArray())
    if (!std::isfinite(v)) throw Error("miscalibration", "offsets must be finite");
  impl_->robot(robot).miscalibration = offsets;
  impl_->applyMiscalibration(robot);
  mj_forward(impl_->m, impl_->d);
}

CameraCalibration World::miscalibration(int robot) const { return impl_->robot(robot).miscalibration; }

void World::placeRobot(int robot, const Eigen::Vector3d& pose, const JointArray& posture) {
  Impl& I = *impl_;
  Impl::Robot& r = I.robot(robot);
  mjModel* m = I.m;
  mjData* d = I.d;
  if (!pose.allFinite()) throw Error("--pose", "robot pose must be finite");
  for (int j = 0; j < NumJoints; ++j)
    if (!std::isfinite(posture[j])) throw Error("posture", std::string(kJointNames[j]) + " must be finite");
  mjtNum* q = d->qpos + r.rootQpos;
  q[0] = pose.x();
  q[1] = pose.y();
  q[2] = 1.0;  // trial height, corrected below
  q[3] = std::cos(pose.z() / 2);
  q[4] = 0;
  q[5] = 0;
  q[6] = std::sin(pose.z() / 2);
  JointArray angles = posture;
  for (int j = 0; j < NumJoints; ++j) {
    const int jn = r.joint[j];
    if (jn < 0) continue;
    const double truth = angles[j] + r.offset[j];
    d->qpos[r.qpos[j]] = m->jnt_limited[jn] ? std::clamp(truth, m->jnt_range[2 * jn], m->jnt_range[2 * jn + 1]) : truth;
    angles[j] = d->qpos[r.qpos[j]] - r.offset[j];
  }
  d->qpos[r.rHipYawPitchQpos] = d->qpos[r.qpos[LHipYawPitch]];
  mj_kinematics(m, d);
  const double lowest = std::min(d->site_xpos[3 * r.sole[0] + 2], d->site_xpos[3 * r.sole[1] + 2]);
  q[2] += kPlaceClearance - lowest;
  // At rest: every dof of this robot (its tree starts at the free joint).
  for (int i = 0; i < m->nv; ++i) {
    if (m->body_rootid[m->dof_bodyid[i]] != r.torso) continue;
    d->qvel[i] = 0;
    d->qacc_warmstart[i] = 0;
  }
  r.request.position = angles;
  r.request.stiffness.fill(1.0);
  r.gyroHistory.clear();
  r.accelHistory.clear();
  r.imuNext = 0;
  r.torque.fill(0);
  mj_forward(m, d);
}

void World::placeBall(int ball, const Eigen::Vector3d& position, const Eigen::Vector3d& velocity) {
  Impl& I = *impl_;
  const Impl::Ball& b = I.ball(ball);
  if (!position.allFinite() || !velocity.allFinite()) throw Error("ball", "position and velocity must be finite");
  mjtNum* q = I.d->qpos + b.qpos;
  for (int k = 0; k < 3; ++k) q[k] = position[k];
  q[3] = 1;
  q[4] = q[5] = q[6] = 0;
  mjtNum* v = I.d->qvel + b.dof;
  for (int k = 0; k < 3; ++k) v[k] = velocity[k];
  // On the carpet the ball starts rolling, not sliding: w = (z x v) / r (body frame = world here).
  const bool onGround = position.z() < b.radius + 0.01;
  const Eigen::Vector3d w = onGround ? Eigen::Vector3d(Eigen::Vector3d::UnitZ().cross(velocity) / b.radius)
                                     : Eigen::Vector3d::Zero();
  for (int k = 0; k < 3; ++k) v[3 + k] = w[k];
  mj_forward(I.m, I.d);
}

void World::pushRobot(int robot, const Eigen::Vector3d& impulse) {
  // An instantaneous impulse p at the torso origin: dqvel = M^-1 J^T p (J: the torso origin's
  // translational Jacobian). The whole robot responds as its inertia dictates (translation and
  // rotation); contacts act from the next step on.
  Impl& I = *impl_;
  const Impl::Robot& r = I.robot(robot);
  if (!impulse.allFinite()) throw Error("push", "impulse must be finite");
  mjModel* m = I.m;
  mjData* d = I.d;
  mj_forward(m, d);
  std::vector<mjtNum> jac(3 * m->nv), force(m->nv), dq(m->nv);
  mj_jacBody(m, d, jac.data(), nullptr, r.torso);
  for (int i = 0; i < m->nv; ++i)
    force[i] = jac[i] * impulse.x() + jac[m->nv + i] * impulse.y() + jac[2 * m->nv + i] * impulse.z();
  mj_solveM(m, d, dq.data(), force.data(), 1);
  for (int i = 0; i < m->nv; ++i) d->qvel[i] += dq[i];
  mj_forward(m, d);
}

void World::setJointOffsets(int robot, const JointArray& offsets) {
  for (int j = 0; j < NumJoints; ++j)
    if (!std::isfinite(offsets[j])) throw Error("joint offsets", std::string(kJointNames[j]) + " must be finite");
  impl_->robot(robot).offset = offsets;
}

JointArray World::jointOffsets(int robot) const { return impl_->robot(robot).offset; }

double World::scaleLinkMasses(int robot, double spread, std::uint64_t seed) {
  if (!(spread >= 0 && spread <= 0.5)) throw Error("mass spread", "must be in [0, 0.5]");
  Impl& I = *impl_;
  Impl::Robot& r = I.robot(robot);
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> factor(1 - spread, 1 + spread);
  r.mass = 0;
  for (int b = 0; b < I.m->nbody; ++b) {
    if (I.m->body_rootid[b] != r.torso) continue;
    const double f = factor(rng);
    I.m->body_mass[b] *= f;
    for (int k = 0; k < 3; ++k) I.m->body_inertia[3 * b + k] *= f;
    r.mass += I.m->body_mass[b];
  }
  // mj_setConst recomputes the derived constants at qpos0; keep the state.
  const std::vector<mjtNum> qpos(I.d->qpos, I.d->qpos + I.m->nq), qvel(I.d->qvel, I.d->qvel + I.m->nv);
  mj_setConst(I.m, I.d);
  std::copy(qpos.begin(), qpos.end(), I.d->qpos);
  std::copy(qvel.begin(), qvel.end(), I.d->qvel);
  mj_forward(I.m, I.d);
  return r.mass;
}

void World::setFloorFriction(double friction) {
  if (!(friction > 0 && friction <= 5)) throw Error("floor friction", "must be in (0, 5]");
  Impl& I = *impl_;
  const int carpet = mj_name2id(I.m, mjOBJ_GEOM, "field/carpet");
  for (int g = 0; g < I.m->ngeom; ++g)
    if (g == carpet || I.geomFoot[g] >= 0) I.m->geom_friction[3 * g] = friction;
}

bool World::setGeomColour(int robot, const std::string& geom, const Eigen::Vector4d& rgba) {
  Impl& I = *impl_;
  const int g = mj_name2id(I.m, mjOBJ_GEOM, (I.robot(robot).prefix + geom).c_str());
  if (g < 0) return false;
  for (int k = 0; k < 4; ++k) I.m->geom_rgba[4 * g + k] = static_cast<float>(std::clamp(rgba[k], 0.0, 1.0));
  return true;
}

void World::placeCamera(int robot, CameraId camera, const Eigen::Isometry3d& fieldPose, double fovY) {
  Impl& I = *impl_;
  const int c = cameraIndex(robot, camera);
  I.m->cam_bodyid[c] = 0;  // the world body: cam_pos and cam_quat are field coordinates
  I.m->cam_mode[c] = mjCAMLIGHT_FIXED;
  for (int k = 0; k < 3; ++k) I.m->cam_pos[3 * c + k] = fieldPose.translation()[k];
  fromEigen(Eigen::Quaterniond(fieldPose.linear() * mujocoToCamera().transpose()).normalized(), I.m->cam_quat + 4 * c);
  I.m->cam_fovy[c] = fovY * 180 / M_PI;
  mj_forward(I.m, I.d);
}

Eigen::Vector3d World::robotPose(int robot) const {
  const Eigen::Isometry3d t = torsoPose(robot);
  return {t.translation().x(), t.translation().y(), std::atan2(t.linear()(1, 0), t.linear()(0, 0))};
}

Eigen::Isometry3d World::torsoPose(int robot) const {
  const int b = impl_->robot(robot).torso;
  return frame(impl_->d->xpos + 3 * b, impl_->d->xmat + 9 * b);
}

Eigen::Isometry3d World::cameraPose(int robot, CameraId camera) const {
  const int c = cameraIndex(robot, camera);
  Eigen::Isometry3d t = frame(impl_->d->cam_xpos + 3 * c, impl_->d->cam_xmat + 9 * c);
  t.linear() = t.linear() * mujocoToCamera();
  return t;
}

int World::cameraIndex(int robot, CameraId camera) const {
  return impl_->robot(robot).camera[static_cast<int>(camera)];
}

CameraResolution World::cameraResolution(CameraId camera) const {
  return camera == CameraId::Top ? impl_->spec.top : impl_->spec.bottom;
}

double World::cameraFovY() const {
  const int c = impl_->robots.empty() ? 0 : impl_->robots[0].camera[0];
  return impl_->m->ncam > 0 ? impl_->m->cam_fovy[c] * M_PI / 180.0 : 43.7 * M_PI / 180.0;
}

Eigen::Vector3d World::ballPosition(int ball) const {
  return Eigen::Vector3d(impl_->d->xpos + 3 * impl_->ball(ball).body);
}

Eigen::Vector3d World::handPosition(int robot, bool left) const {
  return Eigen::Vector3d(impl_->d->xpos + 3 * impl_->robot(robot).hand[left ? 0 : 1]);
}

std::array<Eigen::Vector3d, 8> World::soleCorners(int robot) const {
  const Impl& I = *impl_;
  std::array<Eigen::Vector3d, 8> corners{};
  for (int side = 0; side < 2; ++side) {
    const int g = I.robot(robot).soleGeom[side];
    if (g < 0) throw Error(I.modelName, "the robot has no box geom on its " + std::string(side ? "right" : "left") + " foot");
    const Eigen::Vector3d centre(I.d->geom_xpos + 3 * g);
    const Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>> rot(I.d->geom_xmat + 9 * g);
    const double* size = I.m->geom_size + 3 * g;
    int k = 0;
    for (double sx : {-1.0, 1.0})
      for (double sy : {-1.0, 1.0})
        corners[static_cast<std::size_t>(4 * side + k++)] = centre + rot * Eigen::Vector3d(sx * size[0], sy * size[1], -size[2]);
  }
  return corners;
}

std::vector<World::BallContact> World::takeBallContacts() {
  std::vector<BallContact> out;
  out.swap(impl_->ballContacts);
  return out;
}

Eigen::Vector3d World::ballVelocity(int ball) const {
  return Eigen::Vector3d(impl_->d->qvel + impl_->ball(ball).dof);  // a free joint's linear velocity is in the world frame
}

}  // namespace nao::sim
