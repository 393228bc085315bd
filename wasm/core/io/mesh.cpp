#include "io/mesh.h"
#include "io/triangulate.h"

#include <cmath>
#include <cstring>
#include <stdexcept>
#include <unordered_map>

namespace vqsa {

void PolygonSoup::add_polygon(const int* first, std::size_t count) {
    indices.insert(indices.end(), first, first + count);
    polygon_start.push_back(static_cast<int>(indices.size()));
}

namespace {

struct PositionKey {
    std::uint64_t x, y, z;
    bool operator==(const PositionKey& o) const { return x == o.x && y == o.y && z == o.z; }
};

struct PositionHash {
    std::size_t operator()(const PositionKey& k) const {
        std::uint64_t h = k.x * 0x9E3779B97F4A7C15ull;
        h ^= k.y + 0x632BE59BD9B4E019ull + (h << 6) + (h >> 2);
        h ^= k.z + 0x85157AF5ull + (h << 6) + (h >> 2);
        return static_cast<std::size_t>(h ^ (h >> 29));
    }
};

std::uint64_t bits(double v) {
    if (v == 0.0) v = 0.0;  // -0 and +0 are the same point
    std::uint64_t b;
    std::memcpy(&b, &v, sizeof b);
    return b;
}

}  // namespace

Mesh build_mesh(const PolygonSoup& soup) {
    const std::size_t n = soup.positions.size();
    for (std::size_t i = 0; i < n; ++i) {
        if (!soup.positions[i].allFinite())
            throw std::invalid_argument("vertex " + std::to_string(i) +
                                        " has a coordinate that is not a finite number");
        // Squared lengths must not overflow.
        if (soup.positions[i].cwiseAbs().maxCoeff() > 1e150)
            throw std::invalid_argument("vertex " + std::to_string(i) + " has a coordinate beyond ±1e150");
    }
    for (std::size_t i = 0; i < soup.indices.size(); ++i) {
        const int v = soup.indices[i];
        if (v < 0 || static_cast<std::size_t>(v) >= n)
            throw std::invalid_argument("face index " + std::to_string(v) + " is out of range (the file has " +
                                        std::to_string(n) + " vertices)");
    }

    Mesh mesh;
    // Weld exact duplicates (STL is a triangle soup).
    std::vector<int> welded(n);
    {
        std::unordered_map<PositionKey, int, PositionHash> index_of;
        index_of.reserve(n);
        for (std::size_t v = 0; v < n; ++v) {
            const Vec3& p = soup.positions[v];
            auto [it, inserted] =
                index_of.try_emplace({bits(p.x()), bits(p.y()), bits(p.z())}, static_cast<int>(mesh.vertices.size()));
            if (inserted) mesh.vertices.push_back(p);
            welded[v] = it->second;
        }
    }
    mesh.input_vertex_count = static_cast<int>(mesh.vertices.size());

    int triangles_in = 0;
    std::vector<Triangle> pieces;
    for (std::size_t f = 0; f < soup.polygon_count(); ++f) {
        const int begin = soup.polygon_start[f], end = soup.polygon_start[f + 1];
        pieces.clear();
        triangulate_polygon(soup.positions, soup.indices.data() + begin, static_cast<std::size_t>(end - begin), pieces);
        for (const Triangle& piece : pieces) {
            const int source = triangles_in++;
            const Triangle t{welded[piece[0]], welded[piece[1]], welded[piece[2]]};
            if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) continue;
            const Vec3& a = mesh.vertices[t[0]];
            const Vec3 e1 = mesh.vertices[t[1]] - a, e2 = mesh.vertices[t[2]] - a;
            const double twice_area = e1.cross(e2).norm();
            const double longest2 = std::max({e1.squaredNorm(), e2.squaredNorm(), (e2 - e1).squaredNorm()});
            // Collinear to rounding: the cross product is noise at 1e-15 of the edges.
            if (!(twice_area > 1e-13 * longest2)) continue;
            mesh.triangles.push_back(t);
            mesh.source_face.push_back(source);
        }
    }
    mesh.input_face_count = triangles_in;
    // The algorithms work in the unit frame (centred, longest side 1): a triangle that is
    // degenerate there, its size lost to rounding against the model's extent, goes too.
    if (!mesh.triangles.empty()) {
        const Frame frame = unit_frame(mesh);
        std::size_t kept = 0;
        for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
            const Triangle& tri = mesh.triangles[t];
            const Vec3 a = frame.to_unit(mesh.vertices[tri[0]]);
            const Vec3 e1 = frame.to_unit(mesh.vertices[tri[1]]) - a, e2 = frame.to_unit(mesh.vertices[tri[2]]) - a;
            const double longest2 = std::max({e1.squaredNorm(), e2.squaredNorm(), (e2 - e1).squaredNorm()});
            if (!(e1.cross(e2).norm() > 1e-13 * longest2)) continue;
            mesh.triangles[kept] = tri;
            mesh.source_face[kept] = mesh.source_face[t];
            ++kept;
        }
        mesh.triangles.resize(kept);
        mesh.source_face.resize(kept);
    }
    if (triangles_in == 0) throw std::invalid_argument("the file has no faces");
    if (mesh.triangles.empty())
        throw std::invalid_argument("all " + std::to_string(triangles_in) + " triangles are degenerate (zero area)");

    // Vertices no kept triangle uses stay: harmless, and the numbering stays simple.
    return mesh;
}

BoundingBox bounding_box(const Mesh& mesh) {
    BoundingBox box;
    for (const Triangle& t : mesh.triangles)
        for (int v : t) {
            box.min = box.min.cwiseMin(mesh.vertices[v]);
            box.max = box.max.cwiseMax(mesh.vertices[v]);
        }
    return box;
}

Frame unit_frame(const Mesh& mesh) {
    const BoundingBox box = bounding_box(mesh);
    Frame frame;
    frame.translation = box.center();
    frame.scale = box.size().maxCoeff();
    if (!(frame.scale > 0.0) || !std::isfinite(frame.scale))
        throw std::invalid_argument("the mesh has no extent");
    return frame;
}

}  // namespace vqsa
