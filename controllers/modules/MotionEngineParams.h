#pragma once
// The motion engine's parameters as config/parameters/MotionEngine.json holds them
// (robot/Parameters.h). Ranges are what the code can run with, not what is tuned: they catch a
// typo (a speed of 40 m/s, a negative time), the tuning itself is the file's job. GetUp's
// `front`/`back` key frames are for experiments in code and are not in the file.
#include "controllers/GetUp.h"
#include "controllers/InertialOdometry.h"
#include "controllers/Kick.h"
#include "controllers/MotionEngine.h"
#include "controllers/Walk.h"

namespace nao {

template <class V>
void describe(V& v, InertialOdometry::Params& p) {
  v("processVelocity", p.processVelocity, 0.0, 1.0);
  v("processBias", p.processBias, 0.0, 1.0);
  v("measurement", p.measurement, 1e-6, 1.0);
  v("gate", p.gate, 0.1, 100.0);
  v("initialBias", p.initialBias, 0.0, 10.0);
}

template <class V>
void describe(V& v, Walk::Params& p) {
  v("stepDuration", p.stepDuration, 0.05, 2.0);
  v("stepHeight", p.stepHeight, 0.0, 0.1);
  v("torsoHeight", p.torsoHeight, 0.1, 0.35);
  v("torsoPitch", p.torsoPitch, -0.5, 0.5);
  v("footSpacing", p.footSpacing, 0.05, 0.3);
  v("zmpX", p.zmpX, -0.1, 0.1);
  v("zmpYInside", p.zmpYInside, -0.05, 0.05);
  v("zmpTravelX", p.zmpTravelX, 0.0, 1.0);
  v("zmpTravelY", p.zmpTravelY, 0.0, 1.0);
  v("maxZmpTravelX", p.maxZmpTravelX, 0.0, 0.2);
  v("maxZmpTravelY", p.maxZmpTravelY, 0.0, 0.1);
  v("maxForward", p.maxForward, 0.0, 1.0);
  v("maxBackward", p.maxBackward, 0.0, 1.0);
  v("maxSide", p.maxSide, 0.0, 1.0);
  v("maxTurn", p.maxTurn, 0.0, 5.0);
  v("accelForward", p.accelForward, 0.0, 10.0);
  v("accelSide", p.accelSide, 0.0, 10.0);
  v("accelTurn", p.accelTurn, 0.0, 50.0);
  v("maxStepOutward", p.maxStepOutward, 0.0, 0.3);
  v("maxStepInward", p.maxStepInward, 0.0, 0.1);
  v("maxStepForward", p.maxStepForward, 0.0, 0.3);
  v("maxStepBackward", p.maxStepBackward, 0.0, 0.3);
  v("startDuration", p.startDuration, 0.0, 2.0);
  v("gyroPitchGain", p.gyroPitchGain, -2.0, 2.0);
  v("gyroRollGain", p.gyroRollGain, -2.0, 2.0);
  v("adjustUntilPhase", p.adjustUntilPhase, 0.0, 1.0);
  v("servoGain", p.servoGain, 1.0, 1000.0);
  v("headingGain", p.headingGain, 0.0, 1.0);
  v("maxHeadingCorrection", p.maxHeadingCorrection, 0.0, 1.0);
  v("gyroOdometry", p.gyroOdometry);
  v("odometryLoadExponent", p.odometryLoadExponent, 0.0, 10.0);
  v("odometryScale", p.odometryScale, 0.5, 1.5);
  v("kinematicOdometryScale", p.kinematicOdometryScale, 0.5, 1.5);
  v("twistAboutContact", p.twistAboutContact);
  v("inertialOdometry", p.inertialOdometry);
  v("inertial", p.inertial);
  v("odometrySwingAfter", p.odometrySwingAfter, 0.0, 1.0);
  v("sagCompensation", p.sagCompensation, 0.0, 2.0);
  v("leadTime", p.leadTime, 0.0, 0.1);
  v("supportLeadTime", p.supportLeadTime, 0.0, 0.1);
  v("swingTiltCompensation", p.swingTiltCompensation, 0.0, 2.0);
  v("landingCorrectionDecay", p.landingCorrectionDecay, 1e-3, 10.0);
  v("levelSoles", p.levelSoles);
  v("levelTime", p.levelTime, 1e-3, 10.0);
  v("maxLevelCorrection", p.maxLevelCorrection, 0.0, 0.5);
  v("maxLevelRate", p.maxLevelRate, 0.0, 10.0);
}

template <class V>
void describe(V& v, Kick::Params& p) {
  v("torsoHeight", p.torsoHeight, 0.1, 0.35);
  v("footSpacing", p.footSpacing, 0.05, 0.3);
  v("shiftTime", p.shiftTime, 0.01, 5.0);
  v("liftTime", p.liftTime, 0.01, 5.0);
  v("strikeTime", p.strikeTime, 0.01, 5.0);
  v("holdTime", p.holdTime, 0.0, 5.0);
  v("retractTime", p.retractTime, 0.01, 5.0);
  v("lowerTime", p.lowerTime, 0.01, 5.0);
  v("returnTime", p.returnTime, 0.01, 5.0);
  v("comInward", p.comInward, -0.1, 0.1);
  v("comForward", p.comForward, -0.1, 0.1);
  v("liftHeight", p.liftHeight, 0.0, 0.2);
  v("windUp", p.windUp, 0.0, 0.2);
  v("strikeHeight", p.strikeHeight, 0.0, 0.2);
  v("followThrough", p.followThrough, 0.0, 0.3);
  v("strikeReach", p.strikeReach, 0.0, 0.3);
  v("windUpPitch", p.windUpPitch, -1.0, 1.0);
  v("strikePitch", p.strikePitch, -1.0, 1.0);
  v("ballGap", p.ballGap, 0.0, 0.2);
  v("maxFootYaw", p.maxFootYaw, 0.0, 1.0);
  v("yawBias", p.yawBias, -0.5, 0.5);
  v("strikeInward", p.strikeInward, -0.1, 0.1);
  v("gyroPitchGain", p.gyroPitchGain, -2.0, 2.0);
  v("gyroRollGain", p.gyroRollGain, -2.0, 2.0);
  v("servoGain", p.servoGain, 1.0, 1000.0);
}

template <class V>
void describe(V& v, GetUp::Squat& p) {
  v("pitch", p.pitch, -1.6, 1.6);
  v("height", p.height, 0.0, 0.35);
  v("width", p.width, 0.0, 0.3);
  v("yaw", p.yaw, -1.6, 1.6);
  v("comX", p.comX, -0.1, 0.1);
}

template <class V>
void describe(V& v, GetUp::Params& p) {
  v("frontSquat", p.frontSquat);
  v("backSquat", p.backSquat);
  v("riseTime", p.riseTime, 0.05, 10.0);
  v("torsoHeight", p.torsoHeight, 0.1, 0.35);
  v("footSpacing", p.footSpacing, 0.05, 0.3);
  v("gyroGain", p.gyroGain, -2.0, 2.0);
  v("settleTime", p.settleTime, 0.0, 10.0);
  v("uprightTilt", p.uprightTilt, 0.0, 1.6);
  v("settleMaxTime", p.settleMaxTime, 0.0, 30.0);
  v("squatMaxLean", p.squatMaxLean, 0.0, 3.2);
  v("riseMaxTilt", p.riseMaxTilt, 0.0, 3.2);
  v("backRollsOver", p.backRollsOver);
}

template <class V>
void describe(V& v, MotionEngine::Params& p) {
  v("walk", p.walk);
  v("kick", p.kick);
  v("getUp", p.getUp);
  v("transitionTime", p.transitionTime, 0.01, 10.0);
  v("sitDownTime", p.sitDownTime, 0.01, 10.0);
  v("playDeadStiffness", p.playDeadStiffness, 0.0, 1.0);
  v("walkToGain", p.walkToGain, 0.0, 20.0);
  v("walkToTurnGain", p.walkToTurnGain, 0.0, 20.0);
  v("walkToMaxTurn", p.walkToMaxTurn, 0.0, 5.0);
  v("walkToDeceleration", p.walkToDeceleration, 0.01, 10.0);
  v("walkToNearDistance", p.walkToNearDistance, 0.0, 2.0);
  v("walkToNearSpeed", p.walkToNearSpeed, 0.0, 1.0);
  v("walkToPositionTolerance", p.walkToPositionTolerance, 1e-4, 0.5);
  v("walkToAngleTolerance", p.walkToAngleTolerance, 1e-4, 1.0);
  v("walkToResumePosition", p.walkToResumePosition, 1.0, 100.0);
  v("walkToResumeAngle", p.walkToResumeAngle, 1.0, 100.0);
  v("kickPositionTolerance", p.kickPositionTolerance, 1e-4, 0.5);
  v("kickAngleTolerance", p.kickAngleTolerance, 1e-4, 1.0);
  v("armRaiseTime", p.armRaiseTime, 0.1, 5.0);
}

}  // namespace nao
