// Nearest-triangle queries (geometry/bvh.h) against brute force.
#include "geometry/bvh.h"
#include "shapes.h"

#include <gtest/gtest.h>

#include <limits>
#include <random>

using namespace vqsa;

namespace {

struct Brute {
    double distance = std::numeric_limits<double>::infinity();
    int triangle = -1;
};

Brute brute_nearest(const Mesh& mesh, const Vec3& p) {
    Brute best;
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
        const Triangle& tri = mesh.triangles[t];
        const double d =
            (closest_point_on_triangle(p, mesh.vertices[tri[0]], mesh.vertices[tri[1]], mesh.vertices[tri[2]]) - p).norm();
        if (d < best.distance) best = {d, static_cast<int>(t)};
    }
    return best;
}

}  // namespace

TEST(Bvh, ClosestPointOnATriangleInEachRegion) {
    // The seven Voronoi regions of a triangle: inside, three edges, three vertices.
    const Vec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
    EXPECT_TRUE(closest_point_on_triangle({0.2, 0.2, 3}, a, b, c).isApprox(Vec3(0.2, 0.2, 0)));
    EXPECT_TRUE(closest_point_on_triangle({0.5, -1, 1}, a, b, c).isApprox(Vec3(0.5, 0, 0)));
    EXPECT_TRUE(closest_point_on_triangle({-1, 0.5, 0}, a, b, c).isApprox(Vec3(0, 0.5, 0)));
    EXPECT_TRUE(closest_point_on_triangle({1, 1, 0}, a, b, c).isApprox(Vec3(0.5, 0.5, 0)));
    EXPECT_LT(closest_point_on_triangle({-1, -1, 2}, a, b, c).norm(), 1e-15);
    EXPECT_TRUE(closest_point_on_triangle({3, -0.5, 0}, a, b, c).isApprox(b));
    EXPECT_TRUE(closest_point_on_triangle({-0.5, 3, -1}, a, b, c).isApprox(c));
}

TEST(Bvh, NearestMatchesBruteForce) {
    // A closed capsule and a scatter of loose triangles, queried from points near the
    // surface, inside, and far away.
    Mesh mesh = make_capsule(0.5, 1.0, 24, 8).mesh;
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-2, 2);
    for (int k = 0; k < 50; ++k) {
        const int first = static_cast<int>(mesh.vertices.size());
        const Vec3 centre(u(rng), u(rng), u(rng));
        for (int j = 0; j < 3; ++j) mesh.vertices.push_back(centre + 0.1 * Vec3(u(rng), u(rng), u(rng)));
        mesh.triangles.push_back({first, first + 1, first + 2});
    }
    const TriangleTree tree(mesh.vertices, mesh.triangles);
    std::uniform_real_distribution<double> far(-10, 10);
    for (int q = 0; q < 2000; ++q) {
        const Vec3 p = q % 4 == 0 ? Vec3(far(rng), far(rng), far(rng)) : Vec3(u(rng), u(rng), u(rng));
        const Brute expected = brute_nearest(mesh, p);
        const TriangleTree::Hit hit = tree.nearest(p);
        ASSERT_NEAR(hit.distance, expected.distance, 1e-12) << "query " << q;
        EXPECT_NEAR((hit.point - p).norm(), hit.distance, 1e-12);
        // The triangle may differ only on a tie (a shared edge or vertex).
        const Triangle& t = mesh.triangles[hit.triangle];
        EXPECT_NEAR((closest_point_on_triangle(p, mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]]) - p).norm(),
                    expected.distance, 1e-12);
    }
}

TEST(Bvh, OneTriangleAndDegenerateOnes) {
    const std::vector<Vec3> points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {2, 2, 2}};
    const std::vector<Triangle> one = {{0, 1, 2}};
    EXPECT_NEAR(TriangleTree(points, one).nearest({0.25, 0.25, -4}).distance, 4, 1e-15);
    // A triangle collapsed to a point still answers with that point.
    const std::vector<Triangle> collapsed = {{3, 3, 3}, {0, 1, 2}};
    const TriangleTree::Hit hit = TriangleTree(points, collapsed).nearest({2, 2, 2.5});
    EXPECT_EQ(hit.triangle, 0);
    EXPECT_NEAR(hit.distance, 0.5, 1e-15);
}
