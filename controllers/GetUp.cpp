#include "controllers/GetUp.h"

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <utility>

#include "controllers/Kinematics.h"
#include "robot/ForwardKinematics.h"
#include "robot/RobotDimensions.h"

namespace nao {

namespace {

constexpr double kDeg = M_PI / 180;
// After a roll, the torso's x axis this far below the horizontal (sine) counts as lying on the front.
constexpr double kFrontTipped = 0.3;

double smoothstep(double t) {
  t = std::clamp(t, 0.0, 1.0);
  return t * t * (3 - 2 * t);
}

double tiltOf(const SensorFrame& frame) {
  return std::acos(std::clamp(std::cos(frame.inertial.angle.x()) * std::cos(frame.inertial.angle.y()), -1.0, 1.0));
}

// The torso's forward lean (rad) in its sagittal plane: 0 upright, pi/2 lying on the face,
// beyond that head down (hips up); -pi/2 lying on the back. The IMU's pitch alone folds back
// beyond 90 deg (the roll then reads ~180 deg).
double forwardLean(const SensorFrame& frame) {
  // The torso's z axis has the upward component cos(roll) cos(pitch), its x axis -sin(pitch):
  // leaning forward by `lean`, z up = cos(lean), x up = -sin(lean).
  const double roll = frame.inertial.angle.x(), pitch = frame.inertial.angle.y();
  double lean = std::atan2(std::sin(pitch), std::cos(roll) * std::cos(pitch));
  if (lean < -M_PI / 2 - 0.3) lean += 2 * M_PI;
  return lean;
}

// A symmetric frame from the angles (deg) that matter; left values, the right side mirrored.
struct Pose {
  double headPitch = 0;
  double shoulderPitch = 90, shoulderRoll = 10, elbowYaw = -90, elbowRoll = -5, wristYaw = 0;
  double hipYawPitch = 0, hipRoll = 0, hipPitch = 0, knee = 0, anklePitch = 0, ankleRoll = 0;
};

void setArms(JointArray& j, const Pose& p) {
  j[HeadYaw] = 0;
  j[HeadPitch] = p.headPitch * kDeg;
  j[LShoulderPitch] = j[RShoulderPitch] = p.shoulderPitch * kDeg;
  j[LShoulderRoll] = p.shoulderRoll * kDeg;
  j[RShoulderRoll] = -p.shoulderRoll * kDeg;
  j[LElbowYaw] = p.elbowYaw * kDeg;
  j[RElbowYaw] = -p.elbowYaw * kDeg;
  j[LElbowRoll] = p.elbowRoll * kDeg;
  j[RElbowRoll] = -p.elbowRoll * kDeg;
  j[LWristYaw] = p.wristYaw * kDeg;
  j[RWristYaw] = -p.wristYaw * kDeg;
}

void clampAll(JointArray& j) {
  for (int i = 0; i < NumJoints; ++i) j[i] = clampToLimits(static_cast<Joint>(i), j[i]);
}

GetUp::KeyFrame frame(double duration, double stiffness, const Pose& p) {
  GetUp::KeyFrame k;
  k.duration = duration;
  k.stiffness = stiffness;
  JointArray& j = k.angles;
  setArms(j, p);
  j[LHipYawPitch] = p.hipYawPitch * kDeg;
  j[LHipRoll] = p.hipRoll * kDeg;
  j[RHipRoll] = -p.hipRoll * kDeg;
  j[LHipPitch] = j[RHipPitch] = p.hipPitch * kDeg;
  j[LKneePitch] = j[RKneePitch] = p.knee * kDeg;
  j[LAnklePitch] = j[RAnklePitch] = p.anklePitch * kDeg;
  j[LAnkleRoll] = p.ankleRoll * kDeg;
  j[RAnkleRoll] = -p.ankleRoll * kDeg;
  clampAll(j);
  return k;
}

// The squat's legs with these arms.
GetUp::KeyFrame squatFrame(const GetUp::Squat& squat, double duration, const Pose& arms) {
  GetUp::KeyFrame k;
  k.duration = duration;
  k.angles = GetUp::squatPosture(squat);
  setArms(k.angles, arms);
  clampAll(k.angles);
  return k;
}

}  // namespace

void GetUp::risePosture(const Params& p, const Squat& q, double s, JointArray& joints) {
  const double pitch = (1 - s) * q.pitch;
  const double height = q.height + s * (p.torsoHeight - q.height);
  const double width = q.width + s * (p.footSpacing / 2 - q.width);
  const double yaw = (1 - s) * q.yaw;
  const double comX = (1 - s) * q.comX + s * 0.005;
  Eigen::Isometry3d l = Eigen::Isometry3d::Identity(), r = Eigen::Isometry3d::Identity();
  l.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  r.linear() = Eigen::AngleAxisd(-yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  l.translation() = Eigen::Vector3d(0, width, 0);
  r.translation() = Eigen::Vector3d(0, -width, 0);
  comIK(l, r, Eigen::Vector2d(comX, 0), height, pitch, 0, joints);
}

JointArray GetUp::squatPosture(const Squat& squat) {
  JointArray j{};
  setArms(j, Pose{});
  risePosture(Params{}, squat, 0, j);
  clampAll(j);
  return j;
}

std::vector<GetUp::KeyFrame> GetUp::frontFrames(const Params& params) {
  // Lying on the face: the arms go overhead along the floor (out to the side first: swung
  // through the front they would hit the floor), the legs straighten and spread. Then the hips
  // flex into a wide-legged pike ("downward dog"): straight arms in line with the torso prop the
  // head off the floor, the soles are flat (whole-body IK: the leg angles that keep both soles
  // flat at the torso's expected lean), most of the weight is on the feet. From there the torso
  // rises, the hips sink and the hands come back while the centre of mass moves over the feet
  // (lean 120 -> 90 -> 80 -> 70 -> 55 deg, each posture from comIK with the COM as close to the
  // soles as the joint limits allow) into the frog squat. The arms carry load only as straight
  // struts: weak shoulder motors (~2 Nm) cannot lift the chest, so nothing asks them to.
  // Angles in deg, left side (the right mirrored).
  std::vector<KeyFrame> frames;
  Pose p;
  p.headPitch = -20;
  p.elbowRoll = -3;
  frames.push_back(frame(0.30, 1, p));  // flat: arms along the body, legs straight
  p.shoulderRoll = 76;
  frames.push_back(frame(0.30, 1, p));  // arms out to the side, along the floor
  p.shoulderPitch = -90;
  frames.push_back(frame(0.25, 1, p));  // turned about their own axis
  p.shoulderRoll = 10;
  p.hipRoll = 40;
  frames.push_back(frame(0.35, 1, p));  // overhead; legs spread
  // IK postures: lean (deg), hip height and half width of the feet (m), toes out (deg), COM
  // ahead of the soles' midpoint (m), then ShoulderPitch (deg; about 90 - lean = arms vertical).
  struct Stage {
    double duration, lean, height, width, yaw, comX, shoulderPitch;
  };
  for (const Stage& st : {Stage{0.8, 120, 0.22, 0.15, 20, 0.07, -90}, Stage{0.5, 120, 0.24, 0.15, 20, 0.07, -90},
                          Stage{0.6, 90, 0.22, 0.15, 20, 0.07, -60}, Stage{0.5, 80, 0.19, 0.15, 40, 0.05, -10},
                          Stage{0.5, 70, 0.19, 0.15, 40, 0.03, 10}, Stage{0.5, 55, 0.16, 0.13, 40, 0.02, 30}}) {
    Squat q;
    q.pitch = st.lean * kDeg;
    q.height = st.height;
    q.width = st.width;
    q.yaw = st.yaw * kDeg;
    q.comX = st.comX;
    Pose arms;
    arms.headPitch = -20;
    arms.shoulderPitch = st.shoulderPitch;
    arms.elbowRoll = -3;
    frames.push_back(squatFrame(q, st.duration, arms));
  }
  Pose arms;
  arms.headPitch = -20;
  arms.shoulderPitch = 30;
  arms.elbowRoll = -3;
  KeyFrame squat = squatFrame(params.frontSquat, 0.50, arms);
  // Early abort: not on the feet with the torso leaning less than ~75 deg by now, the rise
  // cannot work; failing here lets the motion engine start the next attempt at once.
  squat.pitchMin = -0.3;
  squat.pitchMax = params.squatMaxLean;
  squat.maxWait = 0.6;
  frames.push_back(squat);
  return frames;
}


std::vector<GetUp::KeyFrame> GetUp::backFrames(const Params& params) {
  (void)params;
  // Onto the front (see GetUp.h): first onto the left side -- three frames from an earlier
  // cross-entropy search: the left leg and arm swing across the body while the right arm
  // reaches over the head. Angles in deg, clamped to the joint limits.
  std::vector<KeyFrame> frames;
  const auto add = [&frames](double duration, std::initializer_list<std::pair<Joint, double>> angles) {
    KeyFrame k = frame(duration, 1, Pose{});
    for (const auto& [joint, deg] : angles) k.angles[joint] = clampToLimits(joint, deg * kDeg);
    frames.push_back(k);
  };
  add(0.23, {
      {LShoulderPitch, 13.0}, {LShoulderRoll, -26.3}, {LElbowRoll, -57.4}, {RShoulderPitch, -88.9},
      {RShoulderRoll, -105.5}, {RElbowRoll, 21.8}, {LHipYawPitch, -9.2}, {LHipRoll, -25.9}, {RHipRoll, 45.8},
      {LHipPitch, -61.8}, {RHipPitch, -140.3}, {LKneePitch, 90.7}, {RKneePitch, 4.4}});
  add(0.51, {
      {LShoulderPitch, -18.7}, {LShoulderRoll, -8.9}, {LElbowRoll, -73.6}, {RShoulderPitch, -96.5},
      {RShoulderRoll, -83.6}, {RElbowRoll, 9.4}, {LHipYawPitch, -32.0}, {LHipRoll, -45.9}, {RHipRoll, -125.3},
      {LHipPitch, -74.3}, {RHipPitch, 25.9}, {LKneePitch, 53.7}, {RKneePitch, 77.7}});
  add(0.45, {
      {LShoulderPitch, -4.6}, {LShoulderRoll, -2.9}, {LElbowRoll, -22.1}, {RShoulderPitch, -58.9},
      {RShoulderRoll, -24.0}, {RElbowRoll, 17.5}, {LHipYawPitch, -24.0}, {LHipRoll, -13.7}, {RHipRoll, -70.0},
      {LHipPitch, -30.7}, {RHipPitch, 32.5}, {LKneePitch, 22.7}, {RKneePitch, 35.7}});
  // On the left side now. Slowly (a fast swing would roll the body back): the upper leg and
  // arm forward, then both legs piked forward, then two frames found by a cross-entropy search
  // (fitness: lying on the face once the limbs straighten, over 4 then 8 trials per candidate,
  // half of them randomised robots) that tip the body over onto its face; then arms along the
  // body, legs straight, and the front get-up follows.
  add(0.9, {
      {LShoulderPitch, -4.6}, {LShoulderRoll, -2.9}, {LElbowRoll, -22.1}, {RShoulderPitch, 20.0},
      {RShoulderRoll, 18.0}, {RElbowRoll, 5.0}, {LHipYawPitch, -24.0}, {LHipRoll, -13.7}, {RHipRoll, 21.0},
      {LHipPitch, -30.7}, {RHipPitch, -70.0}, {LKneePitch, 22.7}, {RKneePitch, 0.0}});
  add(0.8, {
      {LShoulderPitch, -4.6}, {LShoulderRoll, -2.9}, {LElbowRoll, -5.0}, {RShoulderPitch, 20.0},
      {RShoulderRoll, 18.0}, {RElbowRoll, 5.0}, {LHipYawPitch, 0.0}, {LHipRoll, -13.7}, {RHipRoll, 21.0},
      {LHipPitch, -88.0}, {RHipPitch, -88.0}, {LKneePitch, 0.0}, {RKneePitch, 0.0}});
  add(1.14, {
      {LShoulderPitch, -1.4}, {LShoulderRoll, -27.5}, {LElbowRoll, -15.0}, {RShoulderPitch, 58.2},
      {RShoulderRoll, -14.5}, {RElbowRoll, -9.1}, {LHipYawPitch, 53.3}, {LHipRoll, -7.4}, {RHipRoll, -45.9},
      {LHipPitch, -132.6}, {RHipPitch, -143.3}, {LKneePitch, 5.6}, {RKneePitch, -1.1}});
  add(1.04, {
      {LShoulderPitch, -76.7}, {LShoulderRoll, -67.4}, {LElbowRoll, -77.7}, {RShoulderPitch, 1.6},
      {RShoulderRoll, -58.5}, {RElbowRoll, -30.2}, {LHipYawPitch, -32.7}, {LHipRoll, 8.1}, {RHipRoll, 86.7},
      {LHipPitch, 3.0}, {RHipPitch, -4.6}, {LKneePitch, 49.5}, {RKneePitch, -19.7}});
  Pose flat;
  flat.headPitch = -20;
  flat.elbowRoll = -3;
  frames.push_back(frame(0.4, 1, flat));
  frames.push_back(frame(0.5, 1, flat));
  return frames;
}

std::vector<GetUp::KeyFrame> GetUp::sideRollFrames(bool lyingOnLeft) {
  // Onto the back: the upper arm swings over the body, the upper leg bends across.
  Pose p;
  p.shoulderPitch = 0;
  p.shoulderRoll = 0;
  GetUp::KeyFrame k = frame(0.6, 1, p);
  if (lyingOnLeft) {
    k.angles[RShoulderPitch] = -0.5;
    k.angles[RHipPitch] = -0.8;
    k.angles[RKneePitch] = 1.2;
  } else {
    k.angles[LShoulderPitch] = -0.5;
    k.angles[LHipPitch] = -0.8;
    k.angles[LKneePitch] = 1.2;
  }
  return {k, frame(0.6, 0.6, Pose{})};
}

void GetUp::setFrames(FallDirection lying, const std::vector<KeyFrame>& frames) {
  (lying == FallDirection::Back ? params_.back : params_.front) = frames;
}

std::vector<GetUp::KeyFrame> GetUp::framesFor(bool back) const {
  if (back) return params_.back.empty() ? backFrames(params_) : params_.back;
  return params_.front.empty() ? frontFrames(params_) : params_.front;
}

void GetUp::startFrames(const SensorFrame& frame, const std::vector<KeyFrame>& frames, bool back) {
  squat_ = back ? params_.backSquat : params_.frontSquat;
  frames_ = frames;
  frame_ = 0;
  frameStart_ = frame.time;
  from_ = frame.joints.position;
  phase_ = Phase::Frames;
}

const char* GetUp::phase() const {
  if (failed_) return "failed";
  if (done_) return "done";
  switch (phase_) {
    case Phase::Frames: return "frames";
    case Phase::Rise: return "rise";
    case Phase::Settle: return "settle";
  }
  return "?";
}

void GetUp::start(const SensorFrame& frame, FallDirection lying, const JointArray& stand) {
  // The side the robot lies on now, from the IMU: the fall detector's direction dates from the
  // fall, and a failed attempt may have rolled the robot since.
  if (tiltOf(frame) > 0.8) lying = lyingDirection(frame.inertial.angle.x(), frame.inertial.angle.y());
  stand_ = stand;
  done_ = false;
  failed_ = false;
  gyro_.setZero();
  rollingFirst_ = lying == FallDirection::Left || lying == FallDirection::Right ||
                  (lying == FallDirection::Back && params_.backRollsOver);
  sequences_ = 0;
  if (lying == FallDirection::Left || lying == FallDirection::Right)
    startFrames(frame, sideRollFrames(lying == FallDirection::Left), true);
  else startFrames(frame, framesFor(lying == FallDirection::Back), lying == FallDirection::Back);
}

JointRequest GetUp::update(const SensorFrame& frame) {
  JointRequest out;
  out.stiffness.fill(1.0);
  if (done_ || failed_) {
    out.position = frame.joints.position;
    return out;
  }
  const double pitch = frame.inertial.angle.y();
  if (phase_ == Phase::Frames) {
    const KeyFrame& k = frames_[frame_];
    const double t = frame.time - frameStart_;
    const double s = smoothstep(t / k.duration);
    for (int j = 0; j < NumJoints; ++j) out.position[j] = from_[j] + s * (k.angles[j] - from_[j]);
    out.stiffness.fill(k.stiffness);
    if (t < k.duration) return out;
    const double lean = forwardLean(frame);
    if (lean < k.pitchMin || lean > k.pitchMax) {
      if (t > k.duration + k.maxWait) failed_ = true;
      return out;
    }
    from_ = k.angles;
    frameStart_ = frame.time;
    if (++frame_ < frames_.size()) return out;
    if (rollingFirst_) {
      // A roll has ended (from the side onto the back, from the back onto the front); the
      // sequence for the side the IMU says follows -- a few times at most.
      if (++sequences_ > 4) {
        failed_ = true;
        return out;
      }
      FallDirection lying = lyingDirection(frame.inertial.angle.x(), pitch);
      // Tipped past the side towards the face (the torso's x axis well below the horizontal):
      // the front get-up copes with that.
      if (-std::sin(pitch) < -kFrontTipped) lying = FallDirection::Front;
      if (lying == FallDirection::Left || lying == FallDirection::Right) {
        startFrames(frame, sideRollFrames(lying == FallDirection::Left), true);
      } else {
        rollingFirst_ = lying == FallDirection::Back && params_.backRollsOver;
        startFrames(frame, framesFor(lying == FallDirection::Back), lying == FallDirection::Back);
      }
      return out;
    }
    phase_ = Phase::Rise;
    phaseStart_ = frame.time;
    riseFrom_ = k.angles;
    return out;
  }
  gyro_ = 0.7 * gyro_ + 0.3 * frame.inertial.gyroscope.head<2>();
  if (phase_ == Phase::Rise) {
    // Feet flat, the COM above their midpoint, the torso from the squat's height and pitch
    // to upright; the arms and head from the squat's to the stand's.
    const double s = smoothstep((frame.time - phaseStart_) / params_.riseTime);
    if (tiltOf(frame) > params_.riseMaxTilt) {  // toppling: give up early, try again
      failed_ = true;
      out.position = frame.joints.position;
      return out;
    }
    out.position = riseFrom_;
    risePosture(params_, squat_, s, out.position);
    for (int j : {HeadYaw, HeadPitch, LShoulderPitch, LShoulderRoll, LElbowYaw, LElbowRoll, LWristYaw, RShoulderPitch,
                  RShoulderRoll, RElbowYaw, RElbowRoll, RWristYaw})
      out.position[j] = riseFrom_[j] + s * (stand_[j] - riseFrom_[j]);
    if (s >= 1) {
      phase_ = Phase::Settle;
      phaseStart_ = frame.time;
      settleFrom_ = out.position;
      uprightSince_ = -1;
    }
  } else {
    // Settling into the stand; done once the IMU has said "upright" for settleTime.
    const double s = smoothstep((frame.time - phaseStart_) / 0.3);
    for (int j = 0; j < NumJoints; ++j) out.position[j] = settleFrom_[j] + s * (stand_[j] - settleFrom_[j]);
    const double tilt = tiltOf(frame);
    if (tilt < params_.uprightTilt) {
      if (uprightSince_ < 0) uprightSince_ = frame.time;
      if (frame.time - uprightSince_ >= params_.settleTime) done_ = true;
    } else {
      uprightSince_ = -1;
    }
    if (!done_ && frame.time - phaseStart_ > params_.settleMaxTime) failed_ = true;
  }
  for (Joint a : {LAnklePitch, RAnklePitch}) out.position[a] += params_.gyroGain * gyro_.y();
  for (Joint a : {LAnkleRoll, RAnkleRoll}) out.position[a] += params_.gyroGain * gyro_.x();
  return out;
}

}  // namespace nao
