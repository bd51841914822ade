#pragma once
// The scan grid (B-Human 2021, section 5.1): where the colour-segmented scan lines lie,
// adapted to the camera matrix. Vertical lines are spaced by the expected image width of a
// field line at each row: a fine set reaches down only as far as it is needed, every second
// line of it further, and so on (a hierarchy of spacings from minSpacing to maxSpacing), so
// far thin lines are still hit while near rows are scanned coarsely. Horizontal lines are
// spaced likewise by the same width at their row; where that spans more than 3 line widths
// of ground along the view (far away), extra rows lie between them, so that a short line
// running up the image (a goal box side) is still crossed often enough. Nothing above the
// horizon is scanned; the field boundary cuts the lines later (cutAtBoundary /
// computeScanLineRegions). The sample step along a line follows the expected thickness of a
// field line crossing it (every other pixel at least: the 3-pixel smoothing still covers each
// pixel). The robot's own feet (bottom camera looking down) are left out.
#include <vector>

#include "perception/CameraModel.h"

namespace nao {

struct ScanGrid {
  int width = 0, height = 0;
  // Topmost row below the horizon anywhere in the image (0 when the horizon is above the
  // image, height when no ground is visible).
  int horizonY = 0;

  // Vertical lines, ascending x. Each is scanned over rows [topY, bottomY).
  std::vector<int> xs;
  std::vector<int> topY;     // per vertical line: first row below the horizon
  std::vector<int> bottomY;  // per vertical line: end row (exclusive): the image bottom, the
                             // robot's own feet, or where coarser lines take over
  std::vector<int> levels;   // per vertical line: 0 = finest; spacing there = minSpacing << level
  int minSpacing = 4;        // px between the finest vertical lines

  // The rows vertical lines are sampled at (ascending; shared by all vertical lines).
  std::vector<int> sampleRows;

  // Horizontal lines, ascending y. Each is scanned over columns [leftX, rightX) with a step.
  std::vector<int> ys;
  std::vector<int> leftX, rightX, xStep;
  // Per horizontal line: 1 for an extra row between two rows a line's width apart (far
  // away, where a line running up the image is short, see makeScanGrid). Extra rows only add
  // detail (line spots); the image's colour statistics come from the other lines alone, so
  // that they do not depend on how densely the far field is scanned.
  std::vector<char> extraRow;

  // Per image row: expected image size (px) of a field line at the image's centre column:
  // its width when it runs away from the camera (across the row) and its height when it
  // runs across the view (along the column). 0 above the horizon.
  std::vector<float> lineWidthPx, lineHeightPx;

  bool empty() const { return xs.empty(); }
};

// lineWidthM: the field lines' width (SPL: 5 cm).
ScanGrid makeScanGrid(const CameraMatrix& cm, int width, int height, double lineWidthM = 0.05);

// For an image whose camera pose is unknown (a photo to `perceive`): a camera 0.5 m above
// the ground (a standing NAO's top camera) pitched down by half the vertical field of view
// plus 1 deg, so the horizon lies just above the image and all of it is scanned.
CameraMatrix cameraMatrixForUnknownPose(int width, int height);

}  // namespace nao
