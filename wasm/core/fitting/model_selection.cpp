#include "fitting/model_selection.h"

#include "fitting/distance.h"
#include "fitting/least_squares.h"
#include "fitting/special_fit.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

namespace vqsa {

namespace {

// Whether a candidate's samples lie on two parts of its surface, so that no region could be
// it. Under noise a cone's nappes count as two parts wherever its apex: classify takes a
// region whose centroid lies within twice its RMS radius of the apex to run through it,
// and a noisy octagon bore's face came out a cone of half-angle 89.8° whose apex lay
// beside the face, inside that bound; the two nappes, apart there by less than the noise,
// each held the vertices on its side, at half the plane's RMS. A region through a cone's
// apex (a pencil's tip) lies on one nappe. On a mesh judged clean, flat cones straddled
// regions over two faces, which are validity's to split (docs/METHOD.md §6).
bool on_two_parts(Classification c, const Samples& s, double margin) {
    if (s.noise > 0 && (c.type == QuadricType::cone || c.type == QuadricType::elliptic_cone)) c.nappes_apart = true;
    if (!has_two_parts(c)) return false;
    PartWeights parts;
    for (std::size_t i = 0; i < s.points.size(); ++i) {
        const int side = part_of(c, s.points[i], margin);
        if (side != 0) parts.weight[side > 0 ? 0 : 1] += s.weights[i], ++parts.count[side > 0 ? 0 : 1];
    }
    return parts.both(s.total_weight);
}

// Where selection_rms caps each point's distance: at kNoiseCap × the samples' noise on a
// noisy mesh. There a region holding a few faces of
// its neighbour (a plate's rim, nine σ off its face) paid, with them alone, for a bent
// type's parameters: the noisy plate assembly's large faces came out as spheres of radius
// 45 and flat cones, the plane second. Beyond about 3 σ a point tells of the partition,
// not of the region's surface.
constexpr double kNoiseCap = 3.5;

}  // namespace

double selection_rms(const Samples& s, const Quadric& q) {
    return s.noise > 0 ? taubin_rms(s, q, kNoiseCap * s.noise) : taubin_rms(s, q);
}

namespace {

// Whether a candidate is of the imposed type.
bool of_type(const TypedFit& c, ImposedType type) {
    switch (type) {
        case ImposedType::none: return true;
        case ImposedType::plane: return c.special && c.type == QuadricType::plane;
        case ImposedType::sphere: return c.special && c.type == QuadricType::sphere;
        case ImposedType::cylinder: return c.special && c.type == QuadricType::cylinder;
        case ImposedType::cone: return c.special && c.type == QuadricType::cone;
        case ImposedType::quadric: return !c.special;
    }
    return false;
}

// How much farther (in distance) a candidate may lie from a region's edge midpoints than
// the candidate lying nearest them, beyond the tessellation's deviation.
constexpr double kRunAway = 10;

// Mean squared Taubin distance of a region's edge midpoints to q; with `beyond_tolerance`,
// only what lies beyond each midpoint's chordal deviation counts (a chord strays from its
// surface by that much, and a surface that holds the chord closer is no likelier).
double midpoint_mean_square(const Samples& s, const Quadric& q, bool beyond_tolerance) {
    const double a = q.hessian_norm();
    double sum = 0;
    for (std::size_t i = 0; i < s.edge_midpoints.size(); ++i) {
        const double d = taubin_distance(q, a, s.edge_midpoints[i]);
        const double t = beyond_tolerance ? s.midpoint_tolerances[i] : 0;
        sum += std::max(d * d - t * t, 0.0);
    }
    return sum / s.edge_midpoints.size();
}

// Among candidates sorted by the criterion, the simplest reached from the first (the best)
// by steps that each depart from the type they replace by less than the samples' scatter:
// a mean square at most scatter² above it (the replaced type being the surface, the simpler
// one strays from it by that much). An elementary type replaces a general quadric (the
// first elementary one by the criterion: sphere and cylinder are not special cases of each
// other); a cylinder a cone (the cone of apex at infinity); a plane anything. Each step asks
// whether the data resolve the freedom the replaced type has over the simpler one, as
// nested models are tested one step down at a time. With thousands of vertices the
// criterion resolves a quadric that bends away from a cylinder by a fraction of the noise,
// as a remeshed or scanned cylinder's vertices do: a real difference, of the data, not of
// the part.
std::vector<TypedFit>::iterator simplest_within_scatter(std::vector<TypedFit>& candidates, double scatter) {
    auto simplest = candidates.begin();
    // One step down: to the first elementary candidate `admits` takes within the scatter of
    // the type it replaces.
    auto step_down = [&](auto admits) {
        const double allowed = simplest->rms * simplest->rms + scatter * scatter;
        const auto to = std::find_if(candidates.begin(), candidates.end(), [&](const TypedFit& c) {
            return elementary(c) && admits(c) && c.rms * c.rms <= allowed;
        });
        if (to != candidates.end()) simplest = to;
    };
    if (!elementary(*simplest)) step_down([](const TypedFit&) { return true; });
    if (simplest->type == QuadricType::cone) step_down([](const TypedFit& c) { return c.type == QuadricType::cylinder; });
    step_down([](const TypedFit& c) { return c.type == QuadricType::plane; });
    return simplest;
}

// The samples' weighted centroid and RMS radius: the region as classify sees it.
struct Extent {
    Vec3 center;
    double radius;
};
Extent extent_of(const Samples& s) {
    const Vec3 center = weighted_centroid(s);
    double spread = 0;
    for (std::size_t i = 0; i < s.points.size(); ++i) spread += s.weights[i] * (s.points[i] - center).squaredNorm();
    return {center, std::sqrt(spread / s.total_weight) + 1e-300};
}

// Mean squared distances below this count as zero (exact), and below this plus the
// tessellation's deviation as no evidence (floor²): ModelSelectionOptions.
double exact_squared(const Extent& e, const ModelSelectionOptions& options) {
    return (options.floor * e.radius) * (options.floor * e.radius) + options.stored * options.stored;
}

double criterion(const Samples& s, double rms, int parameters, double floor2) {
    const double n = static_cast<double>(s.points.size());
    return n * std::log(rms * rms + floor2) + parameters * std::log(n);
}

// A general quadric as a candidate, typed by its affine type; none if no region could be
// that surface (a pair of planes: the plane candidate is one of them; empty; two parts with
// vertices on both).
std::optional<TypedFit> general_candidate(const Quadric& q, const Samples& s, const Extent& e,
                                          const ClassifyOptions& options) {
    TypedFit g;
    g.quadric = normalized(q);
    g.shape = classify(q, e.center, e.radius, options);
    g.type = q.is_plane() ? QuadricType::plane : g.shape.type;
    g.rms = selection_rms(s, q);
    g.parameters = degrees_of_freedom(g.type);
    const bool pair = g.type == QuadricType::intersecting_planes || g.type == QuadricType::parallel_planes;
    const bool usable = g.type != QuadricType::empty && !pair && !on_two_parts(g.shape, s, 2 * g.rms);
    if (!usable || !std::isfinite(g.rms)) return std::nullopt;
    return g;
}

// The four types a CAD part's faces are made of.
bool cad_type(QuadricType type) {
    return type == QuadricType::plane || type == QuadricType::sphere || type == QuadricType::cylinder ||
           type == QuadricType::cone;
}

constexpr ImposedType kImposedTypes[] = {ImposedType::none, ImposedType::plane, ImposedType::sphere,
                                         ImposedType::cylinder, ImposedType::cone, ImposedType::quadric};

}  // namespace

std::optional<TypedFit> general_fit(const Quadric& q, const Samples& vertices, const ClassifyOptions& options) {
    return general_candidate(q, vertices, extent_of(vertices), options);
}

bool elementary(const TypedFit& c) { return c.special && cad_type(c.type); }

const char* imposed_type_name(ImposedType type) {
    switch (type) {
        case ImposedType::none: return "none";
        case ImposedType::plane: return "plane";
        case ImposedType::sphere: return "sphere";
        case ImposedType::cylinder: return "cylinder";
        case ImposedType::cone: return "cone";
        case ImposedType::quadric: return "quadric";
    }
    return "unknown";
}

ImposedType imposed_type_from(const std::string& name) {
    std::string names;
    for (ImposedType t : kImposedTypes) {
        if (name == imposed_type_name(t)) return t;
        names += std::string(names.empty() ? "" : ", ") + imposed_type_name(t);
    }
    throw std::invalid_argument("unknown type '" + name + "' (one of " + names + ")");
}

ModelChoice select_model(const Samples& s, const Quadric& general, const ModelSelectionOptions& options) {
    std::vector<TypedFit> candidates;
    if (s.points.size() < 3 || !(s.total_weight > 0)) {
        TypedFit only;
        only.quadric = general;
        only.parameters = 9;
        candidates.push_back(only);
        return {only, std::nullopt};
    }
    const Extent extent = extent_of(s);
    const Vec3& center = extent.center;
    const double radius = extent.radius;

    auto add_special = [&](const std::optional<SpecialFit>& fit) {
        if (!fit || !std::isfinite(fit->rms)) return;
        // A geometric fit knows its surface, not the region: where a cone's nappes are
        // apart is judged here, from the samples, as classify judges it for a quadric.
        Classification shape = fit->shape;
        if (shape.type == QuadricType::cone) shape.nappes_apart = nappes_apart(shape.center, center, radius);
        // Every candidate measured alike (Taubin's distance is below the true one, more so
        // away from the surface): a fair contest.
        const double rms = selection_rms(s, fit->quadric);
        if (on_two_parts(shape, s, 2 * rms)) return;
        candidates.push_back({shape.type, fit->quadric, shape, rms, degrees_of_freedom(shape.type), true});
    };
    // Every type's fit, or, without rivals, only the imposed type's.
    const bool every_type = options.rivals || options.imposed == ImposedType::none;
    const auto wanted = [&](ImposedType type) { return every_type || options.imposed == type; };
    if (wanted(ImposedType::plane)) add_special(fit_plane_geometric(s));
    // A region its faces do not determine has a plane for its quadric (a strip: Lloyd's
    // min_quadric_faces and is_strip), though its vertices may not be flat: a plate's rounded
    // corner one facet tall, whose two rows of vertices lie on two circles of its cylinder.
    // Where the plane misses them by more than twice all that explains a miss (the
    // tessellation's deviation, the stored precision, the noise), the sphere and the
    // cylinder are fitted too, the cylinder from each principal direction of the vertices
    // (for a band, its axis is one; the general quadric, a plane, gives none). Each competes
    // if it holds the vertices an order of magnitude closer than the plane: a curved fit
    // also bends to noise, by far less.
    const double exact2 = exact_squared(extent, options);
    const double floor2 = exact2 + s.tolerance * s.tolerance;
    const double explained2 = floor2 + s.noise * s.noise + s.scatter * s.scatter;
    const bool flat_misses = general.is_plane() && !candidates.empty() &&
                             candidates.front().rms * candidates.front().rms > 4 * explained2;
    if (s.points.size() >= 6 && flat_misses && options.imposed == ImposedType::none) {
        const std::size_t planes = candidates.size();
        const double plane_rms = candidates.front().rms;
        add_special(fit_sphere_geometric(s));
        const Eigen::Matrix3d axes = principal_axes(s, center);
        for (int i = 0; i < 3; ++i) add_special(fit_cylinder_geometric(s, axes.col(i)));
        candidates.erase(std::remove_if(candidates.begin() + planes, candidates.end(),
                                        [&](const TypedFit& c) { return !(kRunAway * c.rms <= plane_rms); }),
                         candidates.end());
    }
    if (s.points.size() >= 6 && (!general.is_plane() || options.imposed != ImposedType::none)) {
        if (wanted(ImposedType::sphere)) add_special(fit_sphere_geometric(s));
        // Axis guesses from the general quadric: the eigenvector of A with the smallest
        // |eigenvalue| (cylinder), the one whose eigenvalue's sign stands alone (cone),
        // the one along which the quadric is linear (paraboloid).
        Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(general.A());
        const Vec3 lambda = eig.eigenvalues();
        int flattest = 0;
        for (int i = 1; i < 3; ++i)
            if (std::abs(lambda[i]) < std::abs(lambda[flattest])) flattest = i;
        if (wanted(ImposedType::cylinder)) add_special(fit_cylinder_geometric(s, eig.eigenvectors().col(flattest)));
        const int positives = (lambda.array() > 0).count();
        if (wanted(ImposedType::cone) && (positives == 1 || positives == 2)) {
            int lone = 0;
            for (int i = 0; i < 3; ++i)
                if ((lambda[i] > 0) == (positives == 1)) lone = i;
            // The start needs a point of the axis: the quadric's centre. Across the axis,
            // the two other eigenvalues fix it; where one is near zero (an axis ratio above
            // 10:1: a shallow cone, a dish or a draft, fits as nearly two planes) the centre
            // runs off along that eigenvector, as far as the fit's rounding puts it, and the
            // point nearest the samples' centroid is tried as well.
            const Eigen::FullPivLU<Eigen::Matrix3d> lu(general.A());
            const Vec3 axis = eig.eigenvectors().col(lone);
            if (lu.isInvertible()) add_special(fit_cone_geometric(s, axis, lu.solve(-0.5 * general.b())));
            const int u = (lone + 1) % 3, v = (lone + 2) % 3;
            const int flat = std::abs(lambda[u]) < std::abs(lambda[v]) ? u : v, steep = u + v - flat;
            if (std::abs(lambda[flat]) < 0.01 * std::abs(lambda[steep])) {
                // Centre's coordinates along the lone and steep eigenvectors, from the centroid.
                const Vec3 residual = -0.5 * general.b() - general.A() * center;
                Vec3 apex = center;
                for (int k : {lone, steep}) apex += eig.eigenvectors().col(k) * (eig.eigenvectors().col(k).dot(residual) / lambda[k]);
                if (apex.allFinite()) add_special(fit_cone_geometric(s, axis, apex));
            }
        }
        if (every_type) add_special(fit_paraboloid_geometric(s, eig.eigenvectors().col(flattest)));  // never imposed
    }
    // The region's quadric was fitted to its triangles, which a CAD tessellation lays
    // inside curved surfaces; the special fits see the vertices. Both general quadrics
    // compete, each as its affine type.
    if (wanted(ImposedType::quadric))
        for (const Quadric& q : {general, fit_taubin(moments_of(s)).quadric})
            if (const auto g = general_candidate(q, s, extent, options.classify)) candidates.push_back(*g);

    // A candidate of as many parameters as there are vertices passes through them whatever
    // the surface: its fit is no evidence (a 6-face region's 8 vertices lie on a quadric).
    const auto undetermined = [&](const TypedFit& c) { return static_cast<std::size_t>(c.parameters) >= s.points.size(); };
    if (!std::all_of(candidates.begin(), candidates.end(), undetermined))
        candidates.erase(std::remove_if(candidates.begin(), candidates.end(), undetermined), candidates.end());
    for (TypedFit& c : candidates) c.bic = criterion(s, c.rms, c.parameters, floor2);
    std::stable_sort(candidates.begin(), candidates.end(), [](const TypedFit& a, const TypedFit& b) { return a.bic < b.bic; });
    // Candidates the edges' midpoints rule out: no choice, but still the report's runner-up
    // when no candidate left is of another type (how clear the choice was).
    std::vector<TypedFit> dropped;
    if (!s.edge_midpoints.empty() && options.imposed == ImposedType::none) {
        // Nor do the vertices say where the surface runs between them: the two rows of
        // vertices of a flat strip one facet wide lie closer, under noise, to a paraboloid
        // curving sharply away from the strip than to their plane, and a long pin's two
        // end circles lie exactly on the sphere centred half way along it, which passes
        // the middle of every facet by half the pin's length. A candidate that strays from
        // the edges' midpoints by an order of magnitude more than another, beyond the
        // tessellation's own deviation, is not the mesh's surface, however closely it
        // holds the vertices. The midpoints carry the noise too, so the least stray is
        // itself mostly noise and ten times it lets a candidate bend away by seven σ (a
        // strip's cylinder, 12 σ off its midpoints, passed): on a noisy mesh a candidate
        // may also stray beyond the least by no more than the cap past which a point
        // tells of something else than the region's surface.
        double allowed = floor2;
        for (double t : s.midpoint_tolerances) allowed += t * t / s.midpoint_tolerances.size();
        // A candidate strays by the larger of its mean squares at the midpoints and at the
        // vertices: a quadric fitted to the faces may also pass the midpoints and miss the
        // vertices (a tooth flank's near-flat cone, 40 times farther from them than their
        // plane), and it is no more the mesh's surface.
        std::vector<double> strays;
        for (const TypedFit& c : candidates)
            strays.push_back(std::max(midpoint_mean_square(s, c.quadric, false), c.rms * c.rms));
        const double least = *std::min_element(strays.begin(), strays.end());
        const double noise_bound = s.noise > 0 ? least + allowed + (kNoiseCap * s.noise) * (kNoiseCap * s.noise)
                                               : std::numeric_limits<double>::infinity();
        std::vector<TypedFit> kept;
        for (std::size_t i = 0; i < candidates.size(); ++i)
            (strays[i] <= kRunAway * kRunAway * (least + allowed) && strays[i] <= noise_bound ? kept : dropped)
                .push_back(candidates[i]);
        if (!kept.empty()) candidates.swap(kept);
        // Where several types hold the vertices to rounding, the vertices cannot tell them
        // apart (a band one facet tall holds two circles: on a cylinder, a sphere and many
        // quadrics); a tessellation lays its edges along a surface's straight lines, so the
        // one that also holds the edges' midpoints best, by the same criterion, is it. Under
        // noise the vertices cannot tell the elementary types apart where those differ by
        // less than the noise either: a noisy hole one facet tall was the sphere through its
        // two circles, which leaves its vertical edges by h²/8r, less than σ; a thin plate's
        // rim, whose two rows of vertices move along normals tilted by the plate's faces and
        // fold like a cylinder's section, was a cylinder. So where the criterion chose an
        // elementary type, the midpoints judge among the elementary types. Not among the
        // general quadrics, which bend to noisy midpoints as to noisy vertices (judged by
        // them too, spheres came out ellipsoids: bench/RESULTS.md §4).
        const bool among_elementary = s.noise > 0 && elementary(candidates.front());
        if (among_elementary || candidates.front().rms * candidates.front().rms <= exact2) {
            auto eligible = [&](const TypedFit& c) { return among_elementary ? elementary(c) : c.rms * c.rms <= exact2; };
            const double m = static_cast<double>(s.edge_midpoints.size());
            auto with_edges = [&](const TypedFit& c) { return c.bic + m * std::log(midpoint_mean_square(s, c.quadric, true) + floor2); };
            auto best = candidates.begin();
            double best_score = with_edges(*best);
            for (auto c = candidates.begin() + 1; c != candidates.end(); ++c) {
                if (!eligible(*c)) continue;
                const double score = with_edges(*c);
                if (score < best_score) best = c, best_score = score;
            }
            std::rotate(candidates.begin(), best, best + 1);
        }
    }
    // Where the vertices stray from every candidate (noise, a remeshing), the scatter none
    // of them explains bounds what a closer fit can tell: at most the best's own RMS.
    if (options.imposed == ImposedType::none && s.scatter > 0 && !candidates.empty() &&
        !(candidates.front().rms * candidates.front().rms <= exact2)) {
        const auto simplest = simplest_within_scatter(candidates, std::min(s.scatter, candidates.front().rms));
        std::rotate(candidates.begin(), simplest, simplest + 1);
    }
    const auto chosen = std::find_if(candidates.begin(), candidates.end(),
                                     [&](const TypedFit& c) { return of_type(c, options.imposed); });
    if (chosen == candidates.end())
        throw std::invalid_argument(std::string("no ") + imposed_type_name(options.imposed) + " fits these vertices");
    std::rotate(candidates.begin(), chosen, chosen + 1);
    ModelChoice choice{candidates.front(), std::nullopt};
    for (std::size_t i = 1; i < candidates.size() && !choice.runner_up; ++i)
        if (candidates[i].type != choice.chosen.type) choice.runner_up = candidates[i];
    for (std::size_t i = 0; i < dropped.size() && !choice.runner_up; ++i)
        if (dropped[i].type != choice.chosen.type) choice.runner_up = dropped[i];
    return choice;
}

bool descends(const TypedFit& fit) { return !fit.special && !cad_type(fit.type); }

ModelChoice descend(const Samples& s, const ModelChoice& choice, const ModelSelectionOptions& options) {
    const TypedFit& start = choice.chosen;
    if (!descends(start) || static_cast<std::size_t>(start.parameters) >= s.points.size()) return choice;
    // Steps along an orthonormal basis of the coefficients orthogonal to the start's: they
    // change the surface, not the scale, which the distance ignores.
    using Coefficients = Eigen::Matrix<double, 10, 1>;
    using Step = Eigen::Matrix<double, 9, 1>;
    const Coefficients q0 = Eigen::Map<const Coefficients>(start.quadric.c.data()).normalized();
    Eigen::Matrix<double, 10, 10> spanning = Eigen::Matrix<double, 10, 10>::Identity();
    spanning.col(0) = q0;
    const Eigen::Matrix<double, 10, 10> Q = Eigen::HouseholderQR<Eigen::Matrix<double, 10, 10>>(spanning).householderQ();
    const Eigen::Matrix<double, 10, 9> basis = Q.rightCols<9>();
    auto quadric_of = [&](const Step& t) {
        Quadric q;
        Eigen::Map<Coefficients>(q.c.data()) = q0 + basis * t;
        return q;
    };
    const double cap = s.noise > 0 ? kNoiseCap * s.noise : std::numeric_limits<double>::infinity();
    const Step t = least_squares<9>(
        s, Step::Zero(),
        [&](const Step& theta) {
            const Quadric q = quadric_of(theta);
            const double a = q.hessian_norm();
            return [q, a, cap](const Vec3& p) {
                const double d = std::min(taubin_distance(q, a, p), cap);
                return q.value(p) < 0 ? -d : d;
            };
        },
        1.0);  // the scale of a step: the coefficients have unit norm
    const Extent extent = extent_of(s);
    const auto descended = general_candidate(quadric_of(t), s, extent, options.classify);
    if (!descended) return choice;
    const double floor2 = exact_squared(extent, options) + s.tolerance * s.tolerance;
    TypedFit fit = *descended;
    fit.bic = criterion(s, fit.rms, fit.parameters, floor2);
    // The start was scored on the samples it was chosen by, which these may weigh otherwise.
    TypedFit from = start;
    from.rms = selection_rms(s, start.quadric);
    from.bic = criterion(s, from.rms, from.parameters, floor2);
    if (!(fit.bic < from.bic)) return choice;
    // Of another type now, the fit it started from is the best candidate of another type.
    return {fit, fit.type != start.type ? std::optional<TypedFit>(from) : choice.runner_up};
}

}  // namespace vqsa
