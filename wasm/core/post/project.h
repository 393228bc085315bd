// Projection of points and meshes onto proxies (docs/METHOD.md §9).
#pragma once

#include "fitting/classify.h"
#include "geometry/model.h"
#include "fitting/quadric.h"

#include <optional>
#include <vector>

namespace vqsa {

// The nearest point of {f = 0} to p, for a general quadric: in the eigenframe of A the
// Lagrange condition gives x_i(μ) = (p_i − μ β_i / 2) / (1 + μ λ_i); f(x(μ)) = 0 cleared
// of denominators is a polynomial of degree ≤ 6 whose real roots (companion matrix,
// polished by Newton) are the candidates. Empty when no candidate exists.
std::optional<Vec3> foot_point(const Quadric& f, const Vec3& p);

// Closed forms for plane, sphere, cylinder and cone.
Vec3 special_foot_point(const Classification& shape, const Vec3& p);

// One proxy as the projection sees it: its quadric, and its special shape when the
// quadric is exactly that shape (then the closed form is used).
struct ProjectionTarget {
    Quadric quadric;
    std::optional<Classification> special;
};

// Every vertex moves to the mean of its foot points on the proxies of its faces.
// Foot points farther than `max_distance` (unit frame) are ignored, a guard against
// far-away roots; a vertex without any stays where it is. Returns positions in the
// unit frame, one per model point.
std::vector<Vec3> project_vertices(const Model& model, const std::vector<int>& labels,
                                   const std::vector<ProjectionTarget>& targets, double max_distance);

}  // namespace vqsa
