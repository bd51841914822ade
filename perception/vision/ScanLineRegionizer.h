#pragma once
// Colour-segmented scan lines (B-Human 2021, section 5.1), with every threshold computed from
// the image at hand (the constants in the .cpp are generic: noise multiples, what a green
// field can look like at all, fractions of a field line's expected size):
// 1. Regions: each scan line is sampled at the grid's steps; a sample is the 3x3-Gaussian
//    smoothed luminance (and the chroma along the line). Where a sample differs from the one
//    3 px or more before it by more than the edge threshold (a multiple of this image's median
//    such difference: its noise and texture), the peak of a Sobel-type derivative between them
//    places the region edge exactly (a colour edge of the same kind splits too). Each region
//    gets the mean YHS2 colour of its pixels on the line.
// 2. Field: touching regions of similar colour (on neighbouring vertical lines, neighbouring
//    horizontal lines, and where a vertical and a horizontal line cross) are united with
//    union-find; sets whose mean colour stays similar keep growing. United sets that cover
//    enough of the image and lie in the plausible field range (greenish hue, some chroma for
//    their luminance) -- but not a set brighter, greyer and thin like a line -- define THIS
//    image's field colour range (hue, saturation, luminance, chroma per luminance percentiles);
//    every region is then classified field by that range.
// 3. White: the image's white point is the median chroma per luminance of the regions that
//    stand out brightly from the field on both sides (lines, robots, balls; taken across the
//    field's own colour direction, so that it follows a light's cast, e.g. orange at 2700 K
//    without white balance). A region is white when it is clearly brighter than the field's
//    median (and not darker than 0.9 of the image's mean) and greyer about the white point
//    than the field, or -- where sun and shadow defeat global thresholds -- clearly brighter
//    and greyer than the field regions beside it. A region much longer than a line is thick,
//    in the field's hue with half its chroma or more, is field (a washed-out sunlit patch).
// 3b. Sensor saturation: where the sensor clips, R = G = B at one level and colourless
//    regions pile up at one luminance -- a spike in the histogram that gives THIS image's
//    clipping level (213 in real image 00159, 255 in the simulator's bright light). A clipped
//    area (long saturated stretches crossing each other on both scan directions, in a big
//    colourless united set) and its blurred edges are left Unknown: no colour, so neither
//    field nor white, and no line spot or field colour comes from it. A clipped line stays
//    white (long one way only), and so does a clipped goal post or robot that merely touches a
//    clipped area. The field boundary takes Unknown as neutral, as it takes white.
// 3c. Wide white: a white stretch that is long along its scan line and, measured across it on
//    the scan lines of the other direction (or the neighbouring vertical lines), more than two
//    line widths wide on the ground is no paint (a line is one width wide at any angle): in the
//    field's hue about the white point -- a washed-out sunlit carpet between shadow stripes, as
//    in real image 00159 -- it is field.
// 3d. Near the clipping level: where a region's brightest channel is within kNearClip (5 %)
//    below this image's clipping level, the sensor has cut that channel and its chroma is a
//    lower bound, not a measurement. White there, more than two line sizes thick and in the
//    field's hue about the white point (sunlit carpet whose green clips, touching a foot or a
//    robot, where step 3c cannot measure its width), is left Unknown like a clipped area. A line
//    at the clipping level is R = G = B, without hue, and stays white.
// 4. Cleanup: white specks much thinner than a line between field are field; same-class
//    neighbours on a line merge; small gaps between a field and a white region are split
//    between them.
//
// The field boundary needs the regions, and the regions should end at the boundary: run
// computeScanLineRegions without a boundary, find the boundary, then cutAtBoundary (which
// trims without rescanning) -- segmentField does exactly that plus the obstacles, in one scan
// (about 0.5 ms for a 640x480 image on one core).
#include "perception/CameraModel.h"
#include "perception/vision/ScanGrid.h"
#include "perception/vision/VisionTypes.h"

namespace nao {

// boundary (nullable): the scan lines start at it.
ScanLineRegions computeScanLineRegions(const CameraImage& image, const ScanGrid& grid, const FieldBoundary* boundary);

// The regions below the boundary: vertical lines start at it (the region it cuts keeps its
// class and colour), horizontal lines keep only their stretch below it.
ScanLineRegions cutAtBoundary(const ScanLineRegions& regions, const FieldBoundary& boundary);

// The first half of the vision in one call: grid, regions (one scan), boundary, cut,
// obstacles.
struct FieldSegmentation {
  ScanGrid grid;
  ScanLineRegions regions;  // cut at the boundary
  FieldBoundary boundary;
  ObstaclesPercept obstacles;
};
FieldSegmentation segmentField(const CameraImage& image, const CameraMatrix& cm, double lineWidthM = 0.05);

}  // namespace nao
