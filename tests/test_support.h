// Canonical quadric surfaces with their parametrisations, shared by the tests.
#pragma once

#include "fitting/classify.h"
#include "fitting/quadric.h"
#include "pipeline/pipeline.h"

#include <functional>
#include <random>
#include <string>
#include <vector>

namespace vqsa::test {

struct Surface {
    std::string name;
    QuadricType type;
    Quadric quadric;  // canonical pose
    std::function<Vec3(double, double)> point;
    double u0, u1, v0, v1;  // a patch of the surface
};

// One surface of each type that has a parametrisation (all but the plane pairs).
std::vector<Surface> surfaces();

Eigen::Matrix3d random_rotation(std::mt19937& rng);

// f(R⁻¹ (q - t)): the quadric moved by p → R p + t.
Quadric moved(const Quadric& f, const Eigen::Matrix3d& rotation, const Vec3& translation);

// Directory of ../shared/meshes.
std::string shared_mesh(const std::string& name);

Options with_proxies(int count, std::uint64_t seed = 1);

// The message of the std::invalid_argument that `f` throws, or "" when it throws none.
std::string invalid_argument_of(const std::function<void()>& f);

// A whole run; `progress` (if any) sees every step.
Result approximate(const Mesh& mesh, const Options& options, const ProgressCallback& progress = {});

}  // namespace vqsa::test
