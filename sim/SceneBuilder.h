#pragma once
// Assembles the simulated world as one MJCF document: the SPL field generated from
// FieldDimensions (carpet, lines, centre circle, marks, goals with nets), the hall around it,
// a sun light, N copies of the NAO model (every name prefixed "r<i>/") and M balls.
//
// Names in the scene (besides the robots' prefixed ones):
//   balls:  body, free joint and sphere geom "ball<j>" (the sphere is the body's first geom);
//           visual-only patches "ball<j>/patch<k>"
//   field:  geoms "field/carpet" (the collision plane, z = 0); paint as visual-only planes 0.5 mm
//           above it, 50 mm wide: "field/line/<FieldLine name>" (lengthened by half a line width
//           at both ends), "field/circle/<k>" (96 chords), "field/center_mark" (a 100 mm dash
//           along x across the halfway line), "field/penalty_cross/<k>/x|y" (100 mm crosses)
//   hall:   "hall/floor" (grey, visual only) and "hall/wall_*" 3 m beyond the carpet; a venue's
//           look (SceneSpec::venue, sim/VenueScene.h) adds "hall/window<k>", "hall/door<k>",
//           "hall/board<k>/...", "hall/table<k>/...", "hall/person<k>/...", "hall/floor_line<k>"
//           and draws each line as pieces "field/line/<name>/<k>"
//   decor:  the static body holding the paint and the hall's visual-only geoms; its geom list
//           (body_geomnum) is emptied after compiling, so collision detection never visits them
//   goals:  geoms "goal/own/..." (x < 0) and "goal/opp/..." (x > 0)
//   light:  "sun" (directional; CameraRenderer sets it from a Lighting before each frame)
// Rendering shows geom groups 0-2 only; groups 3-5 are hidden (for collision-only geoms).
//
// Robot copies: the robot file's compiler, option, size, default, asset and custom sections are
// merged once (asset file paths made absolute, <include> expanded); its worldbody bodies,
// contact, equality, tendon, actuator and sensor sections are copied per robot with every name
// and name reference prefixed (class, material, texture, mesh and hfield names stay shared).
// Worldbody geoms/lights of a stand-alone robot file and keyframes are dropped. The body
// "torso" (else the first top-level body) is put at (x, y, its own z), turned by theta; its
// orientation in the file must be a quat (or none).
// Physics: the spec's timestep, the implicit integrator (stable with stiff servo PD).
#include <string>

#include "sim/SceneSpec.h"

struct mjModel_;

namespace nao::sim {

inline constexpr double kBallRadius = 0.05;  // m (SPL: 100 mm diameter)
inline constexpr double kBallMass = 0.044;   // kg

// "r<i>/": the prefix of every name of robot i in the scene.
std::string robotPrefix(int robot);

// The robot MJCF the spec names (spec.robotModel, or models/nao_v6.xml under dataPath()).
std::string robotModelPath(const SceneSpec& spec);

// The scene as MJCF text. Throws nao::Error(robot model path, reason) when the robot MJCF is
// missing or malformed, nao::Error("SceneSpec", reason) for an implausible spec.
std::string buildSceneXml(const SceneSpec& spec);

// buildSceneXml compiled by MuJoCo; the caller owns the model (mj_deleteModel). Throws
// nao::Error(robot model path, "MuJoCo: ...") on a compile error (one line).
mjModel_* compileScene(const SceneSpec& spec);

}  // namespace nao::sim
