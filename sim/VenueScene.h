#pragma once
// The scene builder's venue part (sim/VenueLook.h): the carpet's and the paint's textures, the
// paint's uneven strokes, and the hall with what stands in it. Everything here is visual only
// (no collisions); a plain look ("none") adds nothing and the scene stays the diagram it was.
#include <cstdint>
#include <functional>
#include <random>
#include <string>

#include <Eigen/Core>

#include "sim/VenueLook.h"

namespace tinyxml2 {
class XMLElement;
}
struct mjModel_;

namespace nao::sim::venue {

inline constexpr int kPaintMaterials = 4;  // "scene_paint<k>": worn paint, each its own texture

// The venue's carpet ("scene_turf", one texture over the whole carpet) and paint materials.
void addAssets(tinyxml2::XMLElement* asset, const VenueLook& look);

// A paint piece: centre, half length and half width, yaw, material and stacking layer.
using PaintFn = std::function<void(const std::string& name, double x, double y, double halfLength, double halfWidth,
                                   double yaw, const std::string& material, int layer)>;

// A straight stroke of paint from `from` to `to` (its ends already where the paint ends), width
// `width`, as pieces of about half a metre whose width varies and which drift sideways.
void stroke(const PaintFn& paint, const std::string& name, const Eigen::Vector2d& from, const Eigen::Vector2d& to,
            double width, const VenueLook& look, std::mt19937_64& rng);
// One short piece (a circle chord, a mark) with the venue's width variation and material.
void piece(const PaintFn& paint, const std::string& name, const Eigen::Vector2d& centre, double halfLength,
           double width, double yaw, int layer, const VenueLook& look, std::mt19937_64& rng);

// The hall's size: the carpet's half sizes, the walls' (inner) half sizes, the floor's height.
struct Hall {
  double carpetX, carpetY, wallX, wallY, floorZ, wallHeight;
};
// Windows, doors, boards, tables, people and floor lines, placed from `seed`.
void addHall(tinyxml2::XMLElement* world, const VenueLook& look, const Hall& hall, std::uint64_t seed);

// Fills the textures addAssets declared (after MuJoCo compiled the scene, before any renderer
// uploads them). `carpetSize` is the carpet's full size in m.
void paintTextures(mjModel_* m, const VenueLook& look, const Eigen::Vector2d& carpetSize, std::uint64_t seed);

}  // namespace nao::sim::venue
