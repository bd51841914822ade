#pragma once
// A venue of the calibration challenge (config/venues.json): where phase 2's balls are taped
// (the same for every robot there) and how the carpet grips. The rules rank teams per venue
// and average over at least three.
#include <array>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "perception/FieldDimensions.h"
#include "sim/VenueLook.h"

namespace nao::sim {

struct Venue {
  std::string name;
  double floorFriction = 1.0;
  std::array<Eigen::Vector2d, 2> balls{};  // own half's, then the opponent half's (field, m)
  VenueLook look;                          // how it looks to the cameras (none given: the diagram)
};

// Every venue of `path`, each checked against `field` (its balls inside the field, one per half,
// not on a line; friction in 0.2..2). Throws nao::Error naming the file and the key.
std::vector<Venue> loadVenues(const std::string& path, const FieldDimensions& field);
// The venue named `name` in `venues`; throws nao::Error("--venue", ...) listing the names.
const Venue& venueNamed(const std::vector<Venue>& venues, const std::string& name);

}  // namespace nao::sim
