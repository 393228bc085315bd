// Triangle meshes as vqsa reads them and as the algorithms see them.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <array>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

namespace vqsa {

using Vec3 = Eigen::Vector3d;
using Triangle = std::array<int, 3>;

// What a reader produces: positions and polygons exactly as stored in the file.
struct PolygonSoup {
    std::vector<Vec3> positions;
    std::vector<int> polygon_start;  // polygon i is indices[polygon_start[i] .. polygon_start[i+1])
    std::vector<int> indices;

    PolygonSoup() { polygon_start.push_back(0); }
    std::size_t polygon_count() const { return polygon_start.size() - 1; }
    void add_polygon(const int* first, std::size_t count);
};

// A cleaned triangle mesh in the input's coordinates: duplicate positions welded,
// polygons fanned, degenerate triangles dropped. `source_face` maps every kept
// triangle back to its position among the input's fanned triangles, so results can be
// reported in the input's own face order.
struct Mesh {
    std::vector<Vec3> vertices;
    std::vector<Triangle> triangles;
    std::vector<int> source_face;
    int input_vertex_count = 0;  // distinct positions in the file
    int input_face_count = 0;  // fanned triangles, including the dropped ones

    std::size_t face_count() const { return triangles.size(); }
};

// Welds positions that are exactly equal, fans polygons (v0, vi, vi+1), drops
// triangles that repeat a vertex or whose area is zero to rounding.
// Throws std::invalid_argument on NaN/inf coordinates, out-of-range indices, or when
// nothing usable remains.
Mesh build_mesh(const PolygonSoup& soup);

struct BoundingBox {
    Vec3 min = Vec3::Constant(std::numeric_limits<double>::infinity());
    Vec3 max = Vec3::Constant(-std::numeric_limits<double>::infinity());
    Vec3 size() const { return max - min; }
    Vec3 center() const { return 0.5 * (min + max); }
    double diagonal() const { return size().norm(); }
};

BoundingBox bounding_box(const Mesh& mesh);

// The similarity p_input = scale * p + translation between the unit frame the
// algorithms work in (centred, longest bounding-box side 1) and the input's frame.
struct Frame {
    double scale = 1.0;
    Vec3 translation = Vec3::Zero();

    Vec3 to_input(const Vec3& p) const { return scale * p + translation; }
    Vec3 to_unit(const Vec3& p) const { return (p - translation) / scale; }
};

Frame unit_frame(const Mesh& mesh);

}  // namespace vqsa
