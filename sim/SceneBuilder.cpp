#include "sim/SceneBuilder.h"

#include <mujoco/mujoco.h>
#include <tinyxml2.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>
#include <numbers>
#include <random>
#include <sstream>
#include <vector>

#include "perception/FieldDimensions.h"
#include "sim/Mjcf.h"
#include "sim/MujocoMessages.h"
#include "sim/VenueScene.h"
#include "robot/Error.h"
#include "robot/Paths.h"

namespace nao::sim {

namespace {

namespace fs = std::filesystem;
using tinyxml2::XMLDocument;
using tinyxml2::XMLElement;
using tinyxml2::XMLNode;
using mjcf::add;
using mjcf::num;
using mjcf::vec;
using mjcf::yawQuat;

// Paint is a finite plane 0.5 mm above the carpet (clear of z-fighting). Planes, unlike thin
// boxes, neither shadow themselves ("acne") nor speckle the carpet along their edges with
// shadow-map texels, yet they receive shadows.
constexpr double kLineTop = 0.0005;      // m
constexpr int kCircleSegments = 96;      // centre circle chords: 0.4 mm from the true arc
constexpr double kFloorDrop = 0.004;     // m: the hall floor below the carpet (visual only)
constexpr double kHallMargin = 3.0;      // m from the carpet edge to the hall walls
constexpr double kWallHeight = 2.5;      // m
constexpr double kNetThickness = 0.004;  // m
constexpr double kBarRadius = 0.0125;    // m: the net's support bars
constexpr double kPatchRadius = 0.016;   // m: the ball's black patches (12, like a soccer ball)
constexpr double kPatchDepth = 0.004;    // m: half-thickness of a patch ellipsoid
constexpr double kPatchRise = 0.0007;    // m: how far a patch stands out of the sphere
// The foam ball on turf: a dropped ball comes to rest without bouncing (the turf's pile absorbs
// the impact). Ball-carpet is an explicit contact pair (it overrides the generated one):
// condim 3 (sliding friction: the ball rolls without slipping), critically damped. Its rolling
// resistance is World's (a constant deceleration, the same in every direction: MuJoCo's
// rolling friction under the pyramidal cone was 1.4 times stronger along the field's axes than
// along its diagonals).
constexpr const char* kBallFriction = "0.8 0.005 0.0075";
constexpr const char* kBallCarpetFriction = "1 1";
constexpr const char* kBallCarpetSolref = "0.02 1";
// Against hard things (the robot's plastic feet and legs, goal posts) the foam ball rebounds
// with a coefficient of restitution of about 0.5: an underdamped contact (time constant,
// damping ratio < 1), measured by tests/world_test (BallReboundsOffAGoalPost). The ball's geom
// has priority 2, above the soles' 1, so its solref/solimp/friction govern those contacts.
constexpr const char* kBallSolref = "0.02 0.28";
constexpr const char* kBallSolimp = "0.9 0.95 0.001";

// Name-reference attributes of MJCF elements that point at per-robot objects. Asset and
// default-class references (class, childclass, material, texture, mesh, hfield) stay shared.
constexpr std::array<const char*, 25> kNameAttributes = {
    "name",   "joint",   "joint1",  "joint2",   "jointinparent", "body",       "body1", "body2", "site",
    "site1",  "site2",   "refsite", "sidesite", "cranksite",     "slidersite", "geom",  "geom1", "geom2",
    "tendon", "tendon1", "tendon2", "actuator", "objname",       "refname",    "target"};

std::string oneLine(std::string text) {
  for (char& c : text)
    if (c == '\n' || c == '\r') c = ' ';
  while (!text.empty() && text.back() == ' ') text.pop_back();
  return text;
}

// ---------------------------------------------------------------------------------------------
// The robot model file.

void expandIncludes(XMLElement* element, const fs::path& dir, const std::string& path, int depth) {
  for (XMLElement* child = element->FirstChildElement(); child;) {
    XMLElement* next = child->NextSiblingElement();
    if (std::strcmp(child->Name(), "include") == 0) {
      const char* file = child->Attribute("file");
      if (!file) throw Error(path, "<include> without a file attribute");
      if (depth > 8) throw Error(path, "<include> nested too deeply");
      const fs::path included = fs::path(file).is_absolute() ? fs::path(file) : dir / file;
      XMLDocument sub;
      if (sub.LoadFile(included.c_str()) != tinyxml2::XML_SUCCESS)
        throw Error(included.string(), "malformed XML: " + oneLine(sub.ErrorStr()));
      XMLElement* subRoot = sub.RootElement();
      if (!subRoot || std::strcmp(subRoot->Name(), "mujoco") != 0)
        throw Error(included.string(), "root element must be <mujoco>");
      expandIncludes(subRoot, dir, included.string(), depth + 1);
      XMLNode* after = child->PreviousSibling();
      for (const XMLElement* c = subRoot->FirstChildElement(); c; c = c->NextSiblingElement()) {
        XMLNode* clone = c->DeepClone(element->GetDocument());
        after = after ? element->InsertAfterChild(after, clone) : element->InsertFirstChild(clone);
      }
      element->DeleteChild(child);
    } else {
      expandIncludes(child, dir, path, depth);
    }
    child = next;
  }
}

struct RobotModel {
  std::string path;
  fs::path dir;
  XMLDocument doc;
  XMLElement* root = nullptr;
  XMLElement* torso = nullptr;  // the top-level body the scene places
};

void loadRobot(RobotModel& r, const std::string& path) {
  r.path = path;
  std::error_code ec;
  if (!fs::exists(path, ec)) throw Error(path, "file not found");
  if (!fs::is_regular_file(path, ec)) throw Error(path, "not a regular file");
  if (r.doc.LoadFile(path.c_str()) != tinyxml2::XML_SUCCESS)
    throw Error(path, "malformed XML: " + oneLine(r.doc.ErrorStr()));
  r.root = r.doc.RootElement();
  if (!r.root || std::strcmp(r.root->Name(), "mujoco") != 0) throw Error(path, "root element must be <mujoco>");
  r.dir = fs::absolute(fs::path(path)).parent_path();
  expandIncludes(r.root, r.dir, path, 0);

  XMLElement* world = r.root->FirstChildElement("worldbody");
  if (!world) throw Error(path, "no <worldbody>");
  XMLElement* first = world->FirstChildElement("body");
  if (!first) throw Error(path, "<worldbody> has no body");
  for (XMLElement* b = first; b; b = b->NextSiblingElement("body")) {
    const char* name = b->Attribute("name");
    if (name && std::strcmp(name, "torso") == 0) r.torso = b;
  }
  if (!r.torso) r.torso = first;
  for (const char* attribute : {"euler", "axisangle", "xyaxes", "zaxis"})
    if (r.torso->Attribute(attribute))
      throw Error(path, std::string("body '") + (r.torso->Attribute("name") ? r.torso->Attribute("name") : "") +
                            "': give its orientation as quat (the scene turns it to the robot's heading)");
}

std::vector<double> numbers(const char* text, std::size_t count, const std::string& path, const char* what) {
  std::vector<double> v;
  std::istringstream in(text ? text : "");
  double x;
  while (in >> x) v.push_back(x);
  if (v.size() != count || !in.eof())
    throw Error(path, std::string(what) + ": expected " + std::to_string(count) + " numbers");
  return v;
}

void prefixNames(XMLElement* element, const std::string& prefix) {
  for (const char* attribute : kNameAttributes) {
    const char* value = element->Attribute(attribute);
    if (value && *value) element->SetAttribute(attribute, (prefix + value).c_str());
  }
  for (XMLElement* c = element->FirstChildElement(); c; c = c->NextSiblingElement()) prefixNames(c, prefix);
}

// Asset files resolved against the robot model's folder, so that the scene (compiled from
// memory) finds them.
void resolveAssetFiles(XMLElement* asset, const RobotModel& r, const XMLElement* compiler) {
  auto dirOf = [&](const char* key) {
    fs::path d = r.dir;
    if (compiler) {
      if (const char* a = compiler->Attribute("assetdir")) d = d / a;
      if (const char* k = compiler->Attribute(key)) d = r.dir / k;
    }
    return d;
  };
  for (XMLElement* e = asset->FirstChildElement(); e; e = e->NextSiblingElement()) {
    const bool mesh = std::strcmp(e->Name(), "mesh") == 0;
    const bool texture = std::strcmp(e->Name(), "texture") == 0;
    const fs::path base = mesh ? dirOf("meshdir") : texture ? dirOf("texturedir") : r.dir;
    for (const char* key : {"file", "fileright", "fileleft", "fileup", "filedown", "filefront", "fileback"}) {
      const char* file = e->Attribute(key);
      if (file && *file && !fs::path(file).is_absolute())
        e->SetAttribute(key, (base / file).lexically_normal().c_str());
    }
  }
}

// ---------------------------------------------------------------------------------------------
// The scene.

struct Scene {
  XMLDocument doc;
  XMLElement* root;
  XMLElement *compiler, *option, *size, *visual, *statistic, *defaults, *asset, *world, *contact, *equality, *tendon,
      *actuator, *sensor, *custom;
  // The static body of everything only the cameras see (paint, the hall's floor and contents).
  // MuJoCo 2.2's collision detection visits every static geom against every moving body each
  // step, whatever its contype (a venue's 300 hall geoms halved bench sim's physics_rtf, and
  // neither a body of their own nor contact excludes helped); compileScene takes this body's
  // geoms out of its geom list, which is what collision detection walks.
  XMLElement* decor;

  Scene() {
    root = add(&doc, "mujoco", {{"model", "nao_soccer_scene"}});
    compiler = add(root, "compiler");
    option = add(root, "option");
    size = add(root, "size");
    visual = add(root, "visual");
    statistic = add(root, "statistic");
    defaults = add(root, "default");
    asset = add(root, "asset");
    world = add(root, "worldbody");
    decor = add(world, "body", {{"name", "decor"}});
    // A static body's mass is never used, but MuJoCo's compiler wants one (planes have none).
    add(decor, "inertial", {{"pos", "0 0 0"}, {"mass", "1"}, {"diaginertia", "1 1 1"}});
    contact = add(root, "contact");
    equality = add(root, "equality");
    tendon = add(root, "tendon");
    actuator = add(root, "actuator");
    sensor = add(root, "sensor");
    custom = add(root, "custom");
  }

  std::string text() {
    for (XMLElement* e : {compiler, option, size, defaults, asset, contact, equality, tendon, actuator, sensor, custom})
      if (!e->FirstChild() && !e->FirstAttribute()) root->DeleteChild(e);
    tinyxml2::XMLPrinter printer;
    doc.Print(&printer);
    return printer.CStr();
  }

  // A static, visual-only rectangle of paint (no collisions), e.g. a line. `layer` lifts it by
  // 0.1 mm steps: pieces that overlap (circle chords, marks on lines) must not be coplanar, or
  // the shadow map z-fights between them and leaves dark ticks on the paint.
  void paint(const std::string& name, double x, double y, double halfLength, double halfWidth, double yaw,
             int layer = 0, const std::string& material = "scene_line") {
    add(decor, "geom",
        {{"name", name},
         {"type", "plane"},
         {"material", material},
         {"contype", "0"},
         {"conaffinity", "0"},
         {"group", "0"},
         {"pos", vec({x, y, kLineTop + 1e-4 * layer})},
         {"quat", yawQuat(yaw)},
         {"size", vec({halfLength, halfWidth, 1.0})}});
  }
};

void addAssets(Scene& s, const VenueLook& look) {
  add(s.asset, "texture",
      {{"name", "scene_sky"},
       {"type", "skybox"},
       {"builtin", "gradient"},
       {"rgb1", "0.62 0.63 0.66"},
       {"rgb2", "0.28 0.28 0.30"},
       {"width", "256"},
       {"height", "256"}});
  if (look.plain()) {
    // Turf: the colour is the material's (about the mean of real SPL carpets under hall light); the
    // texture only adds a fine grain. OpenGL clamps the lit colour before multiplying by a texture,
    // so a coloured texture could never be over-exposed; a near-white grain can.
    add(s.asset, "texture",
        {{"name", "scene_turf"},
         {"type", "2d"},
         {"builtin", "flat"},
         {"rgb1", "0.9 0.9 0.9"},
         {"mark", "random"},
         {"random", "0.35"},
         {"markrgb", "1 1 1"},
         {"width", "512"},
         {"height", "512"}});
    add(s.asset, "material",
        {{"name", "scene_turf"},
         {"texture", "scene_turf"},
         {"rgba", "0.24 0.61 0.22 1"},
         {"texrepeat", "8 8"},
         {"texuniform", "true"},
         {"specular", "0"},
         {"shininess", "0"},
         {"reflectance", "0"}});
  } else {
    venue::addAssets(s.asset, look);
  }
  add(s.asset, "material",
      {{"name", "scene_line"},
       {"rgba", "0.95 0.95 0.95 1"},
       {"specular", "0"},
       {"shininess", "0"},
       {"reflectance", "0"}});
  add(s.asset, "material",
      {{"name", "scene_hall_floor"},
       {"rgba", vec({look.floor.x(), look.floor.y(), look.floor.z(), 1})},
       {"specular", "0"},
       {"reflectance", "0"}});
  add(s.asset, "material",
      {{"name", "scene_hall_wall"},
       {"rgba", vec({look.wall.x(), look.wall.y(), look.wall.z(), 1})},
       {"specular", "0"},
       {"reflectance", "0"}});
  add(s.asset, "material",
      {{"name", "scene_goal"},
       {"rgba", "0.96 0.96 0.96 1"},
       {"specular", "0.2"},
       {"shininess", "0.2"},
       {"reflectance", "0"}});
  add(s.asset, "material",
      {{"name", "scene_net"}, {"rgba", "0.85 0.85 0.85 0.3"}, {"specular", "0"}, {"reflectance", "0"}});
  add(s.asset, "material",
      {{"name", "scene_bar"}, {"rgba", "0.15 0.15 0.15 1"}, {"specular", "0.1"}, {"reflectance", "0"}});
  add(s.asset, "material",
      {{"name", "scene_ball"},
       {"rgba", "0.95 0.95 0.95 1"},
       {"specular", "0.1"},
       {"shininess", "0.1"},
       {"reflectance", "0"}});
  add(s.asset, "material",
      {{"name", "scene_ball_patch"}, {"rgba", "0.05 0.05 0.05 1"}, {"specular", "0.1"}, {"reflectance", "0"}});
}

void addField(Scene& s, const FieldModel& f, const VenueLook& look, std::uint64_t seed) {
  const FieldDimensions& d = f.dims;
  const double hl = d.length / 2, hw = d.width / 2, w = d.lineWidth;
  const double cx = hl + d.borderStripWidth, cy = hw + d.borderStripWidth;  // carpet half sizes

  // The carpet is the collision floor (a plane collides everywhere; its size is only visual).
  add(s.world, "geom",
      {{"name", "field/carpet"},
       {"type", "plane"},
       {"material", "scene_turf"},
       {"size", vec({cx, cy, 0.25})},
       {"pos", "0 0 0"},
       {"condim", "3"},
       {"friction", "1 0.005 0.0001"},
       {"contype", "1"},
       {"conaffinity", "1"},
       {"group", "0"}});
  // The hall: a grey floor around the carpet and walls, so the field boundary is visible.
  const double hx = cx + kHallMargin, hy = cy + kHallMargin;
  add(s.decor, "geom",
      {{"name", "hall/floor"},
       {"type", "plane"},
       {"material", "scene_hall_floor"},
       {"size", vec({hx, hy, 1})},
       {"pos", vec({0, 0, -kFloorDrop})},
       {"contype", "0"},
       {"conaffinity", "0"},
       {"group", "0"}});
  const double t = 0.05;
  struct Wall {
    const char* name;
    double x, y, sx, sy;
  };
  for (const Wall& wall :
       {Wall{"hall/wall_opp", hx + t, 0, t, hy + 2 * t}, Wall{"hall/wall_own", -hx - t, 0, t, hy + 2 * t},
        Wall{"hall/wall_left", 0, hy + t, hx + 2 * t, t}, Wall{"hall/wall_right", 0, -hy - t, hx + 2 * t, t}})
    add(s.world, "geom",
        {{"name", wall.name},
         {"type", "box"},
         {"material", "scene_hall_wall"},
         {"pos", vec({wall.x, wall.y, kWallHeight / 2})},
         {"size", vec({wall.sx, wall.sy, kWallHeight / 2})},
         {"contype", "1"},
         {"conaffinity", "1"},
         {"group", "0"}});
  if (!look.plain())
    venue::addHall(s.decor, look, {cx, cy, hx, hy, -kFloorDrop, kWallHeight}, seed);

  // The venue's paint: strokes of uneven pieces (sim/VenueScene.h); the plain look's: one piece
  // per line, chord, dash.
  std::mt19937_64 paintRng(seed * 0x9e3779b97f4a7c15ULL + 0x7061696e74ULL);
  const venue::PaintFn venuePaint = [&](const std::string& name, double x, double y, double halfLength,
                                        double halfWidth, double yaw, const std::string& material, int layer) {
    s.paint(name, x, y, halfLength, halfWidth, yaw, layer, material);
  };
  auto paintPiece = [&](const std::string& name, const Eigen::Vector2d& centre, double halfLength, double yaw,
                        int layer) {
    if (look.plain())
      s.paint(name, centre.x(), centre.y(), halfLength, w / 2, yaw, layer);
    else
      venue::piece(venuePaint, name, centre, halfLength, w, yaw, layer, look, paintRng);
  };

  // Straight lines, each lengthened by half a line width at both ends so corners are filled.
  // Straight lines must not overlap either (same shadow-map reason): where a line ends on
  // another one (a T, or an L corner where the other line is the earlier one) it stops at that
  // line's edge; otherwise it runs on by half a width to close the corner.
  auto endsOnEarlierOrSpan = [&](std::size_t self, const Eigen::Vector2d& end) {
    for (std::size_t o = 0; o < f.lines.size(); ++o) {
      if (o == self) continue;
      const FieldLine& other = f.lines[o];
      const Eigen::Vector2d od = other.to - other.from;
      const double along = (end - other.from).dot(od) / od.squaredNorm();
      const double off = std::abs((end - other.from).x() * od.normalized().y() - (end - other.from).y() * od.normalized().x());
      if (off > 1e-6 || along < -1e-9 || along > 1 + 1e-9) continue;
      const bool atOtherEnd = along < 1e-9 || along > 1 - 1e-9;
      if (!atOtherEnd || o < self) return true;
    }
    return false;
  };
  for (std::size_t i = 0; i < f.lines.size(); ++i) {
    const FieldLine& line = f.lines[i];
    const Eigen::Vector2d dir = (line.to - line.from).normalized();
    const Eigen::Vector2d from = line.from - dir * (endsOnEarlierOrSpan(i, line.from) ? -w / 2 : w / 2);
    const Eigen::Vector2d to = line.to + dir * (endsOnEarlierOrSpan(i, line.to) ? -w / 2 : w / 2);
    const Eigen::Vector2d mid = (from + to) / 2;
    if (look.plain())
      s.paint("field/line/" + line.name, mid.x(), mid.y(), (to - from).norm() / 2, w / 2, std::atan2(dir.y(), dir.x()));
    else
      venue::stroke(venuePaint, "field/line/" + line.name, from, to, w, look, paintRng);
  }
  // Centre circle: chords centred on the line-centre radius, long enough to close the outer edge.
  const double r = f.centerCircleRadius;
  const double halfChord = (r + w / 2) * std::tan(std::numbers::pi / kCircleSegments);
  for (int k = 0; k < kCircleSegments; ++k) {
    const double a = 2 * std::numbers::pi * k / kCircleSegments;
    paintPiece("field/circle/" + std::to_string(k),
               f.centerCircleCenter + r * Eigen::Vector2d(std::cos(a), std::sin(a)), halfChord,
               a + std::numbers::pi / 2, 1 + k % 2);
  }
  // Centre mark: a dash of penaltyCrossSize across the halfway line (along x), so with the
  // halfway line it reads as a cross like the penalty marks.
  paintPiece("field/center_mark", f.centerMark, d.penaltyCrossSize / 2, 0, 3);
  for (std::size_t k = 0; k < f.penaltyCrosses.size(); ++k) {
    const Eigen::Vector2d& p = f.penaltyCrosses[k];
    const std::string name = "field/penalty_cross/" + std::to_string(k);
    paintPiece(name + "/x", p, d.penaltyCrossSize / 2, 0, 0);
    paintPiece(name + "/y", p, d.penaltyCrossSize / 2, std::numbers::pi / 2, 0);
  }
}

// A goal on the goal line at x = side * length/2: posts centred on the line, crossbar, net
// (back, sides, top) on black support bars, depth behind the goal line.
void addGoal(Scene& s, const FieldDimensions& d, double side) {
  const std::string prefix = side < 0 ? "goal/own/" : "goal/opp/";
  const double gx = side * d.length / 2, bx = side * (d.length / 2 + d.goalDepth), mx = (gx + bx) / 2;
  const double r = d.goalPostDiameter / 2, py = d.goalInnerWidth / 2 + r, h = d.goalHeight, nt = kNetThickness / 2;
  auto cylinder = [&](const std::string& name, const char* material, double radius,
                      std::initializer_list<double> fromto) {
    add(s.world, "geom",
        {{"name", prefix + name},
         {"type", "cylinder"},
         {"material", material},
         {"size", num(radius)},
         {"fromto", vec(fromto)},
         {"contype", "1"},
         {"conaffinity", "1"},
         {"group", "0"}});
  };
  auto net = [&](const std::string& name, double x, double y, double z, double sx, double sy, double sz) {
    add(s.world, "geom",
        {{"name", prefix + name},
         {"type", "box"},
         {"material", "scene_net"},
         {"pos", vec({x, y, z})},
         {"size", vec({sx, sy, sz})},
         {"contype", "1"},
         {"conaffinity", "1"},
         {"group", "0"}});
  };
  cylinder("post_left", "scene_goal", r, {gx, py, 0, gx, py, h});
  cylinder("post_right", "scene_goal", r, {gx, -py, 0, gx, -py, h});
  cylinder("crossbar", "scene_goal", r, {gx, -py, h - r, gx, py, h - r});
  net("net_back", bx, 0, h / 2, nt, py, h / 2);
  net("net_left", mx, py, h / 2, d.goalDepth / 2, nt, h / 2);
  net("net_right", mx, -py, h / 2, d.goalDepth / 2, nt, h / 2);
  net("net_top", mx, 0, h - nt, d.goalDepth / 2, py, nt);
  const double br = kBarRadius;
  cylinder("bar_back_top", "scene_bar", br, {bx, -py, h - br, bx, py, h - br});
  cylinder("bar_back_bottom", "scene_bar", br, {bx, -py, br, bx, py, br});
  for (double sy : {1.0, -1.0}) {
    const std::string lr = sy > 0 ? "left" : "right";
    cylinder("bar_back_" + lr, "scene_bar", br, {bx, sy * py, 0, bx, sy * py, h});
    cylinder("bar_top_" + lr, "scene_bar", br, {gx, sy * py, h - br, bx, sy * py, h - br});
    cylinder("bar_bottom_" + lr, "scene_bar", br, {gx, sy * py, br, bx, sy * py, br});
  }
}

void addBall(Scene& s, int index, const Eigen::Vector3d& position) {
  const std::string name = "ball" + std::to_string(index);
  XMLElement* body = add(s.world, "body", {{"name", name}, {"pos", vec({position.x(), position.y(), position.z()})}});
  const double inertia = 0.4 * kBallMass * kBallRadius * kBallRadius;  // a solid foam sphere
  add(body, "inertial",
      {{"pos", "0 0 0"}, {"mass", num(kBallMass)}, {"diaginertia", vec({inertia, inertia, inertia})}});
  add(body, "joint",
      {{"name", name},
       {"type", "free"},
       {"damping", "0"},
       {"armature", "0"},
       {"stiffness", "0"},
       {"frictionloss", "0"}});
  // The sphere first: World reads the ball radius from the body's first geom.
  add(body, "geom",
      {{"name", name},
       {"type", "sphere"},
       {"size", num(kBallRadius)},
       {"mass", num(kBallMass)},
       {"material", "scene_ball"},
       {"condim", "6"},
       {"friction", kBallFriction},
       {"priority", "2"},
       {"solref", kBallSolref},
       {"solimp", kBallSolimp},
       {"contype", "1"},
       {"conaffinity", "1"},
       {"margin", "0"},
       {"gap", "0"},
       {"group", "0"}});
  add(s.contact, "pair",
      {{"name", name + "/carpet"},
       {"geom1", name},
       {"geom2", "field/carpet"},
       {"condim", "3"},
       {"friction", kBallCarpetFriction},
       {"solref", kBallCarpetSolref},
       {"solimp", "0.9 0.95 0.001"},
       {"margin", "0"},
       {"gap", "0"}});
  // Twelve black patches at the icosahedron's vertices (a soccer ball's pentagons).
  const double phi = (1 + std::sqrt(5.0)) / 2;
  std::vector<Eigen::Vector3d> dirs;
  for (double a : {-1.0, 1.0})
    for (double b : {-phi, phi}) {
      dirs.emplace_back(0, a, b);
      dirs.emplace_back(a, b, 0);
      dirs.emplace_back(b, 0, a);
    }
  for (std::size_t k = 0; k < dirs.size(); ++k) {
    const Eigen::Vector3d u = dirs[k].normalized();
    const Eigen::Vector3d c = u * (kBallRadius + kPatchRise - kPatchDepth);
    add(body, "geom",
        {{"name", name + "/patch" + std::to_string(k)},
         {"type", "ellipsoid"},
         {"size", vec({kPatchRadius, kPatchRadius, kPatchDepth})},
         {"pos", vec({c.x(), c.y(), c.z()})},
         {"zaxis", vec({u.x(), u.y(), u.z()})},
         {"mass", "0"},
         {"material", "scene_ball_patch"},
         {"contype", "0"},
         {"conaffinity", "0"},
         {"group", "0"}});
  }
}

void addRobots(Scene& s, RobotModel& r, const SceneSpec& spec) {
  // Sections shared by all copies: compiler, option, size, defaults, assets, custom.
  const XMLElement* robotCompiler = r.root->FirstChildElement("compiler");
  for (const XMLElement* e = r.root->FirstChildElement(); e; e = e->NextSiblingElement()) {
    const std::string tag = e->Name();
    auto copyAttributes = [&](XMLElement* to) {
      for (const tinyxml2::XMLAttribute* a = e->FirstAttribute(); a; a = a->Next())
        to->SetAttribute(a->Name(), a->Value());
    };
    auto copyChildren = [&](XMLElement* to) {
      for (const XMLElement* c = e->FirstChildElement(); c; c = c->NextSiblingElement())
        to->InsertEndChild(c->DeepClone(&s.doc));
    };
    if (tag == "compiler") {
      copyAttributes(s.compiler);
    } else if (tag == "option") {
      copyAttributes(s.option);
      copyChildren(s.option);
    } else if (tag == "size") {
      copyAttributes(s.size);
    } else if (tag == "default") {
      copyAttributes(s.defaults);
      copyChildren(s.defaults);
    } else if (tag == "asset") {
      copyChildren(s.asset);
    } else if (tag == "custom") {
      copyChildren(s.custom);
    }
  }
  resolveAssetFiles(s.asset, r, robotCompiler);
  // Files are absolute now; the scene's own geoms must survive whatever the robot asked for.
  for (const char* key : {"meshdir", "texturedir", "assetdir"}) s.compiler->DeleteAttribute(key);
  s.compiler->SetAttribute("discardvisual", "false");

  // Per-robot copies with prefixed names.
  const std::vector<double> torsoPos =
      numbers(r.torso->Attribute("pos") ? r.torso->Attribute("pos") : "0 0 0", 3, r.path, "body 'torso' pos");
  const std::vector<double> torsoQuat =
      numbers(r.torso->Attribute("quat") ? r.torso->Attribute("quat") : "1 0 0 0", 4, r.path, "body 'torso' quat");
  for (std::size_t i = 0; i < spec.robots.size(); ++i) {
    const std::string prefix = robotPrefix(static_cast<int>(i));
    const Eigen::Vector3d& pose = spec.robots[i];
    XMLElement* robotWorld = r.root->FirstChildElement("worldbody");
    for (const XMLElement* b = robotWorld->FirstChildElement("body"); b; b = b->NextSiblingElement("body")) {
      auto* copy = b->DeepClone(&s.doc)->ToElement();
      if (b == r.torso) {
        copy->SetAttribute("pos", vec({pose.x(), pose.y(), torsoPos[2]}).c_str());
        const Eigen::Quaterniond q =
            Eigen::Quaterniond(Eigen::AngleAxisd(pose.z(), Eigen::Vector3d::UnitZ())) *
            Eigen::Quaterniond(torsoQuat[0], torsoQuat[1], torsoQuat[2], torsoQuat[3]).normalized();
        copy->SetAttribute("quat", vec({q.w(), q.x(), q.y(), q.z()}).c_str());
      }
      prefixNames(copy, prefix);
      s.world->InsertEndChild(copy);
    }
    // Other worldbody content (floor, lights of a stand-alone model) is not copied.
    for (const auto& [section, target] : {std::pair{"contact", s.contact},
                                          {"equality", s.equality},
                                          {"tendon", s.tendon},
                                          {"actuator", s.actuator},
                                          {"sensor", s.sensor}}) {
      for (const XMLElement* e = r.root->FirstChildElement(section); e; e = e->NextSiblingElement(section))
        for (const XMLElement* c = e->FirstChildElement(); c; c = c->NextSiblingElement()) {
          auto* copy = c->DeepClone(&s.doc)->ToElement();
          prefixNames(copy, prefix);
          target->InsertEndChild(copy);
        }
    }
  }
  // Keyframes are dropped: their qpos would not fit a scene with several robots and balls.
}

void validateSpec(const SceneSpec& spec) {
  if (!(spec.physicsStep > 0 && spec.physicsStep < 0.1)) throw Error("SceneSpec", "physicsStep: must be in (0, 0.1) s");
  for (const CameraResolution& c : {spec.top, spec.bottom})
    if (c.width <= 0 || c.height <= 0 || c.width > 4096 || c.height > 4096 || c.width % 2 != 0)
      throw Error("SceneSpec", "camera resolution " + std::to_string(c.width) + "x" + std::to_string(c.height) +
                                   ": must be even-width and at most 4096x4096");
  for (const Eigen::Vector3d& p : spec.robots)
    if (!p.allFinite()) throw Error("SceneSpec", "robots: pose must be finite");
  for (const Eigen::Vector3d& p : spec.balls)
    if (!p.allFinite()) throw Error("SceneSpec", "balls: position must be finite");
}

}  // namespace

std::string robotPrefix(int robot) {
  std::string prefix = "r";  // built in steps: GCC 12 warns falsely on "r" + std::string&&
  prefix += std::to_string(robot);
  prefix += '/';
  return prefix;
}

std::string robotModelPath(const SceneSpec& spec) {
  return spec.robotModel.empty() ? dataPath("models/nao_v6.xml") : spec.robotModel;
}

std::string buildSceneXml(const SceneSpec& spec) {
  validateSpec(spec);
  spec.field.validate("SceneSpec.field");
  const FieldModel field = FieldModel::from(spec.field);

  Scene s;
  if (!spec.robots.empty()) {
    RobotModel robot;
    loadRobot(robot, robotModelPath(spec));
    addRobots(s, robot, spec);
  }

  // Physics: semi-implicit Euler. MuJoCo integrates joint damping implicitly with it too, and
  // the servo torques are computed in World (ctrl), so the implicit integrator's actuator
  // derivatives buy nothing while costing ~40% of a step (bench sim: RTF 21 -> 38).
  s.option->SetAttribute("timestep", num(spec.physicsStep).c_str());
  s.option->SetAttribute("integrator", "Euler");
  const int contacts = 100 + 150 * static_cast<int>(spec.robots.size()) + 10 * static_cast<int>(spec.balls.size());
  s.size->SetAttribute("nconmax", std::max(contacts, s.size->IntAttribute("nconmax", 0)));
  s.size->SetAttribute("njmax", std::max(6 * contacts, s.size->IntAttribute("njmax", 0)));

  // Rendering: offscreen buffer for the largest camera, 4x multisampling, a large shadow map.
  const FieldDimensions& d = spec.field;
  const double extent = std::hypot(d.length / 2 + d.borderStripWidth, d.width / 2 + d.borderStripWidth);
  add(s.visual, "global",
      {{"offwidth", std::to_string(std::max(spec.top.width, spec.bottom.width))},
       {"offheight", std::to_string(std::max(spec.top.height, spec.bottom.height))}});
  add(s.visual, "quality", {{"shadowsize", "4096"}, {"offsamples", "4"}});
  add(s.visual, "headlight",
      {{"ambient", "0.3 0.3 0.3"}, {"diffuse", "0 0 0"}, {"specular", "0 0 0"}, {"active", "1"}});
  // znear/zfar are fractions of the extent: clip at 1 cm and 60 m; the shadow map spans the carpet.
  add(s.visual, "map", {{"znear", num(0.01 / extent)}, {"zfar", num(60 / extent)}, {"shadowclip", "1.1"}});
  s.statistic->SetAttribute("extent", num(extent).c_str());
  s.statistic->SetAttribute("center", "0 0 0.3");

  addAssets(s, spec.venue);
  // The sun; CameraRenderer overwrites colour and direction from a Lighting before each frame.
  add(s.world, "light",
      {{"name", "sun"},
       {"directional", "true"},
       {"castshadow", "true"},
       {"mode", "fixed"},
       {"pos", "0 0 10"},
       {"dir", "-0.25 -0.43 -0.87"},
       {"diffuse", "0.7 0.7 0.7"},
       {"specular", "0 0 0"},
       {"ambient", "0 0 0"}});
  addField(s, field, spec.venue, spec.venueSeed);
  addGoal(s, d, -1);
  addGoal(s, d, +1);
  for (std::size_t j = 0; j < spec.balls.size(); ++j) addBall(s, static_cast<int>(j), spec.balls[j]);
  return s.text();
}

mjModel_* compileScene(const SceneSpec& spec) {
  routeMujocoMessages();
  const std::string xml = buildSceneXml(spec);
  auto vfs = std::make_unique<mjVFS>();
  mj_defaultVFS(vfs.get());
  const char* fileName = "nao_soccer_scene.xml";
  if (mj_makeEmptyFileVFS(vfs.get(), fileName, static_cast<int>(xml.size())) != 0)
    throw Error(robotModelPath(spec), "MuJoCo: cannot hold the scene in memory");
  const int index = mj_findFileVFS(vfs.get(), fileName);
  std::memcpy(vfs->filedata[index], xml.data(), xml.size());
  char error[1024] = "";
  mjModel* m = mj_loadXML(fileName, vfs.get(), error, sizeof error);
  mj_deleteVFS(vfs.get());
  // MuJoCo names the object at fault (robot objects carry their r<i>/ prefix); its line numbers
  // count in the generated scene, not in the robot file.
  if (!m) throw Error(robotModelPath(spec), "MuJoCo (generated scene): " + oneLine(error));
  // The decor's geoms stay in the model (the renderer and mj_ray visit every geom) but leave
  // the body's geom list, which is what collision detection walks.
  if (const int decor = mj_name2id(m, mjOBJ_BODY, "decor"); decor > 0) m->body_geomnum[decor] = 0;
  if (!spec.venue.plain()) {
    const FieldDimensions& d = spec.field;
    venue::paintTextures(m, spec.venue,
                         {d.length + 2 * d.borderStripWidth, d.width + 2 * d.borderStripWidth}, spec.venueSeed);
  }
  return m;
}

}  // namespace nao::sim
