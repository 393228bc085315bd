// Projection of points and meshes onto proxies (docs/METHOD.md §9).
#pragma once

#include "fitting/classify.h"
#include "geometry/model.h"
#include "fitting/quadric.h"

#include <optional>
#include <vector>

namespace vqsa {

// The nearest point of {f = 0} to p, for a general quadric, set up once per quadric for
// many points. In the eigenframe of A the Lagrange condition gives
// x_i(μ) = (p_i − μ β_i / 2) / (1 + μ λ_i). Where every 1 + μ λ_i > 0, F(μ) = f(x(μ)) is
// decreasing (it is the derivative of the concave dual function), and its root there is the
// global minimum (strong duality with one quadratic constraint): a bracketed Newton
// iteration started at μ = 0 finds it in a few steps. Only when that root does not exist
// (p on a symmetry axis or plane: the "hard case") are all the real roots of F cleared of
// denominators — a polynomial of degree ≤ 6, by its companion matrix — the candidates.
// Empty when no candidate exists.
class FootPoint {
public:
    explicit FootPoint(const Quadric& f);
    std::optional<Vec3> operator()(const Vec3& p) const;
    // The polynomial's candidates only (the fallback; exposed for tests).
    std::optional<Vec3> by_polynomial(const Vec3& p) const;

private:
    Quadric f_;
    Eigen::Matrix3d R_;  // eigenvectors of A
    Vec3 lambda_;        // eigenvalues, ascending
};

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
// far-away roots; a vertex without any stays where it is. In pieces of
// `vertices_per_step` vertices; the model and labels must outlive the projector.
class Projector {
public:
    Projector(const Model& model, const std::vector<int>& labels, const std::vector<ProjectionTarget>& targets,
              double max_distance, int vertices_per_step = 50000);
    bool step();  // false once every vertex is done
    double fraction() const;
    // Positions in the unit frame, one per model point, once step() has returned false.
    std::vector<Vec3> take() { return std::move(out_); }

private:
    const Model& model_;
    const std::vector<int>& labels_;
    std::vector<ProjectionTarget> targets_;
    std::vector<FootPoint> solvers_;
    double max_distance_;
    int vertices_per_step_;
    std::vector<int> first_face_, next_face_;  // per vertex: its faces as a linked list
    std::vector<Vec3> out_;
    std::size_t next_ = 0;
};

}  // namespace vqsa
