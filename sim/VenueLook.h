#pragma once
// How a venue looks to the cameras: the carpet's texture, the paint, the hall around the field
// and what stands in it (config/venues.json, each venue's "look"; docs/vision/venues.md). The
// simulated world is built from it; nothing in the robot program reads it.
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <nlohmann/json_fwd.hpp>

namespace nao::sim {

struct VenueLook {
  std::string name = "none";
  bool diagram = true;  // the plain diagram: uniform carpet, even paint, a grey hall with nothing in it

  // The carpet: its mean colour, and how it varies (relative, 1 sd): brightness over patches of
  // about a metre, each channel on its own (hue), texel grain, alternating stripes across the
  // field's length (mowing or the turf's rolls), and a sheen that depends on the view direction.
  Eigen::Vector3d turf{0.24, 0.61, 0.22};
  double turfPatches = 0.05;
  double turfHue = 0.03;
  double grain = 0.12;
  double stripeWidth = 1.0;  // m; 0: none
  double stripeContrast = 0.03;
  double sheen = 0.1;  // the carpet's specular

  // The paint (or tape): each piece's width varies by this share (1 sd), the lines drift
  // sideways by up to `lineBend` m, and `lineWear` of the paint is worn down to the carpet.
  double lineWidthJitter = 0.05;
  double lineBend = 0.004;
  double lineWear = 0.04;

  // The hall: wall and floor colours; how many windows (daylight), doors, advertising boards,
  // tables with laptops and people standing around the carpet; a gym's coloured floor lines
  // (none when floorLines is all 0).
  Eigen::Vector3d wall{0.55, 0.56, 0.60};
  Eigen::Vector3d floor{0.33, 0.33, 0.35};
  int windows = 2, doors = 1, boards = 4, tables = 2, people = 6;
  Eigen::Vector3d floorLines{0, 0, 0};

  bool plain() const { return diagram; }
};

// Every venue's look in `path` (config/venues.json: each venue's name and "look", a venue
// without one is the plain diagram; the other keys are the challenge's, scenarios/Venue.h).
// Throws nao::Error naming the file and the key.
std::vector<VenueLook> loadVenueLooks(const std::string& path);
// config/venues.json's JSON with its "venues" a non-empty array of objects, each with a
// non-empty "name" (the challenge's reader checks the rest, scenarios/Venue.h).
nlohmann::json readVenueFile(const std::string& path);
// loadVenueLooks on a file's text (`path` names it in errors).
std::vector<VenueLook> parseVenueLooks(const std::string& text, const std::string& path);
// One venue's "look" object; `where` names it in errors ("venues[2].look").
VenueLook parseVenueLook(const nlohmann::json& look, const std::string& name, const std::string& path,
                         const std::string& where);

// The look that `--venue` names: "none", "random" (seed's turn through `looks`: seed mod the
// count, as the challenge's venues) or a name. Throws nao::Error("--venue", ...) listing them.
VenueLook venueLookFor(const std::vector<VenueLook>& looks, const std::string& venue, std::uint64_t seed);

// What `--venue` chose, resolved per seed (an evaluation's trials each take their own).
struct VenueChoice {
  std::string venue = "none";   // none, random or a name
  std::vector<VenueLook> looks;  // config/venues.json's
  VenueLook forSeed(std::uint64_t seed) const { return venueLookFor(looks, venue, seed); }
  // "none" needs no file; anything else reads `path` (config/venues.json).
  static VenueChoice load(const std::string& venue, const std::string& path);
};

// The look as JSON (what an evaluation states it drew from).
nlohmann::json toJson(const VenueLook& look);

}  // namespace nao::sim
