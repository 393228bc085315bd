// Triangles of a polygon as a mesh file gives it (docs/METHOD.md §1).
#pragma once

#include "io/mesh.h"

#include <cstddef>
#include <vector>

namespace vqsa {

// Appends to `out` the count − 2 triangles of a planar polygon (`polygon[i]`: indices into
// `points`, in order round it). A convex polygon gets the fan from its first vertex; a
// concave one (a wall round a notch, as CAD programs write faces) is cut ear by ear in the
// plane of its Newell normal, where the fan would lay triangles outside it. Degenerate
// triangles (collinear vertices) are kept: the caller drops them.
void triangulate_polygon(const std::vector<Vec3>& points, const int* polygon, std::size_t count,
                         std::vector<Triangle>& out);

}  // namespace vqsa
