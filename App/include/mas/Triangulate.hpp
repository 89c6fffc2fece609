// Triangles of planar regions, for drawing: a layer's prism as the build preview shows it, made
// from the layer's regions in microseconds where OCCT's face making and meshing took about two
// milliseconds a region (issue: the preview's first drawing of a thousand layers).
//
// triangulate() is ear clipping (Eberly, "Triangulation by Ear Clipping") after each hole is joined
// to the outer boundary by a bridge: the hole's rightmost point to the outer point it sees first
// along +X (or, where a reflex point hides that one, the reflex point nearest the ray's
// direction), holes taken rightmost first so that a later hole may join an earlier one. No point
// is added. A loop's repeated consecutive points (and a last point repeating the first) count as
// one; a loop with under three distinct points, or no area, adds nothing. Ears are clipped while
// the point tests find them; on a polygon they cannot finish (touching or crossing loops, which
// a section does not make), points on a straight line are dropped, then the remaining convex
// corners are clipped regardless, so that it always ends: the triangles then cover the outline
// but may overlap. An ear test looks only at the corners that are not convex, kept in a grid
// (testing every point of the ring made it quadratic). `mas_bench` times it against OCCT making
// the face and meshing it (BRepMesh): a circle of 3000 points 0.035 ms against 306 ms, a ring of
// 3000 points round a hole of 1500 2.1 ms against 1.9 s, a disc of 400 points with 25 holes of 40
// 0.23 ms against 44 ms.
#pragma once

#include <array>
#include <vector>

#include "mas/Mesh.hpp"
#include "mas/Polygon2.hpp"
#include "mas/Section.hpp"

namespace mas {

// Triangles covering `region`, counter-clockwise, as indices into its points numbered outer loop
// first, then each hole in turn. Either orientation of a loop is taken (the outer is the outer,
// the holes are holes). For n distinct points in 1 + h loops, n + 2h - 2 triangles whose areas
// add up to area(region).
std::vector<std::array<int, 3>> triangulate(const Region2& region);

// The closed surface of `regions` (in PlaneFrame(plane.normal) coordinates, on `plane`) swept
// back along -plane.normal by `depth_mm` > 0: per region its face on the plane (triangulate), the
// same face `depth_mm` below, reversed, and a wall of two triangles along each edge; every
// triangle counter-clockwise seen from outside, vertices shared where faces meet (check_mesh finds
// it closed). Vertices: per region, its points on the plane in triangulate()'s numbering, then the
// same points below. Regions adding no triangle add nothing.
TriangleMesh prism_mesh(const Regions2& regions, const Plane& plane, double depth_mm);

}  // namespace mas
