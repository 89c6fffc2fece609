// Planar polygons with holes and their Booleans and offsets, in a section plane's 2-D frame.
// Paper Eq. 2 (upper section minus its overlap with the lower one) is built from these. Clipper
// does the work behind this header: coordinates are snapped to a 1e-5 mm integer grid inside it.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <utility>
#include <vector>

namespace mas {

// A closed polygon; the last point is not repeated. Orientation carries meaning: counter-clockwise
// (positive signed area) for outer boundaries, clockwise for holes.
struct Polygon2 {
    std::vector<Eigen::Vector2d> points;  // mm
};

// One connected region: an outer boundary (CCW) and the holes inside it (CW).
struct Region2 {
    Polygon2 outer;
    std::vector<Polygon2> holes;
};

using Regions2 = std::vector<Region2>;

// Signed area (mm^2, > 0 for CCW) and area centroid of a single polygon.
double signed_area(const Polygon2& polygon);
Eigen::Vector2d centroid(const Polygon2& polygon);

// Area of a region (outer minus holes) and its centroid; area of a set of regions, and their
// centroid (each region's weighted by its area; the origin where they have none).
double area(const Region2& region);
double area(const Regions2& regions);
Eigen::Vector2d centroid(const Region2& region);
Eigen::Vector2d centroid(const Regions2& regions);
Eigen::AlignedBox2d bounds(const Region2& region);

// The length of a closed polygon's outline, its closing edge included (mm; 0 below two points);
// of a region's loops, its holes' included; of every loop of a set of regions.
double perimeter(const Polygon2& polygon);
double perimeter(const Region2& region);
double perimeter(const Regions2& regions);

// True if the point lies inside the region (inside the outer loop and outside every hole).
bool contains(const Region2& region, const Eigen::Vector2d& point);

// The intervals, along the other coordinate and in increasing order, where the line
// {q[coord] = value} (coord 0: x, 1: y) runs inside the region: crossings with every loop of at
// least three points, even-odd (a vertex on the line counts as above it).
std::vector<std::pair<double, double>> inside_intervals(const Region2& region, int coord,
                                                        double value);

// A point in the region's material, away from its outline: the middle of the widest inside span
// of the horizontal line through its centroid (through its box's middle when that line has
// none). Unlike the centroid it never lies in a hole (a ring's bore) or outside a C's mouth. The
// centroid for a region too thin to have a span; the origin for an empty one.
Eigen::Vector2d interior_point(const Region2& region);

// Groups oriented closed loops into regions: CCW loops are outer boundaries, CW loops are holes,
// each hole going to the smallest outer loop that contains it (a hole inside no outer loop is
// dropped). This is what cutting a closed, outward-oriented mesh gives. Loops with |area| below
// `min_area_mm2` are dropped. Regions come largest area first.
Regions2 regions_from_loops(std::vector<Polygon2> loops, double min_area_mm2 = 0.0);

// Booleans. Results are regions with CCW outers and CW holes; empty results are empty vectors.
Regions2 intersection(const Regions2& a, const Regions2& b);
Regions2 difference(const Regions2& a, const Regions2& b);
Regions2 union_of(const Regions2& a, const Regions2& b);

// Simplifies a closed polygon: drops a point where the outline turns by less than 15 degrees if
// every point dropped since the last kept one lies within `tolerance_mm` of the new edge. Corners
// stay, so exact outlines stay exact; faceted curves lose most of their points. Keeps orientation
// and at least three points.
Polygon2 simplify(const Polygon2& polygon, double tolerance_mm);
Region2 simplify(const Region2& region, double tolerance_mm);

enum class JoinType { Miter, Round, Square };

// Grows (delta > 0) or shrinks (delta < 0) regions by `delta_mm`. Round joins approximate arcs
// within `arc_tolerance_mm`.
Regions2 offset(const Regions2& regions, double delta_mm, JoinType join = JoinType::Round,
                double arc_tolerance_mm = 0.01);

}  // namespace mas
