// Scene assembly (sim/SceneBuilder): the field from field_dimensions.json, robot copies with
// prefixed names, balls, and errors for bad robot models.
#include <gtest/gtest.h>
#include <mujoco/mujoco.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <opencv2/imgcodecs.hpp>
#include <string>

#include "perception/FieldDimensions.h"
#include "robot/Error.h"
#include "robot/Paths.h"
#include "sim/SceneBuilder.h"

namespace {

using namespace nao;
using namespace nao::sim;
namespace fs = std::filesystem;

// A small robot that uses every kind of name reference the builder must prefix.
const char* kStandInRobot = R"(<mujoco model="standin">
  <compiler angle="radian"/>
  <default><default class="standin"><geom rgba="0.9 0.9 0.9 1" contype="2" conaffinity="1"/></default></default>
  <asset><material name="standin_mat" rgba="0.8 0.8 0.8 1"/></asset>
  <worldbody>
    <geom name="floor" type="plane" size="1 1 0.1"/>
    <body name="torso" pos="0 0 0.3" childclass="standin">
      <freejoint name="root"/>
      <geom name="torso_geom" type="box" size="0.05 0.05 0.05" material="standin_mat"/>
      <site name="imu"/>
      <body name="Head" pos="0 0 0.1">
        <joint name="HeadYaw" axis="0 0 1" range="-1 1" limited="true"/>
        <geom name="head_geom" type="sphere" size="0.03"/>
        <camera name="CameraTop" pos="0.03 0 0" xyaxes="0 -1 0 0 0 1" fovy="43.7"/>
        <camera name="CameraBottom" pos="0.03 0 -0.02" xyaxes="0 -1 0 0.6 0 0.8" fovy="43.7"/>
      </body>
      <body name="LLeg" pos="0 0.05 -0.05">
        <joint name="LHipYawPitch" axis="0 1 -1"/>
        <geom name="lleg" type="capsule" fromto="0 0 0 0 0 -0.2" size="0.02"/>
        <site name="LSole" pos="0 0 -0.22"/>
      </body>
      <body name="RLeg" pos="0 -0.05 -0.05">
        <joint name="RHipYawPitch" axis="0 1 1"/>
        <geom name="rleg" type="capsule" fromto="0 0 0 0 0 -0.2" size="0.02"/>
      </body>
    </body>
  </worldbody>
  <contact><exclude body1="LLeg" body2="RLeg"/></contact>
  <equality><joint joint1="RHipYawPitch" joint2="LHipYawPitch" polycoef="0 1 0 0 0"/></equality>
  <tendon><fixed name="hips"><joint joint="LHipYawPitch" coef="1"/><joint joint="RHipYawPitch" coef="1"/></fixed></tendon>
  <actuator><motor name="HeadYaw" joint="HeadYaw" ctrllimited="true" ctrlrange="-1 1"/><motor name="LHipYawPitch" joint="LHipYawPitch"/></actuator>
  <sensor><gyro name="gyro" site="imu"/><framepos name="sole" objtype="site" objname="LSole"/><jointpos name="hy" joint="HeadYaw"/></sensor>
  <keyframe><key name="home" qpos="0 0 0.3 1 0 0 0 0 0 0"/></keyframe>
</mujoco>
)";

class TempDir {
 public:
  TempDir() {
    path_ =
        fs::temp_directory_path() / ("nao_scene_test_" + std::to_string(::getpid()) + "_" + std::to_string(counter_++));
    fs::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  const fs::path& path() const { return path_; }
  std::string write(const std::string& name, const std::string& text) const {
    const fs::path p = path_ / name;
    std::ofstream(p) << text;
    return p.string();
  }

 private:
  fs::path path_;
  static inline int counter_ = 0;
};

FieldDimensions field(const std::string& file) { return FieldDimensions::load(dataPath("config/" + file)); }

struct ModelPtr {
  mjModel* m;
  explicit ModelPtr(mjModel* model) : m(model) {}
  ~ModelPtr() {
    if (m) mj_deleteModel(m);
  }
  ModelPtr(const ModelPtr&) = delete;
  ModelPtr& operator=(const ModelPtr&) = delete;
};

int countGeomsContaining(const mjModel* m, const std::string& part) {
  int n = 0;
  for (int g = 0; g < m->ngeom; ++g) {
    const char* name = mj_id2name(m, mjOBJ_GEOM, g);
    if (name && std::string(name).find(part) != std::string::npos) ++n;
  }
  return n;
}

int id(const mjModel* m, mjtObj type, const std::string& name) { return mj_name2id(m, type, name.c_str()); }

TEST(SceneTest, CompilesTheStandardFieldWithTheNaoModel) {
  SceneSpec spec;
  spec.field = field("field_dimensions.json");
  spec.balls = {Eigen::Vector3d(1, 0, 0.05)};
  ModelPtr model(compileScene(spec));
  const mjModel* m = model.m;
  ASSERT_NE(m, nullptr);
  EXPECT_GE(id(m, mjOBJ_BODY, "r0/torso"), 0);
  EXPECT_GE(id(m, mjOBJ_JOINT, "r0/root"), 0);
  EXPECT_GE(id(m, mjOBJ_CAMERA, "r0/CameraTop"), 0);
  EXPECT_GE(id(m, mjOBJ_CAMERA, "r0/CameraBottom"), 0);
  EXPECT_GE(id(m, mjOBJ_SITE, "r0/imu"), 0);
  EXPECT_GE(id(m, mjOBJ_LIGHT, "sun"), 0);
  EXPECT_GE(id(m, mjOBJ_BODY, "ball0"), 0);
  EXPECT_DOUBLE_EQ(m->opt.timestep, spec.physicsStep);
  EXPECT_EQ(m->vis.global.offwidth, 640);
  EXPECT_EQ(m->vis.global.offheight, 480);

  const FieldModel f = FieldModel::from(spec.field);
  EXPECT_EQ(countGeomsContaining(m, "field/line/"), static_cast<int>(f.lines.size()));
  EXPECT_GT(countGeomsContaining(m, "goal_box"), 0);
  EXPECT_GE(countGeomsContaining(m, "field/circle/"), 72);
  EXPECT_EQ(countGeomsContaining(m, "field/penalty_cross/"), 4);
  EXPECT_EQ(countGeomsContaining(m, "goal/own/post"), 2);
  EXPECT_EQ(countGeomsContaining(m, "goal/opp/post"), 2);

  // Paint is visual only: a plane 0.5 mm above the carpet.
  const int goalLine = id(m, mjOBJ_GEOM, "field/line/opp_goal_line");
  ASSERT_GE(goalLine, 0);
  EXPECT_EQ(m->geom_contype[goalLine], 0);
  EXPECT_EQ(m->geom_conaffinity[goalLine], 0);
  EXPECT_EQ(m->geom_type[goalLine], mjGEOM_PLANE);
  EXPECT_NEAR(m->geom_pos[3 * goalLine + 2], 0.0005, 1e-9);
  EXPECT_NEAR(m->geom_size[3 * goalLine + 1], 0.025, 1e-9);
  EXPECT_NEAR(m->geom_pos[3 * goalLine + 0], 4.5, 1e-9);
  // Posts centred on the goal line, inner faces 1.5 m apart.
  const int post = id(m, mjOBJ_GEOM, "goal/opp/post_left");
  ASSERT_GE(post, 0);
  EXPECT_NEAR(m->geom_pos[3 * post + 0], 4.5, 1e-9);
  EXPECT_NEAR(m->geom_pos[3 * post + 1] - m->geom_size[3 * post], 0.75, 1e-9);
}

TEST(SceneTest, ReducedAnd2019Fields) {
  for (const char* file : {"field_dimensions_reduced.json", "field_dimensions_2019.json"}) {
    SCOPED_TRACE(file);
    SceneSpec spec;
    spec.field = field(file);
    ModelPtr model(compileScene(spec));
    ASSERT_NE(model.m, nullptr);
    const FieldModel f = FieldModel::from(spec.field);
    EXPECT_EQ(countGeomsContaining(model.m, "field/line/"), static_cast<int>(f.lines.size()));
    const int goalLine = id(model.m, mjOBJ_GEOM, "field/line/opp_goal_line");
    ASSERT_GE(goalLine, 0);
    EXPECT_NEAR(model.m->geom_pos[3 * goalLine], spec.field.length / 2, 1e-9);
    if (!spec.field.hasGoalBox) {
      EXPECT_EQ(countGeomsContaining(model.m, "goal_box"), 0);
    }
  }
}

TEST(SceneTest, TwoRobotsAndTwoBallsGetPrefixedNames) {
  TempDir dir;
  SceneSpec spec;
  spec.robotModel = dir.write("standin.xml", kStandInRobot);
  spec.robots = {Eigen::Vector3d(-1, 0.5, 0), Eigen::Vector3d(2, -1, std::numbers::pi / 2)};
  spec.balls = {Eigen::Vector3d(0, 0, 0.05), Eigen::Vector3d(1, 1, 0.05)};
  ModelPtr model(compileScene(spec));
  const mjModel* m = model.m;
  ASSERT_NE(m, nullptr);
  for (int r = 0; r < 2; ++r) {
    const std::string p = robotPrefix(r);
    EXPECT_GE(id(m, mjOBJ_BODY, p + "torso"), 0);
    EXPECT_GE(id(m, mjOBJ_JOINT, p + "root"), 0);
    EXPECT_GE(id(m, mjOBJ_CAMERA, p + "CameraTop"), 0);
    EXPECT_GE(id(m, mjOBJ_SITE, p + "imu"), 0);
    EXPECT_GE(id(m, mjOBJ_SENSOR, p + "gyro"), 0);
    EXPECT_GE(id(m, mjOBJ_TENDON, p + "hips"), 0);
    // References point into the same copy.
    const int act = id(m, mjOBJ_ACTUATOR, p + "HeadYaw");
    ASSERT_GE(act, 0);
    EXPECT_EQ(m->actuator_trnid[2 * act], id(m, mjOBJ_JOINT, p + "HeadYaw"));
    const int sole = id(m, mjOBJ_SENSOR, p + "sole");
    ASSERT_GE(sole, 0);
    EXPECT_EQ(m->sensor_objid[sole], id(m, mjOBJ_SITE, p + "LSole"));
  }
  ASSERT_EQ(m->neq, 2);
  EXPECT_EQ(m->eq_obj1id[1], id(m, mjOBJ_JOINT, "r1/RHipYawPitch"));
  EXPECT_EQ(m->eq_obj2id[1], id(m, mjOBJ_JOINT, "r1/LHipYawPitch"));
  EXPECT_EQ(m->nexclude, 2);
  EXPECT_EQ(m->nkey, 0);  // keyframes are dropped
  // The stand-alone floor of the robot file is not copied; shared assets/classes exist once.
  EXPECT_EQ(id(m, mjOBJ_GEOM, "floor"), -1);
  int standinMaterials = 0;
  for (int i = 0; i < m->nmat; ++i) standinMaterials += std::string(mj_id2name(m, mjOBJ_MATERIAL, i)) == "standin_mat";
  EXPECT_EQ(standinMaterials, 1);
  for (int j = 0; j < 2; ++j) {
    const std::string name = "ball" + std::to_string(j);
    const int body = id(m, mjOBJ_BODY, name);
    ASSERT_GE(body, 0);
    EXPECT_EQ(m->jnt_type[m->body_jntadr[body]], mjJNT_FREE);
    EXPECT_EQ(std::string(mj_id2name(m, mjOBJ_GEOM, m->body_geomadr[body])), name);
    EXPECT_DOUBLE_EQ(m->geom_size[3 * m->body_geomadr[body]], kBallRadius);
    EXPECT_NEAR(m->body_mass[body], kBallMass, 1e-12);
  }
  // Torsos at (x, y, original z) turned to theta.
  const int torso1 = id(m, mjOBJ_BODY, "r1/torso");
  EXPECT_NEAR(m->body_pos[3 * torso1 + 0], 2, 1e-9);
  EXPECT_NEAR(m->body_pos[3 * torso1 + 1], -1, 1e-9);
  EXPECT_NEAR(m->body_pos[3 * torso1 + 2], 0.3, 1e-9);
  EXPECT_NEAR(m->body_quat[4 * torso1 + 0], std::cos(std::numbers::pi / 4), 1e-9);
  EXPECT_NEAR(m->body_quat[4 * torso1 + 3], std::sin(std::numbers::pi / 4), 1e-9);
}

TEST(SceneTest, IncludesAndAssetFilesResolveAgainstTheRobotModelsFolder) {
  TempDir dir;
  fs::create_directories(dir.path() / "textures");
  const cv::Mat texture(8, 8, CV_8UC3, cv::Scalar(20, 40, 200));
  ASSERT_TRUE(cv::imwrite((dir.path() / "textures" / "skin.png").string(), texture));
  dir.write("parts.xml", R"(<mujoco><actuator><motor name="HeadYaw" joint="HeadYaw"/></actuator></mujoco>)");
  SceneSpec spec;
  spec.robotModel = dir.write("robot.xml", R"(<mujoco>
    <compiler texturedir="textures"/>
    <asset><texture name="skin" type="2d" file="skin.png"/><material name="skin" texture="skin"/></asset>
    <worldbody><body name="torso" pos="0 0 0.3"><freejoint name="root"/>
      <geom type="box" size="0.05 0.05 0.05" material="skin"/>
      <body name="Head" pos="0 0 0.1"><joint name="HeadYaw" axis="0 0 1"/><geom type="sphere" size="0.03"/></body>
    </body></worldbody>
    <include file="parts.xml"/>
  </mujoco>)");
  const fs::path cwd = fs::current_path();
  fs::current_path(fs::temp_directory_path());  // not the robot's folder
  mjModel* m = nullptr;
  EXPECT_NO_THROW(m = compileScene(spec));
  fs::current_path(cwd);
  ASSERT_NE(m, nullptr);
  EXPECT_GE(id(m, mjOBJ_ACTUATOR, "r0/HeadYaw"), 0);
  EXPECT_GE(id(m, mjOBJ_TEXTURE, "skin"), 0);
  mj_deleteModel(m);
}

TEST(SceneTest, BadRobotModelsNameTheFile) {
  TempDir dir;
  SceneSpec spec;
  auto expectError = [&](const std::string& path, const std::string& part) {
    spec.robotModel = path;
    try {
      mjModel* m = compileScene(spec);
      mj_deleteModel(m);
      ADD_FAILURE() << "no error for " << path;
    } catch (const Error& e) {
      EXPECT_EQ(e.where(), path);
      EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
      EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
    }
  };
  expectError(dir.write("broken.xml", "<mujoco><worldbody><body name='torso'>"), "malformed XML");
  expectError((fs::temp_directory_path() / "no_such_robot_model.xml").string(), "file not found");
  expectError(dir.write("notmujoco.xml", "<robot/>"), "<mujoco>");
  expectError(dir.write("nobody.xml", "<mujoco><worldbody/></mujoco>"), "no body");
  // Well-formed XML that MuJoCo rejects.
  expectError(dir.write("bad_attr.xml",
                        "<mujoco><worldbody><body name='torso'><freejoint/><geom type='box' size='x y z'/></body>"
                        "</worldbody></mujoco>"),
              "MuJoCo");
}

TEST(SceneTest, BallRollsWithoutSlippingAndADroppedOneRests) {
  SceneSpec spec;
  spec.robots.clear();
  spec.balls = {Eigen::Vector3d(-3, 0, kBallRadius), Eigen::Vector3d(0, 2, 0.3)};
  ModelPtr model(compileScene(spec));
  mjModel* m = model.m;
  mjData* d = mj_makeData(m);
  mj_forward(m, d);
  d->qvel[0] = 3.0;                // rolling at 3 m/s ...
  d->qvel[4] = 3.0 / kBallRadius;  // ... without slipping
  for (int i = 0; i < static_cast<int>(1.0 / m->opt.timestep); ++i) mj_step(m, d);
  // The scene's carpet has sliding friction only: the ball keeps rolling without slipping
  // (its rolling resistance is World's, world_test RolledBallStops).
  EXPECT_NEAR(d->qpos[0] + 3, 3.0, 0.05);
  EXPECT_NEAR(d->qvel[0], 3.0, 0.02);
  // The dropped ball rests on the carpet.
  EXPECT_NEAR(d->qpos[7 + 2], kBallRadius, 0.002);
  EXPECT_LT(std::abs(d->qvel[6 + 2]), 1e-3);
  mj_deleteData(d);
}

}  // namespace
