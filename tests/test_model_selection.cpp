// Model selection (fitting/model_selection.h): each quadric type meshed in a random pose
// keeps its type, clean and with noise, and the special types give their parameters.
#include "fitting/fit.h"
#include "fitting/model_selection.h"
#include "geometry/moments.h"
#include "shapes.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <random>
#include <set>

using namespace vqsa;

namespace {

struct Patch {
    Samples vertices;  // each vertex once
    Quadric general;   // the region's fit, as the Lloyd stage gives it
};

// `noise`: Gaussian displacement along the normal, relative to `size`.
Patch mesh_patch(const test::Surface& surface, const Eigen::Matrix3d& R, const Vec3& t, double noise, double size,
                 std::mt19937& rng, int n = 60) {
    std::normal_distribution<double> gauss(0, 1);
    Shape shape = make_grid(surface.point, surface.u0, surface.u1, surface.v0, surface.v1, n, n);
    for (Vec3& p : shape.mesh.vertices) {
        const Vec3 g = surface.quadric.gradient(p);
        if (noise > 0 && g.norm() > 0) p += noise * size * gauss(rng) * g.normalized();
    }
    transform(shape.mesh, R, t);
    Patch patch;
    std::set<int> used;
    Moments m{};
    for (const Triangle& tri : shape.mesh.triangles) {
        for (int v : tri) used.insert(v);
        add_to(m, triangle_moments(shape.mesh.vertices[tri[0]], shape.mesh.vertices[tri[1]], shape.mesh.vertices[tri[2]]));
    }
    for (int v : used) patch.vertices.add(shape.mesh.vertices[v], 1.0);
    patch.general = fit_region(m).quadric;
    return patch;
}

double angle_degrees(const Vec3& a, const Vec3& b) {
    return std::acos(std::min(1.0, std::abs(a.normalized().dot(b.normalized())))) * 180 / M_PI;
}

}  // namespace

TEST(ModelSelection, EveryTypeKeepsItsTypeFromACleanMesh) {
    std::mt19937 rng(5);
    for (const test::Surface& surface : test::surfaces()) {
        SCOPED_TRACE(surface.name);
        const Patch patch = mesh_patch(surface, test::random_rotation(rng), Vec3(0.3, -1, 2), 0, 1, rng);
        const ModelChoice choice = select_model(patch.vertices, patch.general);
        EXPECT_STREQ(type_name(choice.chosen.type), type_name(surface.type)) << "RMS " << choice.chosen.rms;
        if (surface.type == QuadricType::plane) continue;  // nothing else is fitted to a plane
        ASSERT_TRUE(choice.runner_up.has_value());
        EXPECT_NE(choice.runner_up->type, choice.chosen.type);
        EXPECT_GT(choice.runner_up->bic, choice.chosen.bic);
    }
}

TEST(ModelSelection, NoiseDoesNotAddParameters) {
    // 0.2 % of the patch's size along the normals: a plane stays a plane, a sphere a
    // sphere, a cylinder a cylinder, with their parameters.
    std::mt19937 rng(17);
    for (const test::Surface& surface : test::surfaces()) {
        if (surface.type != QuadricType::plane && surface.type != QuadricType::sphere &&
            surface.type != QuadricType::cylinder && surface.type != QuadricType::cone)
            continue;
        SCOPED_TRACE(surface.name);
        const Eigen::Matrix3d R = test::random_rotation(rng);
        const Vec3 t(1.5, -0.5, 2.0);
        const double size = surface.type == QuadricType::sphere ? 2.0 : 2.2;  // about the patch's diagonal
        const Patch patch = mesh_patch(surface, R, t, 0.002, size, rng, 80);
        const ModelChoice choice = select_model(patch.vertices, patch.general);
        EXPECT_STREQ(type_name(choice.chosen.type), type_name(surface.type)) << "RMS " << choice.chosen.rms;
        const Classification& s = choice.chosen.shape;
        switch (surface.type) {
            case QuadricType::plane: EXPECT_LT(angle_degrees(s.axis(), R.col(2)), 0.1); break;
            case QuadricType::sphere:
                EXPECT_NEAR(s.radius, 1.0, 0.01);
                EXPECT_LT((s.center - t).norm(), 0.01);
                break;
            case QuadricType::cylinder:
                EXPECT_NEAR(s.radius / 0.8, 1.0, 0.01);
                EXPECT_LT(angle_degrees(s.axis(), R.col(2)), 1.0);
                break;
            default:
                EXPECT_NEAR(s.half_angle * 180 / M_PI, 30.0, 0.5);
                EXPECT_LT(angle_degrees(s.axis(), R.col(2)), 1.0);
                break;
        }
    }
}

TEST(ModelSelection, CleanParametersAreExact) {
    std::mt19937 rng(23);
    for (const test::Surface& surface : test::surfaces()) {
        if (surface.type != QuadricType::sphere && surface.type != QuadricType::cylinder && surface.type != QuadricType::cone)
            continue;
        SCOPED_TRACE(surface.name);
        const Eigen::Matrix3d R = test::random_rotation(rng);
        const Vec3 t(-2, 0.5, 1);
        const ModelChoice choice = select_model(mesh_patch(surface, R, t, 0, 1, rng).vertices,
                                                mesh_patch(surface, R, t, 0, 1, rng).general);
        const Classification& s = choice.chosen.shape;
        ASSERT_EQ(choice.chosen.type, surface.type);
        if (surface.type == QuadricType::sphere) {
            EXPECT_NEAR(s.radius, 1.0, 1e-6);
            EXPECT_LT((s.center - t).norm(), 1e-6);
        } else if (surface.type == QuadricType::cylinder) {
            EXPECT_NEAR(s.radius, 0.8, 1e-6);
            EXPECT_LT(angle_degrees(s.axis(), R.col(2)), 1e-4);
        } else {
            EXPECT_NEAR(s.half_angle * 180 / M_PI, 30.0, 1e-4);
            EXPECT_LT((s.center - t).norm(), 1e-6);
        }
    }
}

TEST(ModelSelection, APlanePairIsNeverChosen) {
    // An L of two perpendicular squares: the general quadric is the pair of planes, which
    // no region may be; a single-part surface is chosen instead.
    Samples samples;
    for (int i = 0; i <= 20; ++i)
        for (int j = 0; j <= 20; ++j) {
            samples.add(Vec3(i / 20.0, j / 20.0, 0), 1);
            if (i > 0) samples.add(Vec3(0, j / 20.0, i / 20.0), 1);
        }
    Quadric pair;  // x z = 0
    pair.c[6] = 1;
    const ModelChoice choice = select_model(samples, pair);
    EXPECT_FALSE(has_two_parts(choice.chosen.type)) << type_name(choice.chosen.type);
    EXPECT_TRUE(choice.chosen.special);
}
