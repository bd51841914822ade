// Checks models/nao_v6.xml against nao-v6.md and docs/conventions.md. The reference values
// are typed in here from the documents (not read from the XML) and compared with the
// COMPILED model: masses, COMs, kinematic offsets at qpos 0, camera poses, joint limits
// and axes, the HipYawPitch coupling, sites, sensors, collision filtering, and a short
// standing simulation on a floor.
#include <mujoco/mujoco.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "robot/JointIds.h"
#include "robot/Paths.h"

namespace {

constexpr double kDeg = M_PI / 180.0;
constexpr double kMm = 1e-3;

struct ModelDeleter {
  void operator()(mjModel* m) const { mj_deleteModel(m); }
};
struct DataDeleter {
  void operator()(mjData* d) const { mj_deleteData(d); }
};
using ModelPtr = std::unique_ptr<mjModel, ModelDeleter>;
using DataPtr = std::unique_ptr<mjData, DataDeleter>;

std::string modelPath() { return std::string(NAO_SOURCE_DIR) + "/models/nao_v6.xml"; }

ModelPtr load(const std::string& path) {
  char error[1000] = "";
  ModelPtr m(mj_loadXML(path.c_str(), nullptr, error, sizeof(error)));
  EXPECT_TRUE(m) << path << ": " << error;
  return m;
}

struct Vec3 {
  double x, y, z;
};

Vec3 at(const mjtNum* p) { return {p[0], p[1], p[2]}; }
Vec3 operator-(Vec3 a, Vec3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
double norm(Vec3 a) { return std::sqrt(a.x * a.x + a.y * a.y + a.z * a.z); }
double dot(Vec3 a, Vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

#define EXPECT_VEC_NEAR(actual, expected, tol, what)                                          \
  do {                                                                                        \
    const Vec3 a_ = (actual), e_ = (expected);                                                \
    EXPECT_LT(norm(a_ - e_), (tol)) << (what) << ": got (" << a_.x << ", " << a_.y << ", "   \
                                    << a_.z << "), want (" << e_.x << ", " << e_.y << ", "   \
                                    << e_.z << ")";                                           \
  } while (0)

// --- reference values from nao-v6.md (left side; y mirrored for the right) -------------
struct Link {
  const char* left;   // body name on the left (or the only one)
  const char* right;  // body name on the right, nullptr if central
  double massG;
  Vec3 comMm;  // in the link's joint frame; torso: from the hip midpoint
};
const std::vector<Link> kLinks = {
    {"torso", nullptr, 1049.6, {-4.13, 0, 85 + 43.42}},
    {"Neck", nullptr, 78.42, {0, 0, -27.42}},
    {"Head", nullptr, 659.4, {1.09, 1.46, 57.19}},
    {"LShoulder", "RShoulder", 93.04, {-1.65, -26.63, 0.14}},
    {"LBicep", "RBicep", 157.77, {24.55, 5.63, 3.30}},
    {"LElbow", "RElbow", 64.83, {-27.44, 0, -0.14}},
    {"LForeArm", "RForeArm", 77.61, {25.56, 2.81, 0.76}},
    {"LHand", "RHand", 185.33, {34.34, -0.88, 3.08}},
    {"LPelvis", "RPelvis", 69.81, {-7.81, -11.14, 26.61}},
    {"LHip", "RHip", 140.53, {-15.49, 0.29, -5.15}},
    {"LThigh", "RThigh", 389.68, {1.38, 2.21, -53.73}},
    {"LTibia", "RTibia", 301.42, {4.53, 2.25, -49.36}},
    {"LAnkle", "RAnkle", 134.16, {0.45, 0.29, 6.85}},
    {"LFoot", "RFoot", 171.84, {25.42, 3.30, -32.39}},
};

struct Limit {
  const char* joint;
  double loDeg, hiDeg;
};
const std::vector<Limit> kLimits = {
    {"HeadYaw", -119.5, 119.5},       {"HeadPitch", -38.5, 29.5},
    {"LShoulderPitch", -119.5, 119.5}, {"RShoulderPitch", -119.5, 119.5},
    {"LShoulderRoll", -18, 76},        {"RShoulderRoll", -76, 18},
    {"LElbowYaw", -119.5, 119.5},      {"RElbowYaw", -119.5, 119.5},
    {"LElbowRoll", -88.5, -2},         {"RElbowRoll", 2, 88.5},
    {"LWristYaw", -104.5, 104.5},      {"RWristYaw", -104.5, 104.5},
    {"LHipYawPitch", -65.62, 42.44},   {"RHipYawPitch", -65.62, 42.44},
    {"LHipRoll", -21.74, 45.29},       {"RHipRoll", -45.29, 21.74},
    {"LHipPitch", -88, 27.73},         {"RHipPitch", -88, 27.73},
    {"LKneePitch", -5.29, 121.04},     {"RKneePitch", -5.90, 121.47},
    {"LAnklePitch", -68.15, 52.86},    {"RAnklePitch", -67.97, 53.40},
    {"LAnkleRoll", -22.79, 44.06},     {"RAnkleRoll", -44.06, 22.80},
};

class ModelTest : public ::testing::Test {
 protected:
  void SetUp() override {
    m = load(modelPath());
    ASSERT_TRUE(m);
    d.reset(mj_makeData(m.get()));
    mj_forward(m.get(), d.get());  // qpos0: all joints 0, torso at its file pose
  }
  int id(mjtObj type, const std::string& name) const {
    const int i = mj_name2id(m.get(), type, name.c_str());
    EXPECT_GE(i, 0) << "missing " << name;
    return i;
  }
  Vec3 body(const std::string& name) const { return at(d->xpos + 3 * id(mjOBJ_BODY, name)); }
  Vec3 site(const std::string& name) const { return at(d->site_xpos + 3 * id(mjOBJ_SITE, name)); }
  // Position relative to the torso (which is unrotated at qpos 0).
  Vec3 rel(Vec3 world) const { return world - body("torso"); }

  ModelPtr m;
  DataPtr d;
};

TEST_F(ModelTest, TorsoIsUnrotatedAtQpos0) {
  const mjtNum* R = d->xmat + 9 * id(mjOBJ_BODY, "torso");
  for (int i = 0; i < 9; ++i) EXPECT_NEAR(R[i], (i % 4 == 0) ? 1.0 : 0.0, 1e-12);
  EXPECT_EQ(m->jnt_type[id(mjOBJ_JOINT, "root")], mjJNT_FREE);
  EXPECT_EQ(m->jnt_bodyid[id(mjOBJ_JOINT, "root")], id(mjOBJ_BODY, "torso"));
}

TEST_F(ModelTest, MassesMatchTheTable) {
  double sum = 0;
  for (const Link& l : kLinks) {
    for (const char* name : {l.left, l.right}) {
      if (!name) continue;
      sum += l.massG;
      EXPECT_NEAR(m->body_mass[id(mjOBJ_BODY, name)] * 1000, l.massG, 1.0) << name;
    }
  }
  EXPECT_NEAR(sum, 5359.46, 0.01);  // the table's sum
  const double total = mj_getTotalmass(m.get());
  EXPECT_NEAR(total * 1000, sum, 1.0);
  std::printf("total mass %.5f kg (table %.5f kg)\n", total, sum / 1000);
}

TEST_F(ModelTest, CentresOfMassMatchTheTable) {
  for (const Link& l : kLinks) {
    const Vec3 c{l.comMm.x * kMm, l.comMm.y * kMm, l.comMm.z * kMm};
    EXPECT_VEC_NEAR(at(m->body_ipos + 3 * id(mjOBJ_BODY, l.left)), c, 1e-5, l.left);
    if (l.right)
      EXPECT_VEC_NEAR(at(m->body_ipos + 3 * id(mjOBJ_BODY, l.right)), (Vec3{c.x, -c.y, c.z}), 1e-5,
                      l.right);
  }
}

TEST_F(ModelTest, SolesTouchTheGroundAtQpos0) {
  EXPECT_NEAR(body("torso").z, 0.1 + 0.1029 + 0.04519, 1e-9);
  EXPECT_NEAR(site("LSole").z, 0.0, 1e-9);
  EXPECT_NEAR(site("RSole").z, 0.0, 1e-9);
  // The sole box's bottom face is the sole plane.
  for (const char* foot : {"LFoot", "RFoot"}) {
    int g = -1;
    for (int i = 0; i < m->ngeom; ++i)
      if (m->geom_bodyid[i] == id(mjOBJ_BODY, foot) && m->geom_type[i] == mjGEOM_BOX) g = i;
    ASSERT_GE(g, 0) << foot;
    EXPECT_NEAR(d->geom_xpos[3 * g + 2] - m->geom_size[3 * g + 2], 0.0, 1e-9) << foot;
  }
}

TEST_F(ModelTest, LinkOffsetsAtQpos0) {
  const double tol = 1 * kMm;
  struct Offset {
    const char* left;
    const char* right;
    Vec3 p;  // left side, relative to the torso origin (hip midpoint)
  };
  // Chained from nao-v6.md: neck 211.5 up; shoulder (0, 98, 185); upper arm 105 with an elbow
  // y offset of 15; elbow to wrist 55.95; hand offset (57.75, 0, 12.31); hip (0, 50, 0);
  // thigh 100; tibia 102.9; sole 45.19 below the ankle.
  const std::vector<Offset> offsets = {
      {"Neck", nullptr, {0, 0, 0.2115}},
      {"Head", nullptr, {0, 0, 0.2115}},
      {"LShoulder", "RShoulder", {0, 0.098, 0.185}},
      {"LBicep", "RBicep", {0, 0.098, 0.185}},
      {"LElbow", "RElbow", {0.105, 0.098 + 0.015, 0.185}},
      {"LForeArm", "RForeArm", {0.105, 0.113, 0.185}},
      {"LHand", "RHand", {0.105 + 0.05595, 0.113, 0.185}},
      {"LFingers", "RFingers", {0.16095 + 0.05775, 0.113, 0.185 + 0.01231}},
      {"LPelvis", "RPelvis", {0, 0.05, 0}},
      {"LHip", "RHip", {0, 0.05, 0}},
      {"LThigh", "RThigh", {0, 0.05, 0}},
      {"LTibia", "RTibia", {0, 0.05, -0.1}},
      {"LAnkle", "RAnkle", {0, 0.05, -0.2029}},
      {"LFoot", "RFoot", {0, 0.05, -0.2029}},
  };
  for (const Offset& o : offsets) {
    EXPECT_VEC_NEAR(rel(body(o.left)), o.p, tol, o.left);
    if (o.right) EXPECT_VEC_NEAR(rel(body(o.right)), (Vec3{o.p.x, -o.p.y, o.p.z}), tol, o.right);
  }
  EXPECT_VEC_NEAR(rel(site("LSole")), (Vec3{0, 0.05, -0.24809}), tol, "LSole");
  EXPECT_VEC_NEAR(rel(site("RSole")), (Vec3{0, -0.05, -0.24809}), tol, "RSole");
  EXPECT_VEC_NEAR(rel(site("imu")), (Vec3{-0.008, 0.00606, 0.112}), tol, "imu");
}

TEST_F(ModelTest, JointsAxesAndLimits) {
  for (const Limit& l : kLimits) {
    const int j = id(mjOBJ_JOINT, l.joint);
    ASSERT_GE(j, 0);
    EXPECT_EQ(m->jnt_type[j], mjJNT_HINGE) << l.joint;
    EXPECT_TRUE(m->jnt_limited[j]) << l.joint;
    EXPECT_NEAR(m->jnt_range[2 * j] / kDeg, l.loDeg, 0.1) << l.joint;
    EXPECT_NEAR(m->jnt_range[2 * j + 1] / kDeg, l.hiDeg, 0.1) << l.joint;
  }
  for (const char* hand : {"LHand", "RHand"}) {
    const int j = id(mjOBJ_JOINT, hand);
    EXPECT_TRUE(m->jnt_limited[j]);
    EXPECT_NEAR(m->jnt_range[2 * j], 0.0, 1e-12);
    EXPECT_NEAR(m->jnt_range[2 * j + 1], 1.0, 1e-12);
  }
  // World axes at qpos 0 (= torso axes).
  const double s = std::sqrt(0.5);
  const std::map<std::string, Vec3> axes = {
      {"HeadYaw", {0, 0, 1}},       {"HeadPitch", {0, 1, 0}},     {"LShoulderPitch", {0, 1, 0}},
      {"LShoulderRoll", {0, 0, 1}}, {"LElbowYaw", {1, 0, 0}},     {"LElbowRoll", {0, 0, 1}},
      {"LWristYaw", {1, 0, 0}},     {"LHipYawPitch", {0, s, -s}}, {"RHipYawPitch", {0, s, s}},
      {"LHipRoll", {1, 0, 0}},      {"LHipPitch", {0, 1, 0}},     {"LKneePitch", {0, 1, 0}},
      {"LAnklePitch", {0, 1, 0}},   {"LAnkleRoll", {1, 0, 0}},    {"RShoulderPitch", {0, 1, 0}},
      {"RShoulderRoll", {0, 0, 1}}, {"RElbowYaw", {1, 0, 0}},     {"RElbowRoll", {0, 0, 1}},
      {"RWristYaw", {1, 0, 0}},     {"RHipRoll", {1, 0, 0}},      {"RHipPitch", {0, 1, 0}},
      {"RKneePitch", {0, 1, 0}},    {"RAnklePitch", {0, 1, 0}},   {"RAnkleRoll", {1, 0, 0}},
  };
  for (const auto& [name, axis] : axes)
    EXPECT_VEC_NEAR(at(d->xaxis + 3 * id(mjOBJ_JOINT, name)), axis, 1e-9, name);
  // Each joint sits at its body's origin.
  for (int j = 1; j < m->njnt; ++j)
    EXPECT_VEC_NEAR(at(m->jnt_pos + 3 * j), (Vec3{0, 0, 0}), 1e-12, mj_id2name(m.get(), mjOBJ_JOINT, j));
}

TEST_F(ModelTest, JointSignsFollowTheNaoConventions) {
  // HeadPitch > 0 looks down; HipPitch < 0 swings the leg forward; KneePitch > 0 bends
  // the knee backwards; LHipRoll > 0 spreads the left leg outwards.
  auto moved = [&](const char* joint, double q, const char* bodyName) {
    mju_copy(d->qpos, m->qpos0, m->nq);
    d->qpos[m->jnt_qposadr[id(mjOBJ_JOINT, joint)]] = q;
    mj_kinematics(m.get(), d.get());
    mj_camlight(m.get(), d.get());
    return bodyName ? body(bodyName) : Vec3{};
  };
  const Vec3 footNeutral = body("LFoot");
  EXPECT_GT(moved("LHipPitch", -0.5, "LFoot").x, footNeutral.x + 0.05);
  EXPECT_LT(moved("LKneePitch", 0.5, "LFoot").x, footNeutral.x - 0.02);
  EXPECT_GT(moved("LHipRoll", 0.3, "LFoot").y, footNeutral.y + 0.03);
  EXPECT_LT(moved("RHipRoll", -0.3, "RFoot").y, -footNeutral.y - 0.03);
  moved("HeadPitch", 0.3, nullptr);
  const mjtNum* R = d->cam_xmat + 9 * id(mjOBJ_CAMERA, "CameraTop");
  const double opticalZ = -R[8];  // z of -z_mj (third column)
  EXPECT_NEAR(std::asin(-opticalZ) / kDeg, 1.2 + 0.3 / kDeg, 0.1);
}

TEST_F(ModelTest, Cameras) {
  struct Cam {
    const char* name;
    Vec3 pos;  // in the HeadPitch joint frame
    double pitchDownDeg;
  };
  for (const Cam& c : {Cam{"CameraTop", {0.05871, 0, 0.06364}, 1.2},
                       Cam{"CameraBottom", {0.05071, 0, 0.01774}, 39.7}}) {
    const int cam = id(mjOBJ_CAMERA, c.name);
    ASSERT_GE(cam, 0);
    EXPECT_EQ(m->cam_bodyid[cam], id(mjOBJ_BODY, "Head")) << c.name;
    EXPECT_NEAR(m->cam_fovy[cam], 43.7, 1e-9) << c.name;
    EXPECT_VEC_NEAR(at(d->cam_xpos + 3 * cam) - body("Head"), c.pos, 1 * kMm, c.name);
    // MuJoCo camera axes (columns of cam_xmat) -> camera frame: x_cam = -z_mj, y_cam = -x_mj,
    // z_cam = y_mj. Expected camera frame: Ry(p) (p > 0 turns x towards -z).
    const mjtNum* R = d->cam_xmat + 9 * cam;
    const Vec3 xmj{R[0], R[3], R[6]}, ymj{R[1], R[4], R[7]}, zmj{R[2], R[5], R[8]};
    const Vec3 xc{-zmj.x, -zmj.y, -zmj.z}, yc{-xmj.x, -xmj.y, -xmj.z}, zc = ymj;
    const double p = c.pitchDownDeg * kDeg;
    const Vec3 ex{std::cos(p), 0, -std::sin(p)}, ey{0, 1, 0}, ez{std::sin(p), 0, std::cos(p)};
    const double trace = dot(xc, ex) + dot(yc, ey) + dot(zc, ez);
    const double angleDeg = std::acos(std::min(1.0, (trace - 1) / 2)) / kDeg;
    EXPECT_LT(angleDeg, 0.1) << c.name;
    EXPECT_NEAR(std::asin(-xc.z) / kDeg, c.pitchDownDeg, 0.1) << c.name;  // looks down
    EXPECT_GT(xc.x, 0.7) << c.name;                                         // and forward
  }
}

TEST_F(ModelTest, HipYawPitchCoupling) {
  const int l = id(mjOBJ_JOINT, "LHipYawPitch"), r = id(mjOBJ_JOINT, "RHipYawPitch");
  int found = 0;
  for (int e = 0; e < m->neq; ++e) {
    if (m->eq_type[e] != mjEQ_JOINT) continue;
    EXPECT_EQ(m->eq_obj1id[e], r);
    EXPECT_EQ(m->eq_obj2id[e], l);
    EXPECT_TRUE(m->eq_active[e]);
    const std::array<double, 5> poly = {0, 1, 0, 0, 0};
    for (int i = 0; i < 5; ++i) EXPECT_NEAR(m->eq_data[mjNEQDATA * e + i], poly[i], 1e-12);
    ++found;
  }
  EXPECT_EQ(found, 1);
}

TEST_F(ModelTest, ActuatorsInLolaOrder) {
  ASSERT_EQ(m->nu, nao::NumJoints);
  for (int i = 0; i < nao::NumJoints; ++i) {
    const std::string name(nao::kJointNames[i]);
    EXPECT_EQ(mj_id2name(m.get(), mjOBJ_ACTUATOR, i), name);
    EXPECT_EQ(m->actuator_trntype[i], mjTRN_JOINT) << name;
    EXPECT_EQ(m->actuator_trnid[2 * i], id(mjOBJ_JOINT, name)) << name;
    EXPECT_NEAR(m->actuator_gear[6 * i], 1.0, 1e-12) << name;
    EXPECT_TRUE(m->actuator_ctrllimited[i]) << name;
    EXPECT_NEAR(m->actuator_ctrlrange[2 * i], -m->actuator_ctrlrange[2 * i + 1], 1e-12) << name;
    EXPECT_GT(m->actuator_ctrlrange[2 * i + 1], 0.1) << name;
    ASSERT_GE(m->nuser_actuator, 1);
    EXPECT_GT(m->actuator_user[m->nuser_actuator * i], 1.0) << name << ": no-load speed";
  }
  EXPECT_LT(mj_name2id(m.get(), mjOBJ_ACTUATOR, "RHipYawPitch"), 0);
  // Stall torques: 68 mNm x 201.3 (roll joints, HipYawPitch) and x 130.85 (pitch joints).
  auto stall = [&](const char* n) { return m->actuator_ctrlrange[2 * id(mjOBJ_ACTUATOR, n) + 1]; };
  for (const char* n : {"LHipYawPitch", "LHipRoll", "RHipRoll", "LAnkleRoll", "RAnkleRoll"})
    EXPECT_NEAR(stall(n), 0.068 * 201.3, 0.01) << n;
  for (const char* n : {"LHipPitch", "RHipPitch", "LKneePitch", "RKneePitch", "LAnklePitch", "RAnklePitch"})
    EXPECT_NEAR(stall(n), 0.068 * 130.85, 0.01) << n;
}

TEST_F(ModelTest, SitesAndSensors) {
  struct Fsr {
    const char* name;
    const char* foot;
    double x, y;
  };
  const std::vector<Fsr> fsrs = {
      {"LFsrFL", "LFoot", 0.07025, 0.0299},   {"LFsrFR", "LFoot", 0.07025, -0.0231},
      {"LFsrRL", "LFoot", -0.03025, 0.0299},  {"LFsrRR", "LFoot", -0.02965, -0.0191},
      {"RFsrFL", "RFoot", 0.07025, 0.0231},   {"RFsrFR", "RFoot", 0.07025, -0.0299},
      {"RFsrRL", "RFoot", -0.03025, 0.0191},  {"RFsrRR", "RFoot", -0.02965, -0.0299},
  };
  std::map<std::string, int> perFoot;
  for (const Fsr& f : fsrs) {
    const int s = id(mjOBJ_SITE, f.name);
    ASSERT_GE(s, 0);
    EXPECT_EQ(m->site_bodyid[s], id(mjOBJ_BODY, f.foot)) << f.name;
    EXPECT_VEC_NEAR(site(f.name) - body(f.foot), (Vec3{f.x, f.y, -0.04519}), 1e-6, f.name);
    ++perFoot[f.foot];
  }
  EXPECT_EQ(perFoot["LFoot"], 4);
  EXPECT_EQ(perFoot["RFoot"], 4);
  // The FSRs lie on the sole box.
  for (const Fsr& f : fsrs) {
    const Vec3 local = site(f.name) - body(f.foot);
    const bool left = f.foot[0] == 'L';
    EXPECT_GT(local.x, -0.050);
    EXPECT_LT(local.x, 0.100);
    EXPECT_GT(local.y, left ? -0.03877 : -0.05002);
    EXPECT_LT(local.y, left ? 0.05002 : 0.03877);
  }
  const int gyro = id(mjOBJ_SENSOR, "imu_gyro"), accel = id(mjOBJ_SENSOR, "imu_accel");
  const int quat = id(mjOBJ_SENSOR, "torso_quat");
  ASSERT_GE(gyro, 0);
  ASSERT_GE(accel, 0);
  ASSERT_GE(quat, 0);
  EXPECT_EQ(m->sensor_type[gyro], mjSENS_GYRO);
  EXPECT_EQ(m->sensor_objid[gyro], id(mjOBJ_SITE, "imu"));
  EXPECT_EQ(m->sensor_type[accel], mjSENS_ACCELEROMETER);
  EXPECT_EQ(m->sensor_objid[accel], id(mjOBJ_SITE, "imu"));
  EXPECT_EQ(m->sensor_type[quat], mjSENS_FRAMEQUAT);
  EXPECT_EQ(m->sensor_objid[quat], id(mjOBJ_BODY, "torso"));
}

TEST_F(ModelTest, NoSelfCollisionButContactWithTheWorld) {
  int feet = 0;
  for (int a = 0; a < m->ngeom; ++a) {
    // Every robot geom meets a default world geom (contype = conaffinity = 1).
    EXPECT_TRUE((m->geom_contype[a] & 1) || (m->geom_conaffinity[a] & 1))
        << mj_id2name(m.get(), mjOBJ_GEOM, a);
    for (int b = a + 1; b < m->ngeom; ++b)
      EXPECT_FALSE((m->geom_contype[a] & m->geom_conaffinity[b]) || (m->geom_contype[b] & m->geom_conaffinity[a]))
          << mj_id2name(m.get(), mjOBJ_GEOM, a) << " / " << mj_id2name(m.get(), mjOBJ_GEOM, b);
    const int body = m->geom_bodyid[a];
    if (body == id(mjOBJ_BODY, "LFoot") || body == id(mjOBJ_BODY, "RFoot")) {
      ++feet;
      EXPECT_NEAR(m->geom_friction[3 * a], 1.0, 1e-9);
      EXPECT_GT(m->geom_priority[a], 0);       // its contact parameters win over the floor's
      EXPECT_LE(m->geom_solref[mjNREF * a], 0.005);  // stiff: time constant <= 5 ms
    }
  }
  EXPECT_EQ(feet, 2);
}

// The model plus a floor, written to a temporary file (the model has no relative paths).
ModelPtr loadWithFloor() {
  std::ifstream in(modelPath());
  std::stringstream text;
  text << in.rdbuf();
  std::string xml = text.str();
  const std::string tag = "<worldbody>";
  const auto at = xml.find(tag);
  if (at == std::string::npos) return nullptr;
  xml.insert(at + tag.size(), R"(<geom name="floor" type="plane" size="5 5 0.1"/>)");
  xml.insert(at, R"(<option timestep="0.002"/>)");
  const auto path = std::filesystem::temp_directory_path() / ("nao_model_test_" + std::to_string(::getpid()) + ".xml");
  std::ofstream(path) << xml;
  ModelPtr m = load(path.string());
  std::filesystem::remove(path);
  return m;
}

TEST(ModelDynamics, StandsInABentKneeStanceOnAFloor) {
  ModelPtr m = loadWithFloor();
  ASSERT_TRUE(m);
  DataPtr d(mj_makeData(m.get()));
  mj_forward(m.get(), d.get());
  // Per-joint PD: the stall torque at 3 deg of error, damping ratio 0.7 on the joint's
  // own inertia (armature included).
  std::vector<double> kp(m->nu), kd(m->nu), target(m->nu, 0.0);
  for (int i = 0; i < m->nu; ++i) {
    const int dof = m->jnt_dofadr[m->actuator_trnid[2 * i]];
    kp[i] = m->actuator_ctrlrange[2 * i + 1] / (3 * kDeg);
    kd[i] = 2 * 0.7 * std::sqrt(kp[i] * d->qM[m->dof_Madr[dof]]);
  }
  auto set = [&](int joint, double q) { target[joint] = q; };
  const double bend = 0.35;  // hip -b, knee 2b, ankle -b keeps the soles flat
  const int torso = mj_name2id(m.get(), mjOBJ_BODY, "torso");
  const int lsole = mj_name2id(m.get(), mjOBJ_SITE, "LSole"), rsole = mj_name2id(m.get(), mjOBJ_SITE, "RSole");
  const int lhyp = mj_name2id(m.get(), mjOBJ_JOINT, "LHipYawPitch");
  const int rhyp = mj_name2id(m.get(), mjOBJ_JOINT, "RHipYawPitch");
  const int accel = mj_name2id(m.get(), mjOBJ_SENSOR, "imu_accel");
  double maxPenetration = 0, maxTorqueFraction = 0, maxCouplingError = 0;
  const int steps = 1500;  // 3 s
  for (int step = 0; step < steps; ++step) {
    const double ramp = std::min(1.0, step * m->opt.timestep / 1.0);
    for (const auto [h, k, a] : {std::array{nao::LHipPitch, nao::LKneePitch, nao::LAnklePitch},
                                 std::array{nao::RHipPitch, nao::RKneePitch, nao::RAnklePitch}}) {
      set(h, -bend * ramp);
      set(k, 2 * bend * ramp);
      set(a, -bend * ramp);
    }
    for (int i = 0; i < m->nu; ++i) {
      const int j = m->actuator_trnid[2 * i];
      const double q = d->qpos[m->jnt_qposadr[j]], qd = d->qvel[m->jnt_dofadr[j]];
      const double limit = m->actuator_ctrlrange[2 * i + 1];
      d->ctrl[i] = std::clamp(kp[i] * (target[i] - q) - kd[i] * qd, -limit, limit);
      if (step > 750) maxTorqueFraction = std::max(maxTorqueFraction, std::abs(d->ctrl[i]) / limit);
    }
    mj_step(m.get(), d.get());
    for (int c = 0; c < d->ncon; ++c) maxPenetration = std::max(maxPenetration, -d->contact[c].dist);
    maxCouplingError = std::max(maxCouplingError, std::abs(d->qpos[m->jnt_qposadr[lhyp]] -
                                                           d->qpos[m->jnt_qposadr[rhyp]]));
  }
  const mjtNum* R = d->xmat + 9 * torso;
  const double tiltDeg = std::acos(std::min(1.0, R[8])) / kDeg;
  // Expected hip height of the bent stance: thigh and tibia at angle b from vertical.
  const double expectedZ = (0.1 + 0.1029) * std::cos(bend) + 0.04519;
  std::printf("torso z %.4f (expect %.4f), tilt %.2f deg, max penetration %.3f mm, "
              "max |torque|/stall %.2f, HipYawPitch coupling error %.2e rad, accel z %.3f\n",
              d->xpos[3 * torso + 2], expectedZ, tiltDeg, maxPenetration * 1000, maxTorqueFraction,
              maxCouplingError, d->sensordata[m->sensor_adr[accel] + 2]);
  EXPECT_NEAR(d->xpos[3 * torso + 2], expectedZ, 0.005);
  EXPECT_LT(tiltDeg, 3.0);
  EXPECT_LT(maxPenetration, 0.0005);
  EXPECT_LT(std::abs(d->site_xpos[3 * lsole + 2]), 0.0005);
  EXPECT_LT(std::abs(d->site_xpos[3 * rsole + 2]), 0.0005);
  EXPECT_LT(maxTorqueFraction, 0.5);
  EXPECT_LT(maxCouplingError, 1e-3);
  EXPECT_GE(d->ncon, 4);
  for (int w = 0; w < mjNWARNING; ++w) EXPECT_EQ(d->warning[w].number, 0) << "MuJoCo warning " << w;
  // At rest the accelerometer reads +g up (in the nearly upright torso frame).
  EXPECT_NEAR(d->sensordata[m->sensor_adr[accel] + 2], 9.81, 0.3);
  // No ground contact other than the soles.
  for (int c = 0; c < d->ncon; ++c) {
    const int g = d->contact[c].geom1 == 0 ? d->contact[c].geom2 : d->contact[c].geom1;
    const std::string name = mj_id2name(m.get(), mjOBJ_GEOM, g);
    EXPECT_TRUE(name == "LFoot_geom" || name == "RFoot_geom") << name;
  }
}

}  // namespace
