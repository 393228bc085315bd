#include "cad_parts.h"

#include "geometry/portable_math.h"

#include "geometry/rng.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <map>
#include <stdexcept>

namespace vqsa {

namespace {

constexpr double kPi = 3.14159265358979323846;

class Random {
public:
    explicit Random(std::uint64_t seed) : rng_(seed) {}
    double uniform() { return static_cast<double>(rng_.next() >> 11) * 0x1.0p-53; }
    double normal() {  // Box–Muller
        const double u1 = std::max(uniform(), 1e-300), u2 = uniform();
        return std::sqrt(-2 * portable::log(u1)) * portable::cos(2 * kPi * u2);
    }

private:
    SplitMix64 rng_;
};

// Every vertex moved along its normal (of the faces round it, by area) by a Gaussian of
// σ = `relative` × the bounding-box diagonal, drawn from `random`.
void displace_along_normals(Mesh& mesh, double relative, Random& random) {
    std::vector<Vec3> normal(mesh.vertices.size(), Vec3::Zero());
    for (const Triangle& t : mesh.triangles) {
        const Vec3& a = mesh.vertices[t[0]];
        const Vec3 n = (mesh.vertices[t[1]] - a).cross(mesh.vertices[t[2]] - a);
        for (int v : t) normal[v] += n;
    }
    const double sigma = relative * bounding_box(mesh).diagonal();
    for (std::size_t v = 0; v < normal.size(); ++v)
        if (normal[v].norm() > 0) mesh.vertices[v] += sigma * random.normal() * normal[v].normalized();
}

// base^n by multiplication: exact for 1.5^n up to n = 33, whatever the platform's pow.
double power(double base, int n) {
    double p = 1;
    for (int i = 0; i < n; ++i) p *= base;
    return p;
}

using Labeller = std::function<int(int)>;  // band segment → true face

// Collects polygons labelled by true face; vertices are welded by build_mesh (exactly
// equal positions), which is why shared boundaries are built once and passed around.
class PartBuilder {
public:
    explicit PartBuilder(const PartOptions& options) : options_(options), random_(options.seed * 7919 + 17) {}

    int surface(const TrueSurface& s) {
        surfaces_.push_back(s);
        return static_cast<int>(surfaces_.size()) - 1;
    }
    int count(int base) const { return std::max(1, static_cast<int>(std::lround(base * options_.detail))); }

    // n + 1 parameters from 0 to 1: uniform, or with a density varying about 6× and jitter.
    std::vector<double> spacing(int n) {
        std::vector<double> t(n + 1);
        const double phase = 2 * kPi * random_.uniform();
        for (int i = 0; i <= n; ++i) {
            const double u = double(i) / n;
            t[i] = options_.irregular ? u + 0.7 * (portable::sin(2 * kPi * u + phase) - portable::sin(phase)) / (2 * kPi) : u;
        }
        t[0] = 0, t[n] = 1;
        if (options_.irregular) {
            const std::vector<double> base = t;
            for (int i = 1; i < n; ++i)
                t[i] += (random_.uniform() - 0.5) * 0.4 * std::min(base[i] - base[i - 1], base[i + 1] - base[i]);
        }
        return t;
    }

    // A closed loop of `n` segments round the circle of radius r about the z axis, at z = 0,
    // spaced as `spacing` (its last parameter, 2π, is the first point again).
    std::vector<Vec3> circle(double r, int n) {
        std::vector<Vec3> out;
        for (double t : spacing(n)) out.emplace_back(r * portable::cos(2 * kPi * t), r * portable::sin(2 * kPi * t), 0);
        out.pop_back();
        return out;
    }

    // Points a → b (both included), `n` segments.
    std::vector<Vec3> segment(const Vec3& a, const Vec3& b, int n) {
        std::vector<Vec3> out;
        const std::vector<double> t = spacing(n);
        for (int i = 0; i <= n; ++i) out.push_back(i == 0 ? a : i == n ? b : Vec3(a + t[i] * (b - a)));
        return out;
    }

    // The band between polylines a and b of equal length (loops when `closed`): rows of
    // points on the straight lines a_j → b_j, so planes, cylinders and cones whose lines
    // these are keep every vertex on the surface. Quad (j, j+1) belongs to label_of(j).
    void band(const std::vector<Vec3>& a, const std::vector<Vec3>& b, int rows, bool closed, const Labeller& label_of) {
        if (a.size() != b.size()) throw std::logic_error("band: polylines of different lengths");
        const int m = static_cast<int>(a.size());
        std::vector<double> s(rows + 1);
        for (int r = 0; r <= rows; ++r) {
            const double u = double(r) / rows;
            // Graded rows when irregular: spacing grows geometrically across the band.
            s[r] = options_.irregular && rows > 1 ? (power(1.5, r) - 1) / (power(1.5, rows) - 1) : u;
        }
        std::vector<std::vector<int>> index(rows + 1, std::vector<int>(m));
        for (int r = 0; r <= rows; ++r)
            for (int j = 0; j < m; ++j) {
                Vec3 p;
                if (r == 0) p = a[j];
                else if (r == rows) p = b[j];
                else {
                    double t = s[r];
                    if (options_.irregular) t += (random_.uniform() - 0.5) * 0.5 * std::min(s[r] - s[r - 1], s[r + 1] - s[r]);
                    p = a[j] + t * (b[j] - a[j]);
                }
                index[r][j] = vertex(p);
            }
        for (int r = 0; r < rows; ++r)
            for (int j = 0; j + (closed ? 0 : 1) < m; ++j) {
                const int k = (j + 1) % m;
                quad(index[r][j], index[r][k], index[r + 1][k], index[r + 1][j], label_of(j));
            }
    }
    void band(const std::vector<Vec3>& a, const std::vector<Vec3>& b, int rows, bool closed, int label) {
        band(a, b, rows, closed, [label](int) { return label; });
    }

    // A planar loop star-shaped from `center`, filled with shrinking copies and a fan.
    void fill(const std::vector<Vec3>& loop, const Vec3& center, int rows, int label) {
        std::vector<Vec3> inner;
        for (const Vec3& p : loop) inner.push_back(center + (p - center) / (rows + 1.0));
        band(loop, inner, rows, true, label);
        fan(inner, center, label);
    }

    // A cap: from the loop `previous`, the rings next(1) … next(rows − 1) joined pairwise,
    // then a fan to `apex` (a hemisphere's latitude rings, a cone's rings to its tip).
    template <class NextRing>
    void cap(std::vector<Vec3> previous, int rows, NextRing next, const Vec3& apex, int label) {
        for (int i = 1; i < rows; ++i) {
            std::vector<Vec3> ring = next(i);
            band(previous, ring, 1, true, label);
            previous = std::move(ring);
        }
        fan(previous, apex, label);
    }

    // Triangles from every segment of the loop to `apex`.
    void fan(const std::vector<Vec3>& loop, const Vec3& apex, int label) {
        const int c = vertex(apex), m = static_cast<int>(loop.size());
        std::vector<int> ring;
        for (const Vec3& p : loop) ring.push_back(vertex(p));
        for (int j = 0; j < m; ++j) triangle(ring[j], ring[(j + 1) % m], c, label);
    }

    void triangle(const Vec3& a, const Vec3& b, const Vec3& c, int label) { triangle(vertex(a), vertex(b), vertex(c), label); }

    Part finish(const std::string& name);

    Random& random() { return random_; }

private:
    int vertex(const Vec3& p) {
        soup_.positions.push_back(p);
        return static_cast<int>(soup_.positions.size()) - 1;
    }
    void triangle(int a, int b, int c, int label) {
        const int t[3] = {a, b, c};
        soup_.add_polygon(t, 3);
        labels_.push_back(label);
    }
    // a, b on one row, d, c the points above them: split along the shorter diagonal.
    void quad(int a, int b, int c, int d, int label) {
        const auto& p = soup_.positions;
        if ((p[a] - p[c]).squaredNorm() <= (p[b] - p[d]).squaredNorm()) {
            triangle(a, b, c, label);
            triangle(a, c, d, label);
        } else {
            triangle(a, b, d, label);
            triangle(b, c, d, label);
        }
    }

    PartOptions options_;
    Random random_;
    PolygonSoup soup_;
    std::vector<int> labels_;
    std::vector<TrueSurface> surfaces_;
};

// Flips faces so that neighbours traverse shared edges in opposite directions, then the
// whole mesh so that the enclosed volume is positive (normals point out).
void orient(Mesh& mesh) {
    const int n = static_cast<int>(mesh.face_count());
    std::map<std::pair<int, int>, std::vector<int>> edge_faces;  // undirected edge → faces
    for (int f = 0; f < n; ++f)
        for (int k = 0; k < 3; ++k) {
            const int a = mesh.triangles[f][k], b = mesh.triangles[f][(k + 1) % 3];
            edge_faces[{std::min(a, b), std::max(a, b)}].push_back(f);
        }
    auto has_directed = [&](int f, int a, int b) {
        for (int k = 0; k < 3; ++k)
            if (mesh.triangles[f][k] == a && mesh.triangles[f][(k + 1) % 3] == b) return true;
        return false;
    };
    std::vector<char> done(n, 0);
    for (int start = 0; start < n; ++start) {
        if (done[start]) continue;
        done[start] = 1;
        std::vector<int> stack{start};
        while (!stack.empty()) {
            const int f = stack.back();
            stack.pop_back();
            for (int k = 0; k < 3; ++k) {
                const int a = mesh.triangles[f][k], b = mesh.triangles[f][(k + 1) % 3];
                for (int g : edge_faces[{std::min(a, b), std::max(a, b)}]) {
                    if (done[g]) continue;
                    if (has_directed(g, a, b)) std::swap(mesh.triangles[g][1], mesh.triangles[g][2]);
                    done[g] = 1;
                    stack.push_back(g);
                }
            }
        }
    }
    double volume = 0;
    for (const Triangle& t : mesh.triangles)
        volume += mesh.vertices[t[0]].dot(mesh.vertices[t[1]].cross(mesh.vertices[t[2]]));
    if (volume < 0)
        for (Triangle& t : mesh.triangles) std::swap(t[1], t[2]);
}

Eigen::Matrix3d random_rotation(Random& r) {
    Eigen::Quaterniond q(r.normal(), r.normal(), r.normal(), r.normal());
    q.normalize();
    return q.toRotationMatrix();
}

Part PartBuilder::finish(const std::string& name) {
    Part part;
    part.name = name;
    part.mesh = build_mesh(soup_);
    for (int source : part.mesh.source_face) part.face.push_back(labels_[source]);
    part.surfaces = surfaces_;
    orient(part.mesh);

    if (options_.noise > 0) displace_along_normals(part.mesh, options_.noise, random_);
    if (options_.random_pose) {
        const Eigen::Matrix3d R = random_rotation(random_);
        const Vec3 t(random_.normal(), random_.normal(), random_.normal());
        for (Vec3& p : part.mesh.vertices) p = R * p + t;
        for (TrueSurface& s : part.surfaces) s.point = R * s.point + t, s.axis = R * s.axis;
    }
    return part;
}

TrueSurface plane(const Vec3& point, const Vec3& normal) { return {QuadricType::plane, point, normal.normalized()}; }
TrueSurface cylinder(const Vec3& point, const Vec3& axis, double radius) {
    return {QuadricType::cylinder, point, axis.normalized(), radius};
}

// Rays from `center` through each point of `loop` onto the circle of radius r about it
// (in the plane z = center.z).
std::vector<Vec3> onto_circle(const std::vector<Vec3>& loop, const Vec3& center, double r) {
    std::vector<Vec3> out;
    for (const Vec3& p : loop) {
        const Vec3 d = p - center;
        out.push_back(center + r / d.norm() * d);
    }
    return out;
}

std::vector<Vec3> at_height(const std::vector<Vec3>& points, double z) {
    std::vector<Vec3> out = points;
    for (Vec3& p : out) p.z() = z;
    return out;
}

// Appends `piece` without its last point (the next piece starts there).
void append_open(std::vector<Vec3>& loop, const std::vector<Vec3>& piece) {
    loop.insert(loop.end(), piece.begin(), piece.end() - 1);
}

// A regular polygon round the z axis at z = 0 (first corner on +x), each side a plane face
// of its own cut into `segments` segments: the closed outline, and per segment its side.
struct PolygonOutline {
    std::vector<Vec3> points;
    std::vector<int> side;
};
PolygonOutline regular_polygon(PartBuilder& b, int sides, double circumradius, int segments) {
    std::vector<Vec3> corners;
    for (int k = 0; k < sides; ++k) {
        const double a = 2 * kPi / sides * k;
        corners.emplace_back(circumradius * portable::cos(a), circumradius * portable::sin(a), 0);
    }
    PolygonOutline out;
    for (int k = 0; k < sides; ++k) {
        const Vec3& next = corners[(k + 1) % sides];
        const int side = b.surface(plane(corners[k], (corners[k] + next).normalized()));
        const std::vector<Vec3> edge = b.segment(corners[k], next, segments);
        append_open(out.points, edge);
        out.side.insert(out.side.end(), edge.size() - 1, side);
    }
    return out;
}

// A prism on the loop `outline` (z = 0) up to `height`, bored through along the loop `ring`
// (point for point with the outline): its side (labelled per outline segment), the top
// annulus, the bore and the bottom annulus.
void bored_prism(PartBuilder& b, const std::vector<Vec3>& outline, const std::vector<Vec3>& ring, double height,
                 const Labeller& side, int top, int bore, int bottom, int side_rows, int annulus_rows, int bore_rows) {
    b.band(outline, at_height(outline, height), side_rows, true, side);
    b.band(at_height(outline, height), at_height(ring, height), annulus_rows, true, top);
    b.band(at_height(ring, height), ring, bore_rows, true, bore);
    b.band(ring, outline, annulus_rows, true, bottom);
}

// A prism from z = 0 to `height` over a closed counter-clockwise outline at z = 0, its side
// quad j (from point j to the next) on surface label[j], each side one row of two
// full-height triangles, bottom and top fans from `inside` (and above it) as their planes.
void flat_prism(PartBuilder& b, const std::vector<Vec3>& outline, const std::vector<int>& label, double height,
                const Vec3& inside) {
    const std::vector<Vec3> top = at_height(outline, height);
    b.band(outline, top, b.count(1), true, [&](int j) { return label[j]; });
    b.fill(outline, inside, b.count(2), b.surface(plane({0, 0, 0}, -Vec3::UnitZ())));
    b.fill(top, inside + Vec3(0, 0, height), b.count(2), b.surface(plane({0, 0, height}, Vec3::UnitZ())));
}

// Where the ray from a slot's centre along unit u meets the slot: two half-circle ends of
// radius r centred at ±a along x, joined by flat sides at ±r along y (a = 0: a circle).
// `piece`: 0 the flat side below, 1 above, 2 the end to the right, 3 to the left.
struct SlotHit {
    Vec3 offset;  // from the centre
    int piece;
};
SlotHit slot_hit(const Vec3& u, double a, double r) {
    if (a > 0 && std::abs(u.y()) > 0) {
        const double t = r / std::abs(u.y());
        if (std::abs(t * u.x()) <= a) return {t * u, u.y() > 0 ? 1 : 0};
    }
    const Vec3 centre(u.x() > 0 ? a : -a, 0, 0);
    const double along = u.dot(centre);
    const double t = along + std::sqrt(along * along - centre.squaredNorm() + r * r);
    return {t * u, u.x() > 0 ? 2 : 3};
}

// A box with a cylindrical boss on top and a through hole: 9 faces.
Part box_boss_hole(const PartOptions& o) {
    PartBuilder b(o);
    const double W = 2, D = 1, H = 0.5, hole_r = 0.2, boss_r = 0.3, boss_h = 0.4;
    const Vec3 hole(0.5, 0.5, 0), boss(1.5, 0.5, 0);
    const int bottom = b.surface(plane({0, 0, 0}, -Vec3::UnitZ())), top = b.surface(plane({0, 0, H}, Vec3::UnitZ()));
    const int front = b.surface(plane({0, 0, 0}, -Vec3::UnitY())), right = b.surface(plane({W, 0, 0}, Vec3::UnitX()));
    const int back = b.surface(plane({0, D, 0}, Vec3::UnitY())), left = b.surface(plane({0, 0, 0}, -Vec3::UnitX()));
    const int boss_side = b.surface(cylinder(boss, Vec3::UnitZ(), boss_r));
    const int boss_top = b.surface(plane({0, 0, H + boss_h}, Vec3::UnitZ()));
    const int hole_side = b.surface(cylinder(hole, Vec3::UnitZ(), hole_r));

    const int n = b.count(16), rows = b.count(7), z_rows = b.count(5);
    // Edges at z = 0 of the two unit squares the top and bottom are cut into.
    const Vec3 c00(0, 0, 0), c10(1, 0, 0), c20(W, 0, 0), c21(W, D, 0), c11(1, D, 0), c01(0, D, 0);
    const auto front_left = b.segment(c00, c10, n), front_right = b.segment(c10, c20, n);
    const auto right_edge = b.segment(c20, c21, n), back_right = b.segment(c21, c11, n);
    const auto back_left = b.segment(c11, c01, n), left_edge = b.segment(c01, c00, n);
    const auto middle = b.segment(c10, c11, n);
    std::vector<Vec3> left_square, right_square, outline;
    std::vector<int> outline_face;
    append_open(left_square, front_left), append_open(left_square, middle);
    append_open(left_square, back_left), append_open(left_square, left_edge);
    std::vector<Vec3> middle_down(middle.rbegin(), middle.rend());
    append_open(right_square, front_right), append_open(right_square, right_edge);
    append_open(right_square, back_right), append_open(right_square, middle_down);
    for (const auto& [edge, face] : {std::pair{&front_left, front}, {&front_right, front}, {&right_edge, right},
                                     {&back_right, back}, {&back_left, back}, {&left_edge, left}}) {
        append_open(outline, *edge);
        outline_face.insert(outline_face.end(), edge->size() - 1, face);
    }

    const auto hole_bottom = onto_circle(left_square, hole, hole_r);
    const auto hole_top = at_height(hole_bottom, H);
    const auto boss_foot = at_height(onto_circle(right_square, boss, boss_r), H);
    const auto boss_rim = at_height(boss_foot, H + boss_h);
    b.band(left_square, hole_bottom, rows, true, bottom);
    b.fill(right_square, boss, rows, bottom);
    b.band(at_height(left_square, H), hole_top, rows, true, top);
    b.band(at_height(right_square, H), boss_foot, rows, true, top);
    b.band(outline, at_height(outline, H), z_rows, true, [&](int j) { return outline_face[j]; });
    b.band(hole_bottom, hole_top, z_rows, true, hole_side);
    b.band(boss_foot, boss_rim, z_rows, true, boss_side);
    b.fill(boss_rim, Vec3(boss.x(), boss.y(), H + boss_h), rows, boss_top);
    return b.finish("box_boss_hole");
}

// An L-bracket whose inner edge is a fillet tangent to both legs: 9 faces.
Part l_bracket(const PartOptions& o) {
    PartBuilder b(o);
    const double L = 2, Hh = 1.6, t = 0.3, r = 0.35, width = 1.2;
    auto xz = [](double x, double z) { return Vec3(x, 0, z); };
    const Vec3 fillet_axis_point = xz(t + r, t + r);
    const int bottom = b.surface(plane({0, 0, 0}, -Vec3::UnitZ())), end = b.surface(plane({L, 0, 0}, Vec3::UnitX()));
    const int leg_top = b.surface(plane({0, 0, t}, Vec3::UnitZ()));
    const int fillet = b.surface(cylinder(fillet_axis_point, Vec3::UnitY(), r));
    const int inner = b.surface(plane({t, 0, 0}, Vec3::UnitX())), top = b.surface(plane({0, 0, Hh}, Vec3::UnitZ()));
    const int outer = b.surface(plane({0, 0, 0}, -Vec3::UnitX()));
    const int near_side = b.surface(plane({0, 0, 0}, -Vec3::UnitY()));
    const int far_side = b.surface(plane({0, width, 0}, Vec3::UnitY()));

    // The profile as two paths across the thickness from each other, sampled alike, so
    // that the side caps are bands of quads from one to the other: the outer one (bottom,
    // outer vertical) and the inner one (leg top, fillet, inner vertical). The outer
    // path's corner faces the fillet.
    const int n = b.count(24), k = b.count(8);
    const auto outer_bottom_far = b.segment(xz(L, 0), xz(t + r, 0), n), outer_bottom_near = b.segment(xz(t + r, 0), xz(0, 0), k);
    const auto outer_side_near = b.segment(xz(0, 0), xz(0, t + r), k), outer_side_far = b.segment(xz(0, t + r), xz(0, Hh), n);
    const auto leg = b.segment(xz(L, t), xz(t + r, t), n), inner_side = b.segment(xz(t, t + r), xz(t, Hh), n);
    std::vector<Vec3> arc;
    const std::vector<double> s = b.spacing(2 * k);
    for (std::size_t i = 0; i < s.size(); ++i) {
        const double a = -kPi / 2 - s[i] * kPi / 2;  // from straight below the axis to its left
        arc.push_back(i == 0 ? xz(t + r, t) : i + 1 == s.size() ? xz(t, t + r) : xz(t + r + r * portable::cos(a), t + r + r * portable::sin(a)));
    }
    std::vector<Vec3> outer_path, inner_path;
    for (const auto* piece : {&outer_bottom_far, &outer_bottom_near, &outer_side_near}) append_open(outer_path, *piece);
    outer_path.insert(outer_path.end(), outer_side_far.begin(), outer_side_far.end());
    append_open(inner_path, leg);
    append_open(inner_path, arc);
    inner_path.insert(inner_path.end(), inner_side.begin(), inner_side.end());

    // The closed profile, counter-clockwise, with the face of each segment.
    std::vector<Vec3> profile;
    std::vector<int> profile_face;
    auto add = [&](const std::vector<Vec3>& piece, int face) {
        append_open(profile, piece);
        profile_face.insert(profile_face.end(), piece.size() - 1, face);
    };
    const std::size_t bottom_points = outer_bottom_far.size() + outer_bottom_near.size() - 1;
    add(std::vector<Vec3>(outer_path.begin(), outer_path.begin() + bottom_points), bottom);      // (L,0) → (0,0)
    add(std::vector<Vec3>(outer_path.begin() + bottom_points - 1, outer_path.end()), outer);     // (0,0) → (0,Hh)
    add({xz(0, Hh), xz(t, Hh)}, top);
    const std::vector<Vec3> inner_reversed(inner_path.rbegin(), inner_path.rend());
    add(std::vector<Vec3>(inner_reversed.begin(), inner_reversed.begin() + inner_side.size()), inner);
    add(std::vector<Vec3>(inner_reversed.begin() + inner_side.size() - 1, inner_reversed.begin() + inner_side.size() + arc.size() - 1), fillet);
    add(std::vector<Vec3>(inner_reversed.begin() + inner_side.size() + arc.size() - 2, inner_reversed.end()), leg_top);
    add({xz(L, t), xz(L, 0)}, end);

    std::vector<Vec3> far = profile;
    for (Vec3& p : far) p.y() = width;
    b.band(profile, far, b.count(16), true, [&](int j) { return profile_face[j]; });
    std::vector<Vec3> outer_far = outer_path, inner_far = inner_path;
    for (Vec3& p : outer_far) p.y() = width;
    for (Vec3& p : inner_far) p.y() = width;
    b.band(outer_path, inner_path, 1, false, near_side);
    b.band(outer_far, inner_far, 1, false, far_side);
    return b.finish("l_bracket");
}

// A turned shaft: end disk, two steps of cylinders with a shoulder, a chamfer cone, and
// a hemispherical end tangent to the last cylinder: 7 faces.
Part stepped_shaft(const PartOptions& o) {
    PartBuilder b(o);
    const double R1 = 0.5, R2 = 0.35, R3 = 0.25, z1 = 1.0, z2 = 1.8, z3 = 1.9, z4 = 2.6;  // a 45° chamfer
    const int end = b.surface(plane({0, 0, 0}, -Vec3::UnitZ()));
    const int cyl1 = b.surface(cylinder({0, 0, 0}, Vec3::UnitZ(), R1));
    const int shoulder = b.surface(plane({0, 0, z1}, Vec3::UnitZ()));
    const int cyl2 = b.surface(cylinder({0, 0, 0}, Vec3::UnitZ(), R2));
    // The chamfer's apex lies on the axis where its generator reaches r = 0; it opens downwards.
    const double apex_z = z2 + R2 * (z3 - z2) / (R2 - R3);
    const int chamfer = b.surface({QuadricType::cone, Vec3(0, 0, apex_z), -Vec3::UnitZ(), 0, std::atan((R2 - R3) / (z3 - z2))});
    const int cyl3 = b.surface(cylinder({0, 0, 0}, Vec3::UnitZ(), R3));
    const int ball = b.surface({QuadricType::sphere, Vec3(0, 0, z4), Vec3::UnitZ(), R3});

    std::vector<double> angles;
    for (double t : b.spacing(b.count(64))) angles.push_back(2 * kPi * t);
    angles.pop_back();  // a closed loop: 2π is 0
    auto ring = [&](double r, double z) {
        std::vector<Vec3> out;
        for (double a : angles) out.emplace_back(r * portable::cos(a), r * portable::sin(a), z);
        return out;
    };
    const auto r1_bottom = ring(R1, 0), r1_top = ring(R1, z1), r2_bottom = ring(R2, z1), r2_top = ring(R2, z2);
    const auto r3_bottom = ring(R3, z3), r3_top = ring(R3, z4);
    b.fill(r1_bottom, Vec3::Zero(), b.count(5), end);
    b.band(r1_bottom, r1_top, b.count(10), true, cyl1);
    b.band(r1_top, r2_bottom, b.count(3), true, shoulder);
    b.band(r2_bottom, r2_top, b.count(8), true, cyl2);
    b.band(r2_top, r3_bottom, b.count(3), true, chamfer);
    b.band(r3_bottom, r3_top, b.count(7), true, cyl3);
    // The hemisphere: exact latitude rings, a fan at the pole.
    const std::vector<double> lat = b.spacing(b.count(10));
    b.cap(r3_top, static_cast<int>(lat.size()) - 1, [&](int i) {
        const double a = lat[i] * kPi / 2;
        return ring(R3 * portable::cos(a), z4 + R3 * portable::sin(a));
    }, Vec3(0, 0, z4 + R3), ball);
    return b.finish("stepped_shaft");
}

// An annular flange with six bolt holes: 10 faces.
Part flange(const PartOptions& o) {
    PartBuilder b(o);
    const double Ro = 1.0, Ri = 0.4, T = 0.25, Rp = 0.7, rb = 0.12;
    const int holes = 6;
    const int bottom = b.surface(plane({0, 0, 0}, -Vec3::UnitZ())), top = b.surface(plane({0, 0, T}, Vec3::UnitZ()));
    const int outer = b.surface(cylinder({0, 0, 0}, Vec3::UnitZ(), Ro));
    const int bore = b.surface(cylinder({0, 0, 0}, Vec3::UnitZ(), Ri));
    std::vector<int> hole_face;
    for (int k = 0; k < holes; ++k) {
        const double a = 2 * kPi * k / holes;
        hole_face.push_back(b.surface(cylinder({Rp * portable::cos(a), Rp * portable::sin(a), 0}, Vec3::UnitZ(), rb)));
    }
    // Sector k spans the angles between the radial lines k and k + 1.
    const int n_arc = b.count(10), n_radial = b.count(6), rows = b.count(6), z_rows = b.count(4);
    std::vector<std::vector<Vec3>> radial;  // line k at angle (2k - 1)π/6, from Ri to Ro
    for (int k = 0; k < holes; ++k) {
        const double a = (2 * k - 1) * kPi / holes;
        const Vec3 u(portable::cos(a), portable::sin(a), 0);
        radial.push_back(b.segment(Ri * u, Ro * u, n_radial));
    }
    std::vector<Vec3> outer_loop, inner_loop;
    for (int k = 0; k < holes; ++k) {
        const std::vector<Vec3>&start = radial[k], &stop = radial[(k + 1) % holes];
        const double a0 = (2 * k - 1) * kPi / holes, a1 = (2 * k + 1) * kPi / holes;
        std::vector<Vec3> outer_arc{start.back()}, inner_arc{stop.front()};  // inner: clockwise
        const std::vector<double> so = b.spacing(n_arc), si = b.spacing(n_arc);
        for (int i = 1; i < n_arc; ++i) {
            const double ao = a0 + so[i] * (a1 - a0), ai = a1 - si[i] * (a1 - a0);
            outer_arc.emplace_back(Ro * portable::cos(ao), Ro * portable::sin(ao), 0);
            inner_arc.emplace_back(Ri * portable::cos(ai), Ri * portable::sin(ai), 0);
        }
        outer_arc.push_back(stop.back());
        inner_arc.push_back(start.front());
        std::vector<Vec3> sector;
        append_open(sector, outer_arc);
        append_open(sector, std::vector<Vec3>(stop.rbegin(), stop.rend()));
        append_open(sector, inner_arc);
        append_open(sector, start);
        append_open(outer_loop, outer_arc);
        append_open(inner_loop, std::vector<Vec3>(inner_arc.rbegin(), inner_arc.rend()));
        const double a = 2 * kPi * k / holes;
        const Vec3 centre(Rp * portable::cos(a), Rp * portable::sin(a), 0);
        const auto hole_bottom = onto_circle(sector, centre, rb), hole_top = at_height(hole_bottom, T);
        b.band(sector, hole_bottom, rows, true, bottom);
        b.band(at_height(sector, T), hole_top, rows, true, top);
        b.band(hole_bottom, hole_top, z_rows, true, hole_face[k]);
    }
    b.band(outer_loop, at_height(outer_loop, T), z_rows, true, outer);
    b.band(inner_loop, at_height(inner_loop, T), z_rows, true, bore);
    return b.finish("flange");
}

// A plate half a percent of its size thick: 6 faces.
Part thin_plate(const PartOptions& o) {
    PartBuilder b(o);
    const double W = 2, D = 1.2, T = 0.01;
    const int bottom = b.surface(plane({0, 0, 0}, -Vec3::UnitZ())), top = b.surface(plane({0, 0, T}, Vec3::UnitZ()));
    const int front = b.surface(plane({0, 0, 0}, -Vec3::UnitY())), right = b.surface(plane({W, 0, 0}, Vec3::UnitX()));
    const int back = b.surface(plane({0, D, 0}, Vec3::UnitY())), left = b.surface(plane({0, 0, 0}, -Vec3::UnitX()));
    const int n = b.count(40);
    std::vector<Vec3> outline;
    std::vector<int> outline_face;
    const Vec3 c00(0, 0, 0), c10(W, 0, 0), c11(W, D, 0), c01(0, D, 0);
    for (const auto& [from, to, face, steps] : {std::tuple{c00, c10, front, n}, {c10, c11, right, n * 3 / 5},
                                                {c11, c01, back, n}, {c01, c00, left, n * 3 / 5}}) {
        const auto edge = b.segment(from, to, steps);
        append_open(outline, edge);
        outline_face.insert(outline_face.end(), edge.size() - 1, face);
    }
    const Vec3 centre(W / 2, D / 2, 0);
    b.fill(outline, centre, b.count(16), bottom);
    b.fill(at_height(outline, T), centre + Vec3(0, 0, T), b.count(16), top);
    b.band(outline, at_height(outline, T), 1, true, [&](int j) { return outline_face[j]; });
    return b.finish("thin_plate");
}

// A block with a through slot (two flat sides joined by half-cylinders, tangent): 10 faces.
Part slotted_block(const PartOptions& o) {
    PartBuilder b(o);
    const double W = 2, D = 1.2, H = 0.4, a = 0.45, r = 0.2;
    const Vec3 c(W / 2, D / 2, 0);
    const int bottom = b.surface(plane({0, 0, 0}, -Vec3::UnitZ())), top = b.surface(plane({0, 0, H}, Vec3::UnitZ()));
    const int front = b.surface(plane({0, 0, 0}, -Vec3::UnitY())), right = b.surface(plane({W, 0, 0}, Vec3::UnitX()));
    const int back = b.surface(plane({0, D, 0}, Vec3::UnitY())), left = b.surface(plane({0, 0, 0}, -Vec3::UnitX()));
    // The slot's walls face its axis.
    const int slot_low = b.surface(plane(c - Vec3(0, r, 0), Vec3::UnitY()));
    const int slot_right = b.surface(cylinder(c + Vec3(a, 0, 0), Vec3::UnitZ(), r));
    const int slot_high = b.surface(plane(c + Vec3(0, r, 0), -Vec3::UnitY()));
    const int slot_left = b.surface(cylinder(c - Vec3(a, 0, 0), Vec3::UnitZ(), r));

    // The slot outline, counter-clockwise from (-a, -r), with the face of each piece.
    struct Sample {
        Vec3 inner;
        int slot_face;  // of the slot piece starting here
    };
    std::vector<Sample> slot;
    const int n_flat = b.count(16), n_arc = b.count(14);
    for (const Vec3& p : b.segment(c + Vec3(-a, -r, 0), c + Vec3(a, -r, 0), n_flat)) slot.push_back({p, slot_low});
    slot.pop_back();
    std::vector<double> s = b.spacing(n_arc);
    for (int i = 0; i < n_arc; ++i) {
        const double t = -kPi / 2 + s[i] * kPi;
        slot.push_back({i == 0 ? c + Vec3(a, -r, 0) : c + Vec3(a + r * portable::cos(t), r * portable::sin(t), 0), slot_right});
    }
    for (const Vec3& p : b.segment(c + Vec3(a, r, 0), c + Vec3(-a, r, 0), n_flat)) slot.push_back({p, slot_high});
    slot.pop_back();
    s = b.spacing(n_arc);
    for (int i = 0; i < n_arc; ++i) {
        const double t = kPi / 2 + s[i] * kPi;
        slot.push_back({i == 0 ? c + Vec3(-a, r, 0) : c + Vec3(-a + r * portable::cos(t), r * portable::sin(t), 0), slot_left});
    }
    // Rays from the centre: through each slot sample to the block's outline, and through
    // each corner of the outline back to the slot.
    auto to_outline = [&](const Vec3& d) {
        const double t = std::min(std::abs(d.x()) > 0 ? W / 2 / std::abs(d.x()) : 1e300,
                                  std::abs(d.y()) > 0 ? D / 2 / std::abs(d.y()) : 1e300);
        return Vec3(c + t * d);
    };
    auto to_slot = [&](const Vec3& d) { return Vec3(c + slot_hit(d.normalized(), a, r).offset); };
    struct Ray {
        double angle;
        Vec3 inner, outer;
        int slot_face, side;
    };
    std::vector<Ray> rays;
    auto side_of = [&](double angle) {
        const double corner = std::atan2(D, W);
        if (angle < -kPi + corner || angle >= kPi - corner) return left;
        if (angle < -corner) return front;
        if (angle < corner) return right;
        return back;
    };
    for (const Sample& q : slot) {
        const Vec3 d = q.inner - c;
        rays.push_back({std::atan2(d.y(), d.x()), q.inner, to_outline(d), q.slot_face, 0});
    }
    for (const Vec3& corner : {Vec3(0, 0, 0), Vec3(W, 0, 0), Vec3(W, D, 0), Vec3(0, D, 0)}) {
        const Vec3 d = corner - c;
        const double angle = std::atan2(d.y(), d.x());
        // The slot piece the ray crosses: that of the last sample before it, counter-clockwise.
        int face = -1;
        double best = -1e9, largest = -1e9;
        for (const Sample& q : slot) {
            const double qa = std::atan2((q.inner - c).y(), (q.inner - c).x());
            if (qa <= angle && qa > best) best = qa, face = q.slot_face;
            largest = std::max(largest, qa);
        }
        if (face < 0)
            for (const Sample& q : slot)
                if (std::atan2((q.inner - c).y(), (q.inner - c).x()) == largest) face = q.slot_face;
        rays.push_back({angle, to_slot(d), corner, face, 0});
    }
    std::sort(rays.begin(), rays.end(), [](const Ray& x, const Ray& y) { return x.angle < y.angle; });
    std::vector<Vec3> inner, outer;
    std::vector<int> slot_face, side;
    for (std::size_t i = 0; i < rays.size(); ++i) {
        inner.push_back(rays[i].inner);
        outer.push_back(rays[i].outer);
        slot_face.push_back(rays[i].slot_face);
        // The outline piece from this ray to the next lies on the side of its midpoint's angle.
        const double next = i + 1 < rays.size() ? rays[i + 1].angle : rays[0].angle + 2 * kPi;
        double mid = 0.5 * (rays[i].angle + next);
        if (mid > kPi) mid -= 2 * kPi;
        side.push_back(side_of(mid));
    }
    const int rows = b.count(8), z_rows = b.count(8);
    b.band(outer, inner, rows, true, bottom);
    b.band(at_height(outer, H), at_height(inner, H), rows, true, top);
    b.band(outer, at_height(outer, H), z_rows, true, [&](int j) { return side[j]; });
    b.band(inner, at_height(inner, H), z_rows, true, [&](int j) { return slot_face[j]; });
    return b.finish("slotted_block");
}

// A block with every edge and corner rounded (a box swept by a ball): 6 planes, 12
// quarter cylinders and 8 sphere octants, all tangent-continuous, so that no crease
// separates any two of its 26 faces. Each face of the outer box is a grid whose lines
// include the inner box's edges, lifted onto the rounded surface: a point goes to the
// inner box's nearest point plus the ball's radius along the way to it.
Part rounded_block(const PartOptions& o) {
    PartBuilder b(o);
    const Vec3 inner(1.0, 0.6, 0.35);  // half sizes
    const double r = 0.15;
    // Grid values per axis from −(inner + r) to inner + r with ±inner among them, shared
    // by the four faces that axis crosses (so that their edges weld).
    std::vector<double> grid[3];
    for (int k = 0; k < 3; ++k) {
        auto piece = [&](double from, double to, int n) {
            const std::vector<double> t = b.spacing(n);
            for (int i = grid[k].empty() ? 0 : 1; i <= n; ++i) grid[k].push_back(i == n ? to : from + t[i] * (to - from));
        };
        const int round = b.count(5);
        piece(-inner[k] - r, -inner[k], round);
        piece(-inner[k], inner[k], b.count(static_cast<int>(std::lround(24 * inner[k]))));
        piece(inner[k], inner[k] + r, round);
    }
    auto lift = [&](const Vec3& p) {
        const Vec3 nearest = p.cwiseMax(-inner).cwiseMin(inner);
        return Vec3(nearest + r * (p - nearest).normalized());
    };
    // A true face per zone: the signs of the coordinates beyond the inner box.
    std::map<std::array<int, 3>, int> zone_face;
    auto face_of = [&](const Vec3& p) {
        std::array<int, 3> zone{};
        Vec3 corner = Vec3::Zero();
        int beyond = 0;
        for (int k = 0; k < 3; ++k) {
            zone[k] = p[k] > inner[k] ? 1 : p[k] < -inner[k] ? -1 : 0;
            corner[k] = zone[k] * inner[k];
            beyond += zone[k] != 0;
        }
        const auto found = zone_face.find(zone);
        if (found != zone_face.end()) return found->second;
        TrueSurface s;
        if (beyond == 1) {
            const Vec3 normal(zone[0], zone[1], zone[2]);
            s = plane(corner + r * normal, normal);
        } else if (beyond == 2) {
            s = cylinder(corner, Vec3(zone[0] == 0, zone[1] == 0, zone[2] == 0), r);
        } else {
            s = {QuadricType::sphere, corner, Vec3::UnitZ(), r};
        }
        return zone_face[zone] = b.surface(s);
    };
    for (int k = 0; k < 3; ++k)
        for (const int side : {-1, 1}) {
            const int u = (k + 1) % 3, v = (k + 2) % 3;
            auto point = [&](std::size_t i, std::size_t j) {
                Vec3 p;
                p[k] = side * (inner[k] + r), p[u] = grid[u][i], p[v] = grid[v][j];
                return p;
            };
            for (std::size_t i = 0; i + 1 < grid[u].size(); ++i) {
                std::vector<Vec3> row, next;
                for (std::size_t j = 0; j < grid[v].size(); ++j) row.push_back(lift(point(i, j))), next.push_back(lift(point(i + 1, j)));
                b.band(row, next, 1, false, [&](int j) { return face_of(0.5 * (point(i, j) + point(i + 1, j + 1))); });
            }
        }
    return b.finish("rounded_block");
}

// Three separate plates of an assembly, each 3 % of its length thick, with rounded
// corners (quarter cylinders tangent to the sides) and a through slot or a round hole:
// 14 + 11 + 14 = 39 faces on three components, the narrow sides and corner strips one
// facet tall. Plates lie flat, stacked and crossed, and upright.
Part plate_assembly(const PartOptions& o) {
    PartBuilder b(o);
    const double A = 1.0, B = 0.6, corner_r = 0.15, T = 0.06, slot_r = 0.12;

    // One plate in its own frame (z from 0 to T, centred on the z axis), then placed by
    // p → R p + at. `slot_a`: half the distance between the slot's end centres (0: a hole).
    auto plate = [&](const Eigen::Matrix3d& R, const Vec3& at, double slot_a) {
        auto place = [&](const Vec3& p) { return Vec3(R * p + at); };
        auto place_all = [&](const std::vector<Vec3>& points) {
            std::vector<Vec3> out;
            for (const Vec3& p : points) out.push_back(place(p));
            return out;
        };
        const int bottom = b.surface(plane(place({0, 0, 0}), -(R * Vec3::UnitZ())));
        const int top = b.surface(plane(place({0, 0, T}), R * Vec3::UnitZ()));
        // Sides and corners counter-clockwise from the right side (+x): side k's outward
        // normal is at angle kπ/2, corner k lies between sides k and k + 1.
        int side[4], corner[4];
        const Vec3 corner_centre[4] = {{A - corner_r, B - corner_r, 0}, {-(A - corner_r), B - corner_r, 0},
                                       {-(A - corner_r), -(B - corner_r), 0}, {A - corner_r, -(B - corner_r), 0}};
        const Vec3 side_normal[4] = {Vec3::UnitX(), Vec3::UnitY(), -Vec3::UnitX(), -Vec3::UnitY()};
        for (int k = 0; k < 4; ++k) {
            side[k] = b.surface(plane(place(side_normal[k].cwiseProduct(Vec3(A, B, 0))), R * side_normal[k]));
            corner[k] = b.surface(cylinder(place(corner_centre[k]), R * Vec3::UnitZ(), corner_r));
        }
        // The slot's walls face its axis; a hole is one cylinder.
        const int wall_low = slot_a > 0 ? b.surface(plane(place({0, -slot_r, 0}), R * Vec3::UnitY())) : -1;
        const int end_right = b.surface(cylinder(place({slot_a, 0, 0}), R * Vec3::UnitZ(), slot_r));
        const int wall_high = slot_a > 0 ? b.surface(plane(place({0, slot_r, 0}), -(R * Vec3::UnitY()))) : -1;
        const int end_left = slot_a > 0 ? b.surface(cylinder(place({-slot_a, 0, 0}), R * Vec3::UnitZ(), slot_r)) : end_right;

        // Where the ray from the centre along u meets the outline, and on which face.
        auto outline_hit = [&](const Vec3& u, int* face) {
            const double tx = std::abs(u.x()) > 0 ? A / std::abs(u.x()) : 1e300;
            const double ty = std::abs(u.y()) > 0 ? B / std::abs(u.y()) : 1e300;
            const Vec3 p = std::min(tx, ty) * u;
            if (std::abs(p.x()) > A - corner_r && std::abs(p.y()) > B - corner_r) {
                const int k = p.y() > 0 ? (p.x() > 0 ? 0 : 1) : (p.x() > 0 ? 3 : 2);
                const Vec3& m = corner_centre[k];
                const double along = u.dot(m);
                if (face) *face = corner[k];
                return Vec3(std::max(0.0, along + std::sqrt(along * along - m.squaredNorm() + corner_r * corner_r)) * u);
            }
            if (face) *face = tx <= ty ? side[u.x() > 0 ? 0 : 2] : side[u.y() > 0 ? 1 : 3];
            return p;
        };
        const int slot_face[4] = {wall_low, wall_high, end_right, end_left};

        // Samples of both loops, each a ray from the centre that meets the other loop.
        // Rays in order of a pseudo-angle from + − ÷ only (libm's atan2 differs between
        // platforms in its last bits, and the order makes the mesh).
        auto pseudo_angle = [](const Vec3& p) {
            const double x = p.x(), y = p.y();
            if (y >= 0) return x >= 0 ? y / (x + y) : 1 - x / (y - x);
            return x < 0 ? 2 - y / (-x - y) : 3 + x / (x - y);
        };
        struct Ray {
            double angle;
            int from_slot;  // sampled on the slot, not the outline: after it on one angle
            Vec3 inner, outer;
        };
        std::vector<Ray> rays;
        auto add_outer = [&](const Vec3& p) { rays.push_back({pseudo_angle(p), 0, slot_hit(p.normalized(), slot_a, slot_r).offset, p}); };
        auto add_inner = [&](const Vec3& p) { rays.push_back({pseudo_angle(p), 1, p, outline_hit(p.normalized(), nullptr)}); };
        auto arc = [&](const Vec3& m, double r, double from, int n, const std::function<void(const Vec3&)>& add) {
            const std::vector<double> t = b.spacing(n);
            for (int i = 0; i < n; ++i) {
                const double a = from + t[i] * kPi / 2;
                add(m + r * Vec3(portable::cos(a), portable::sin(a), 0));
            }
        };
        const int n_long = b.count(20), n_short = b.count(12), n_corner = b.count(6), n_flat = b.count(12), n_end = b.count(8);
        for (int k = 0; k < 4; ++k) {  // side k from its start to the next corner, then the corner
            const Vec3& from = corner_centre[(k + 3) % 4];
            const Vec3& to = corner_centre[k];
            const Vec3 offset = corner_r * side_normal[k];
            const auto points = b.segment(from + offset, to + offset, k % 2 == 0 ? n_short : n_long);
            for (std::size_t i = 0; i + 1 < points.size(); ++i) add_outer(points[i]);
            arc(to, corner_r, k * kPi / 2, n_corner, add_outer);
        }
        if (slot_a > 0) {
            for (const auto& [from, to] : {std::pair{Vec3(-slot_a, -slot_r, 0), Vec3(slot_a, -slot_r, 0)},
                                           {Vec3(slot_a, slot_r, 0), Vec3(-slot_a, slot_r, 0)}}) {
                const auto points = b.segment(from, to, n_flat);
                for (std::size_t i = 0; i + 1 < points.size(); ++i) add_inner(points[i]);
                const bool right = to.x() > 0;
                arc(Vec3(right ? slot_a : -slot_a, 0, 0), slot_r, right ? -kPi / 2 : kPi / 2, n_end, add_inner);
                arc(Vec3(right ? slot_a : -slot_a, 0, 0), slot_r, right ? 0 : kPi, n_end, add_inner);
            }
        } else {
            for (int k = 0; k < 4; ++k) arc(Vec3::Zero(), slot_r, k * kPi / 2, n_end, add_inner);
        }
        // A total order: standard libraries sort ties differently.
        std::sort(rays.begin(), rays.end(), [](const Ray& x, const Ray& y) {
            return x.angle != y.angle ? x.angle < y.angle : x.from_slot < y.from_slot;
        });
        // Two samples on one ray (one from each loop) would make a sliver.
        rays.erase(std::unique(rays.begin(), rays.end(), [](const Ray& x, const Ray& y) { return y.angle - x.angle < 1e-9; }),
                   rays.end());

        std::vector<Vec3> inner, outer;
        std::vector<int> inner_face, outer_face;
        for (std::size_t i = 0; i < rays.size(); ++i) {
            inner.push_back(rays[i].inner), outer.push_back(rays[i].outer);
            // The piece from this ray to the next lies on the face their bisector meets.
            const Ray& next = rays[(i + 1) % rays.size()];
            const Vec3 u = (rays[i].outer.normalized() + next.outer.normalized()).normalized();
            int face;
            outline_hit(u, &face), outer_face.push_back(face);
            inner_face.push_back(slot_face[slot_hit(u, slot_a, slot_r).piece]);
        }
        const int rows = b.count(8);
        b.band(place_all(outer), place_all(inner), rows, true, bottom);
        b.band(place_all(at_height(outer, T)), place_all(at_height(inner, T)), rows, true, top);
        b.band(place_all(outer), place_all(at_height(outer, T)), 1, true, [&](int j) { return outer_face[j]; });
        b.band(place_all(inner), place_all(at_height(inner, T)), 1, true, [&](int j) { return inner_face[j]; });
    };
    // Quarter turns about x and z, exactly.
    Eigen::Matrix3d upright, crossed;
    upright << 1, 0, 0, 0, 0, -1, 0, 1, 0;
    crossed << 0, -1, 0, 1, 0, 0, 0, 0, 1;
    plate(Eigen::Matrix3d::Identity(), Vec3::Zero(), 0.4);
    plate(crossed, Vec3(0, 0, 0.5), 0);
    plate(upright, Vec3(0, 1.3, 0.3), 0.35);
    return b.finish("plate_assembly");
}

// A hex nut: six flat sides, top and bottom, a bore countersunk 45° at both ends (cones
// one or two facets tall between the bore and the flat annuli): 11 faces.
Part hex_nut(const PartOptions& o) {
    PartBuilder b(o);
    const double circumradius = 0.6, T = 0.5, bore_r = 0.25, sink_r = 0.33, depth = sink_r - bore_r;
    const int bottom = b.surface(plane({0, 0, 0}, -Vec3::UnitZ())), top = b.surface(plane({0, 0, T}, Vec3::UnitZ()));
    const int bore = b.surface(cylinder({0, 0, 0}, Vec3::UnitZ(), bore_r));
    // A cone's apex lies on the axis where its generator reaches r = 0.
    const double half_angle = std::atan(1.0);
    const int sink_top = b.surface({QuadricType::cone, Vec3(0, 0, T - sink_r), Vec3::UnitZ(), 0, half_angle});
    const int sink_bottom = b.surface({QuadricType::cone, Vec3(0, 0, sink_r), -Vec3::UnitZ(), 0, half_angle});
    const PolygonOutline outline = regular_polygon(b, 6, circumradius, b.count(8));
    const std::vector<Vec3>& hexagon = outline.points;
    const Vec3 axis_bottom = Vec3::Zero();
    const auto sink_bottom_outer = onto_circle(hexagon, axis_bottom, sink_r);
    const auto sink_top_outer = at_height(sink_bottom_outer, T);
    const auto bore_bottom = at_height(onto_circle(hexagon, axis_bottom, bore_r), depth);
    const auto bore_top = at_height(bore_bottom, T - depth);
    b.band(hexagon, at_height(hexagon, T), b.count(5), true, [&](int j) { return outline.side[j]; });
    b.band(at_height(hexagon, T), sink_top_outer, b.count(4), true, top);
    b.band(sink_top_outer, bore_top, b.count(2), true, sink_top);
    b.band(bore_top, bore_bottom, b.count(6), true, bore);
    b.band(bore_bottom, sink_bottom_outer, b.count(2), true, sink_bottom);
    b.band(sink_bottom_outer, hexagon, b.count(4), true, bottom);
    return b.finish("hex_nut");
}

// A square plate with a countersunk through hole, the cone and the bore one facet row each
// between bends of 45° (below the crease angle: one chart holds the top, the cone and the
// bore), 24 facets round, as a CAD export of a thin plate tessellates them: 8 faces. Three
// coaxial circles of vertices lie on one hyperboloid of revolution, so only the bend tells
// the cone from the bore.
Part countersunk_plate(const PartOptions& o) {
    PartBuilder b(o);
    const double T = 0.12, bore_r = 0.08, sink_r = 0.14, depth = sink_r - bore_r;
    const int bottom = b.surface(plane({0, 0, 0}, -Vec3::UnitZ())), top = b.surface(plane({0, 0, T}, Vec3::UnitZ()));
    const int bore = b.surface(cylinder({0, 0, 0}, Vec3::UnitZ(), bore_r));
    const int sink = b.surface({QuadricType::cone, Vec3(0, 0, T - sink_r), Vec3::UnitZ(), 0, std::atan(1.0)});
    const PolygonOutline outline = regular_polygon(b, 4, 0.7, b.count(6));
    const std::vector<Vec3>& square = outline.points;
    const auto sink_outer = at_height(onto_circle(square, Vec3::Zero(), sink_r), T);
    const auto bore_top = at_height(onto_circle(square, Vec3::Zero(), bore_r), T - depth);
    b.band(square, at_height(square, T), b.count(2), true, [&](int j) { return outline.side[j]; });
    b.band(at_height(square, T), sink_outer, b.count(6), true, top);
    b.band(sink_outer, bore_top, 1, true, sink);
    b.band(bore_top, at_height(bore_top, 0), 1, true, bore);
    b.band(at_height(bore_top, 0), square, b.count(6), true, bottom);
    return b.finish("countersunk_plate");
}

// A box with every edge chamfered 45°: 6 faces, 12 chamfer strips two facets wide between
// bends of 45° (below the crease angle, so the whole box is one chart), 8 corner triangles:
// 26 planes.
Part chamfered_box(const PartOptions& o) {
    PartBuilder b(o);
    const Vec3 size(1.2, 0.8, 0.6);
    const double c = 0.06;
    const int steps[3] = {b.count(12), b.count(8), b.count(6)};
    // Face (axis k, side s): the plane coord_k = s ? size_k : 0. Its inset corner nearest the
    // box corner with sides `corner`: the other coordinates c in from that corner.
    auto inset_corner = [&](int k, const std::array<int, 3>& corner) {
        Vec3 p;
        for (int i = 0; i < 3; ++i) p[i] = i == k ? corner[i] * size[i] : (corner[i] ? size[i] - c : c);
        return p;
    };
    int face_id[3][2];
    for (int k = 0; k < 3; ++k)
        for (int side = 0; side < 2; ++side) {
            Vec3 normal = Vec3::Zero(), point = Vec3::Zero();
            normal[k] = side ? 1 : -1, point[k] = side * size[k];
            face_id[k][side] = b.surface(plane(point, normal));
        }
    // The inset edge of face (k, s) beside face (m, t), along the third axis j, low to high.
    std::map<std::array<int, 4>, std::vector<Vec3>> edge;
    for (int k = 0; k < 3; ++k)
        for (int s = 0; s < 2; ++s)
            for (int m = 0; m < 3; ++m)
                for (int t = 0; t < 2; ++t) {
                    if (m == k) continue;
                    const int j = 3 - k - m;
                    std::array<int, 3> low{}, high{};
                    low[k] = high[k] = s, low[m] = high[m] = t, low[j] = 0, high[j] = 1;
                    edge[{k, s, m, t}] = b.segment(inset_corner(k, low), inset_corner(k, high), steps[j]);
                }
    for (int k = 0; k < 3; ++k)
        for (int s = 0; s < 2; ++s)
            for (int m = k + 1; m < 3; ++m)
                for (int t = 0; t < 2; ++t) {
                    Vec3 normal = Vec3::Zero();
                    normal[k] = s ? 1 : -1, normal[m] = t ? 1 : -1;
                    b.band(edge[{k, s, m, t}], edge[{m, t, k, s}], b.count(2), false,
                           b.surface(plane(edge[{k, s, m, t}].front(), normal)));
                }
    // Each face: its inset rectangle, filled; axes a, b the other two in cyclic order.
    for (int k = 0; k < 3; ++k)
        for (int s = 0; s < 2; ++s) {
            const int a = (k + 1) % 3, bb = (k + 2) % 3;
            std::vector<Vec3> loop;
            auto reversed = [](std::vector<Vec3> v) { return std::vector<Vec3>(v.rbegin(), v.rend()); };
            append_open(loop, edge[{k, s, bb, 0}]);
            append_open(loop, edge[{k, s, a, 1}]);
            append_open(loop, reversed(edge[{k, s, bb, 1}]));
            append_open(loop, reversed(edge[{k, s, a, 0}]));
            Vec3 centre = 0.5 * size;
            centre[k] = s * size[k];
            b.fill(loop, centre, b.count(6), face_id[k][s]);
        }
    for (int x = 0; x < 2; ++x)
        for (int y = 0; y < 2; ++y)
            for (int z = 0; z < 2; ++z) {
                const std::array<int, 3> corner{x, y, z};
                const Vec3 normal(x ? 1 : -1, y ? 1 : -1, z ? 1 : -1);
                const Vec3 p = inset_corner(0, corner), q = inset_corner(1, corner), r = inset_corner(2, corner);
                b.triangle(p, q, r, b.surface(plane(p, normal)));
            }
    return b.finish("chamfered_box");
}

// A thin-walled tube, its wall 8 % of its radius: outer and inner cylinder, two annular
// ends (4 faces). The two coaxial cylinders lie a few noise widths apart.
Part tube(const PartOptions& o) {
    PartBuilder b(o);
    const double R = 0.5, r = 0.46, L = 1.5;
    const int outer = b.surface(cylinder({0, 0, 0}, Vec3::UnitZ(), R));
    const int bore = b.surface(cylinder({0, 0, 0}, Vec3::UnitZ(), r));
    const int bottom = b.surface(plane({0, 0, 0}, -Vec3::UnitZ())), top = b.surface(plane({0, 0, L}, Vec3::UnitZ()));
    const std::vector<Vec3> outer_ring = b.circle(R, b.count(64));
    bored_prism(b, outer_ring, onto_circle(outer_ring, Vec3::Zero(), r), L, [&](int) { return outer; }, top, bore, bottom,
                b.count(16), b.count(1), b.count(16));
    return b.finish("tube");
}

// A pencil: a cylinder on a flat end, sharpened to a cone's apex (3 faces).
Part pencil(const PartOptions& o) {
    PartBuilder b(o);
    const double R = 0.3, L = 1.6, tip = 0.6;
    const int end = b.surface(plane({0, 0, 0}, -Vec3::UnitZ()));
    const int side = b.surface(cylinder({0, 0, 0}, Vec3::UnitZ(), R));
    const int cone = b.surface({QuadricType::cone, Vec3(0, 0, L + tip), -Vec3::UnitZ(), 0, std::atan(R / tip)});
    const std::vector<Vec3> ring = b.circle(R, b.count(48));
    b.fill(ring, Vec3::Zero(), b.count(5), end);
    b.band(ring, at_height(ring, L), b.count(16), true, side);
    // Rings towards the apex, shrinking linearly along the cone's generators.
    const int rows = b.count(8);
    b.cap(at_height(ring, L), rows, [&](int i) {
        const double s = 1 - double(i) / rows;
        std::vector<Vec3> next;
        for (const Vec3& p : ring) next.emplace_back(s * p.x(), s * p.y(), L + (1 - s) * tip);
        return next;
    }, Vec3(0, 0, L + tip), cone);
    return b.finish("pencil");
}

// A block under a low roof: two roof planes 10° off the horizontal meet along a ridge,
// bending by 20° (below the crease angle: one chart holds both); 7 faces.
Part roof_block(const PartOptions& o) {
    PartBuilder b(o);
    const double W = 2, D = 1.2, H = 0.6, pitch = 10 * kPi / 180, Hr = H + W / 2 * std::tan(pitch);
    const int bottom = b.surface(plane({0, 0, 0}, -Vec3::UnitZ()));
    const int left = b.surface(plane({0, 0, 0}, -Vec3::UnitX())), right = b.surface(plane({W, 0, 0}, Vec3::UnitX()));
    const int front = b.surface(plane({0, 0, 0}, -Vec3::UnitY())), back = b.surface(plane({0, D, 0}, Vec3::UnitY()));
    const int roof_left = b.surface(plane({0, 0, H}, Vec3(-std::sin(pitch), 0, std::cos(pitch))));
    const int roof_right = b.surface(plane({W, 0, H}, Vec3(std::sin(pitch), 0, std::cos(pitch))));
    const Vec3 b00(0, 0, 0), b10(W, 0, 0), b11(W, D, 0), b01(0, D, 0);
    const Vec3 e00(0, 0, H), e10(W, 0, H), e11(W, D, H), e01(0, D, H), r0(W / 2, 0, Hr), r1(W / 2, D, Hr);
    const int nx = b.count(20), ny = b.count(12), nz = b.count(6);
    auto reversed = [](std::vector<Vec3> v) { return std::vector<Vec3>(v.rbegin(), v.rend()); };
    // Every edge once, shared by the two faces on either side of it.
    const auto bx0 = b.segment(b00, b10, nx), bx1 = b.segment(b01, b11, nx);
    const auto by0 = b.segment(b00, b01, ny), by1 = b.segment(b10, b11, ny);
    const auto z00 = b.segment(b00, e00, nz), z10 = b.segment(b10, e10, nz), z11 = b.segment(b11, e11, nz),
               z01 = b.segment(b01, e01, nz);
    const auto eave0 = b.segment(e00, e01, ny), eave1 = b.segment(e10, e11, ny), ridge = b.segment(r0, r1, ny);
    const auto f0 = b.segment(e00, r0, nx / 2), f1 = b.segment(r0, e10, nx / 2);  // the front gable
    const auto k0 = b.segment(e01, r1, nx / 2), k1 = b.segment(r1, e11, nx / 2);  // the back gable
    auto face = [&](std::initializer_list<std::vector<Vec3>> pieces, int label) {
        std::vector<Vec3> loop;
        Vec3 centre = Vec3::Zero();
        for (const auto& piece : pieces) append_open(loop, piece);
        for (const Vec3& p : loop) centre += p;
        b.fill(loop, centre / loop.size(), b.count(6), label);
    };
    face({bx0, by1, reversed(bx1), reversed(by0)}, bottom);
    face({by0, z01, reversed(eave0), reversed(z00)}, left);
    face({by1, z11, reversed(eave1), reversed(z10)}, right);
    face({bx0, z10, reversed(f1), reversed(f0), reversed(z00)}, front);
    face({bx1, z11, reversed(k1), reversed(k0), reversed(z01)}, back);
    face({f0, ridge, reversed(k0), reversed(eave0)}, roof_left);
    face({f1, eave1, reversed(k1), reversed(ridge)}, roof_right);
    return b.finish("roof_block");
}

// A plate with a hole drilled 35° off its normal: the hole meets both faces along ellipses;
// 7 faces.
Part oblique_hole(const PartOptions& o) {
    PartBuilder b(o);
    const double W = 2, T = 0.3, r = 0.3, tilt = 35 * kPi / 180;
    const Vec3 axis(std::sin(tilt), 0, std::cos(tilt));
    const Vec3 centre(W / 2, W / 2, 0);  // where the axis meets the bottom face
    const int bottom = b.surface(plane({0, 0, 0}, -Vec3::UnitZ())), top = b.surface(plane({0, 0, T}, Vec3::UnitZ()));
    const int hole = b.surface(cylinder(centre, axis, r));
    std::vector<int> side;
    const Vec3 corners[4] = {{0, 0, 0}, {W, 0, 0}, {W, W, 0}, {0, W, 0}};
    std::vector<Vec3> outline;
    std::vector<int> outline_face;
    for (int k = 0; k < 4; ++k) {
        const Vec3 &from = corners[k], &to = corners[(k + 1) % 4];
        side.push_back(b.surface(plane(from, (to - from).cross(Vec3::UnitZ()).normalized())));
        const auto edge = b.segment(from, to, b.count(16));
        append_open(outline, edge);
        outline_face.insert(outline_face.end(), edge.size() - 1, side.back());
    }
    // The hole's section by a plane z = const is an ellipse about the axis's point there,
    // r / cos(tilt) along x and r along y: each outline point's ray meets it once.
    auto ellipse = [&](double z) {
        const Vec3 c = centre + axis * (z / axis.z());
        std::vector<Vec3> out;
        for (const Vec3& p : outline) {
            const Vec3 d = (Vec3(p.x(), p.y(), 0) - Vec3(c.x(), c.y(), 0)).normalized();
            const double a = r / std::cos(tilt), rho = 1 / std::sqrt(d.x() * d.x() / (a * a) + d.y() * d.y() / (r * r));
            out.push_back(Vec3(c.x(), c.y(), z) + rho * d);
        }
        return out;
    };
    const auto hole_top = ellipse(T);
    // The bottom ellipse point on the same generator as each top one.
    std::vector<Vec3> hole_bottom;
    for (const Vec3& p : hole_top) hole_bottom.push_back(p - axis * (T / axis.z()));
    b.band(outline, hole_bottom, b.count(8), true, bottom);
    b.band(at_height(outline, T), hole_top, b.count(8), true, top);
    b.band(hole_bottom, hole_top, b.count(4), true, hole);
    b.band(outline, at_height(outline, T), b.count(3), true, [&](int j) { return outline_face[j]; });
    return b.finish("oblique_hole");
}

// A shaft with a flat: a cylinder cut by a plane along its axis, 0.08 of its 0.3 radius
// deep; the flat meets the cylinder at 43° (below the crease angle). Two D-shaped ends; 4 faces.
Part d_shaft(const PartOptions& o) {
    PartBuilder b(o);
    const double R = 0.3, L = 1.5, y = 0.22;
    const double theta = std::asin(y / R);  // the flat's edges at angles theta and pi - theta
    const int side = b.surface(cylinder({0, 0, 0}, Vec3::UnitZ(), R));
    const int flat = b.surface(plane({0, y, 0}, Vec3::UnitY()));
    const int bottom = b.surface(plane({0, 0, 0}, -Vec3::UnitZ())), top = b.surface(plane({0, 0, L}, Vec3::UnitZ()));
    std::vector<Vec3> loop;
    std::vector<int> label;
    const int arc = b.count(40);
    for (double t : b.spacing(arc)) {
        const double a = kPi - theta + t * (kPi + 2 * theta);  // the long way round
        loop.emplace_back(R * portable::cos(a), R * portable::sin(a), 0);
    }
    loop.pop_back();
    label.assign(loop.size(), side);
    const auto chord = b.segment(Vec3(R * std::cos(theta), y, 0), Vec3(-R * std::cos(theta), y, 0), b.count(8));
    append_open(loop, chord);
    label.insert(label.end(), chord.size() - 1, flat);
    b.fill(loop, Vec3::Zero(), b.count(5), bottom);
    b.band(loop, at_height(loop, L), b.count(16), true, [&](int j) { return label[j]; });
    b.fill(at_height(loop, L), Vec3(0, 0, L), b.count(5), top);
    return b.finish("d_shaft");
}

// An octagonal prism with a through bore: neighbouring sides bend by 45°, below the crease
// angle, so the eight sides are one chart about as round as a cylinder; 11 faces.
Part octagon_bore(const PartOptions& o) {
    PartBuilder b(o);
    const double circumradius = 0.6, T = 0.5, bore_r = 0.25;
    const int bottom = b.surface(plane({0, 0, 0}, -Vec3::UnitZ())), top = b.surface(plane({0, 0, T}, Vec3::UnitZ()));
    const int bore = b.surface(cylinder({0, 0, 0}, Vec3::UnitZ(), bore_r));
    const PolygonOutline outline = regular_polygon(b, 8, circumradius, b.count(6));
    bored_prism(b, outline.points, onto_circle(outline.points, Vec3::Zero(), bore_r), T,
                [&](int j) { return outline.side[j]; }, top, bore, bottom, b.count(5), b.count(4), b.count(6));
    return b.finish("octagon_bore");
}

// A cylinder under a shallow spherical dome (radius 0.6 on a 0.5 cylinder: they meet at 34°,
// below the crease angle); 3 faces.
Part domed_cylinder(const PartOptions& o) {
    PartBuilder b(o);
    const double R = 0.5, L = 0.8, Rs = 0.6, h = std::sqrt(Rs * Rs - R * R);  // sphere centre h below the rim
    const int bottom = b.surface(plane({0, 0, 0}, -Vec3::UnitZ()));
    const int side = b.surface(cylinder({0, 0, 0}, Vec3::UnitZ(), R));
    const int dome = b.surface({QuadricType::sphere, Vec3(0, 0, L - h), Vec3::UnitZ(), Rs});
    const std::vector<Vec3> ring = b.circle(R, b.count(48));
    b.fill(ring, Vec3::Zero(), b.count(5), bottom);
    b.band(ring, at_height(ring, L), b.count(12), true, side);
    const double rim = std::asin(R / Rs);  // polar angle of the rim from the dome's top
    const int rows = b.count(8);
    b.cap(at_height(ring, L), rows, [&](int i) {
        const double polar = rim * (1 - double(i) / rows), r = Rs * std::sin(polar);
        std::vector<Vec3> next;
        for (const Vec3& p : ring) next.emplace_back(p.x() * r / R, p.y() * r / R, L - h + Rs * std::cos(polar));
        return next;
    }, Vec3(0, 0, L - h + Rs), dome);
    return b.finish("domed_cylinder");
}

// A round bar cut at 50° to its axis: the cut meets the side at 140° on one side and at 40°,
// below the crease angle, on the other, so the crease between them runs out half way
// round and the two faces are one chart; 3 faces.
Part angled_cut(const PartOptions& o) {
    PartBuilder b(o);
    const double R = 0.4, L = 1.0, slope = std::tan(50 * kPi / 180);
    const int bottom = b.surface(plane({0, 0, 0}, -Vec3::UnitZ()));
    const int side = b.surface(cylinder({0, 0, 0}, Vec3::UnitZ(), R));
    const int cut = b.surface(plane({0, 0, L}, Vec3(-slope, 0, 1)));
    const std::vector<Vec3> ring = b.circle(R, b.count(48));
    std::vector<Vec3> rim;
    for (const Vec3& p : ring) rim.emplace_back(p.x(), p.y(), L + slope * p.x());
    b.fill(ring, Vec3::Zero(), b.count(5), bottom);
    b.band(ring, rim, b.count(14), true, side);
    b.fill(rim, Vec3(0, 0, L), b.count(6), cut);
    return b.finish("angled_cut");
}

// A hemispherical bowl whose wall is 4 % of its radius thick: two concentric spheres facing
// opposite ways and the flat rim between them, one facet wide; 3 faces.
Part bowl(const PartOptions& o) {
    PartBuilder b(o);
    const double R = 1.0, r = 0.96;
    const int outer = b.surface({QuadricType::sphere, Vec3::Zero(), Vec3::UnitZ(), R});
    const int inner = b.surface({QuadricType::sphere, Vec3::Zero(), Vec3::UnitZ(), r});
    const int rim = b.surface(plane(Vec3::Zero(), Vec3::UnitZ()));
    const std::vector<Vec3> ring = b.circle(1.0, b.count(64));
    auto hemisphere = [&](double radius, int label) {
        const int rows = b.count(16);
        const std::vector<Vec3> start = onto_circle(ring, Vec3::Zero(), radius);
        b.cap(start, rows, [&](int i) {
            const double polar = 0.5 * kPi * i / rows;  // from the rim down
            std::vector<Vec3> next;
            for (const Vec3& p : ring) next.emplace_back(p.x() * radius * std::cos(polar), p.y() * radius * std::cos(polar), -radius * std::sin(polar));
            return next;
        }, Vec3(0, 0, -radius), label);
    };
    hemisphere(R, outer);
    hemisphere(r, inner);
    b.band(onto_circle(ring, Vec3::Zero(), R), onto_circle(ring, Vec3::Zero(), r), 1, true, rim);
    return b.finish("bowl");
}

// A disc whose top is a paraboloid of revolution (z = h − ρ²/4f) meeting its cylindrical
// side at 51°: a quadric that is none of the elementary types, between two that are; 3 faces.
Part dish(const PartOptions& o) {
    PartBuilder b(o);
    const double R = 0.8, H = 0.25, f = 0.5, top = H + R * R / (4 * f);
    const int bottom = b.surface(plane({0, 0, 0}, -Vec3::UnitZ()));
    const int side = b.surface(cylinder({0, 0, 0}, Vec3::UnitZ(), R));
    const int dome = b.surface({QuadricType::elliptic_paraboloid, Vec3(0, 0, top), Vec3::UnitZ(), 2 * f});
    const std::vector<Vec3> ring = b.circle(R, b.count(48));
    b.fill(ring, Vec3::Zero(), b.count(5), bottom);
    b.band(ring, at_height(ring, H), b.count(4), true, side);
    const int rows = b.count(10);
    b.cap(at_height(ring, H), rows, [&](int i) {
        const double rho = R * (1 - double(i) / rows);
        std::vector<Vec3> next;
        for (const Vec3& p : ring) next.emplace_back(p.x() * rho / R, p.y() * rho / R, top - rho * rho / (4 * f));
        return next;
    }, Vec3(0, 0, top), dome);
    return b.finish("dish");
}

// A slice of sheet whose two long edges are rolled round (a stadium in section, as the
// segments of a sheet-metal hinge in the ABC dataset): each flat face two long triangles
// tangent to a half cylinder of 63 facets, each end a fan; 6 faces.
Part rolled_sheet(const PartOptions& o) {
    PartBuilder b(o);
    const double W = 0.6, L = 0.025, T = 0.032, r = T / 2;
    const int top = b.surface(plane({0, 0, T}, Vec3::UnitZ())), bottom = b.surface(plane({0, 0, 0}, -Vec3::UnitZ()));
    const int right = b.surface(cylinder({W, 0, r}, Vec3::UnitY(), r)), left = b.surface(cylinder({0, 0, r}, Vec3::UnitY(), r));
    const int front = b.surface(plane({0, 0, 0}, -Vec3::UnitY())), rear = b.surface(plane({0, L, 0}, Vec3::UnitY()));
    // The section at y = 0, a closed loop: the bottom edge, the right roll up, the top edge,
    // the left roll down. The band along y gives quad j (from point j to the next) to label[j].
    const int facets = b.count(63);
    std::vector<Vec3> section{{0, 0, 0}};
    std::vector<int> label{bottom};
    auto roll = [&](const Vec3& start, double centre_x, double from, int surface) {
        for (int k = 0; k < facets; ++k) {
            const double angle = from + kPi * k / facets;
            section.push_back(k == 0 ? start : Vec3(centre_x + r * portable::cos(angle), 0, r + r * portable::sin(angle)));
            label.push_back(surface);
        }
    };
    roll({W, 0, 0}, W, -kPi / 2, right);
    section.emplace_back(W, 0, T);
    label.push_back(top);
    roll({0, 0, T}, 0, kPi / 2, left);
    std::vector<Vec3> far;
    for (const Vec3& p : section) far.emplace_back(p.x(), L, p.z());
    b.band(section, far, b.count(1), true, [&](int j) { return label[j]; });
    b.fill(section, Vec3(W / 2, 0, r), b.count(2), front);
    b.fill(far, Vec3(W / 2, L, r), b.count(2), rear);
    return b.finish("rolled_sheet");
}

// A plate whose four upright edges are rounded, meshed as CAD exports often mesh a pocket
// or a boss (trimesh's featuretype.STL, octagonal_pocket.stl): each side one quad, two long
// triangles, each corner a quarter cylinder of 11 facets, top and bottom fans; beside it,
// apart, a slab seven times its size (so the plate is as small against the whole as a
// pocket is in a part), its sides one quad each too; 16 faces.
Part rounded_plate(const PartOptions& o) {
    PartBuilder b(o);
    auto direction = [](double angle) { return Vec3(portable::cos(angle), portable::sin(angle), 0); };
    const double W = 1.0, D = 0.6, T = 0.2, r = 0.1;
    const Vec3 centres[4] = {{W - r, r, 0}, {W - r, D - r, 0}, {r, D - r, 0}, {r, r, 0}};
    // Corner k turns from −90° + 90°k to 90°k, and the side after it faces 90°k.
    const int facets = b.count(11);
    std::vector<Vec3> outline;
    std::vector<int> label;
    for (int k = 0; k < 4; ++k) {
        const int corner = b.surface(cylinder(centres[k], Vec3::UnitZ(), r));
        const int side = b.surface(plane(centres[k] + r * direction(kPi / 2 * k), direction(kPi / 2 * k)));
        for (int i = 0; i < facets; ++i) {
            outline.push_back(centres[k] + r * direction(kPi / 2 * (k - 1) + kPi / 2 * i / facets));
            label.push_back(corner);
        }
        outline.push_back(centres[k] + r * direction(kPi / 2 * k));
        label.push_back(side);
    }
    flat_prism(b, outline, label, T, {W / 2, D / 2, 0});
    const double x0 = -1, y0 = -6, X = 7, Y = 5;
    const std::vector<Vec3> slab{{x0, y0, 0}, {x0 + X, y0, 0}, {x0 + X, y0 + Y, 0}, {x0, y0 + Y, 0}};
    std::vector<int> sides;
    for (int k = 0; k < 4; ++k) sides.push_back(b.surface(plane(slab[k], direction(kPi / 2 * (k - 1)))));
    flat_prism(b, slab, sides, 0.5, {x0 + X / 2, y0 + Y / 2, 0});
    return b.finish("rounded_plate");
}

// A block whose back steps in by a tenth of its depth through a 37° chamfer (below the
// crease angle: one chart holds the two walls and the chamfer), each wall meshed as an
// export meshes a side that other features cut, in quads of two full-height triangles
// (five and ten of them), the chamfer one quad: three faces of strips whose vertices lie on
// lines, on many quadrics together; 8 faces.
Part stepped_block(const PartOptions& o) {
    PartBuilder b(o);
    const double W = 1.0, D = 0.5, step = 0.05, run = step * 4 / 3, H = 0.19, x_step = 0.45;
    const int front = b.surface(plane({0, 0, 0}, -Vec3::UnitY()));
    const int right = b.surface(plane({W, 0, 0}, Vec3::UnitX()));
    const int back_low = b.surface(plane({W, D - step, 0}, Vec3::UnitY()));
    const int chamfer = b.surface(plane({x_step + run, D - step, 0}, Vec3(step, run, 0).normalized()));
    const int back_high = b.surface(plane({0, D, 0}, Vec3::UnitY()));
    const int left = b.surface(plane({0, 0, 0}, -Vec3::UnitX()));
    std::vector<Vec3> outline{{0, 0, 0}, {W, 0, 0}};
    std::vector<int> label{front, right};
    const int low = b.count(10), high = b.count(5);
    for (int k = 0; k < low; ++k) {
        outline.emplace_back(W - (W - x_step - run) * k / low, D - step, 0);
        label.push_back(back_low);
    }
    outline.emplace_back(x_step + run, D - step, 0);
    label.push_back(chamfer);
    for (int k = 0; k < high; ++k) {
        outline.emplace_back(x_step - x_step * k / high, D, 0);
        label.push_back(back_high);
    }
    outline.emplace_back(0, D, 0);
    label.push_back(left);
    flat_prism(b, outline, label, H, {W / 2, D / 2, 0});
    return b.finish("stepped_block");
}

}  // namespace

std::vector<std::string> corpus_part_names() {
    return {"box_boss_hole", "l_bracket", "stepped_shaft", "flange", "thin_plate", "slotted_block"};
}

std::vector<std::string> part_names() {
    std::vector<std::string> names = corpus_part_names();
    names.push_back("rounded_block");
    names.push_back("plate_assembly");
    names.push_back("hex_nut");
    names.push_back("chamfered_box");
    names.push_back("tube");
    names.push_back("pencil");
    names.push_back("roof_block");
    names.push_back("oblique_hole");
    names.push_back("d_shaft");
    names.push_back("octagon_bore");
    names.push_back("domed_cylinder");
    names.push_back("angled_cut");
    names.push_back("bowl");
    names.push_back("dish");
    names.push_back("rolled_sheet");
    names.push_back("countersunk_plate");
    names.push_back("rounded_plate");
    names.push_back("stepped_block");  // last: a part's seed follows its place in this list
    return names;
}

void add_normal_noise(Mesh& mesh, double relative, std::uint64_t seed) {
    Random random(seed);
    displace_along_normals(mesh, relative, random);
}

Part make_part(const std::string& name, const PartOptions& options) {
    if (name == "box_boss_hole") return box_boss_hole(options);
    if (name == "l_bracket") return l_bracket(options);
    if (name == "stepped_shaft") return stepped_shaft(options);
    if (name == "flange") return flange(options);
    if (name == "thin_plate") return thin_plate(options);
    if (name == "slotted_block") return slotted_block(options);
    if (name == "rounded_block") return rounded_block(options);
    if (name == "plate_assembly") return plate_assembly(options);
    if (name == "hex_nut") return hex_nut(options);
    if (name == "countersunk_plate") return countersunk_plate(options);
    if (name == "chamfered_box") return chamfered_box(options);
    if (name == "tube") return tube(options);
    if (name == "pencil") return pencil(options);
    if (name == "roof_block") return roof_block(options);
    if (name == "oblique_hole") return oblique_hole(options);
    if (name == "d_shaft") return d_shaft(options);
    if (name == "octagon_bore") return octagon_bore(options);
    if (name == "domed_cylinder") return domed_cylinder(options);
    if (name == "angled_cut") return angled_cut(options);
    if (name == "bowl") return bowl(options);
    if (name == "dish") return dish(options);
    if (name == "rolled_sheet") return rolled_sheet(options);
    if (name == "rounded_plate") return rounded_plate(options);
    if (name == "stepped_block") return stepped_block(options);
    throw std::invalid_argument("unknown part '" + name + "'");
}

}  // namespace vqsa
