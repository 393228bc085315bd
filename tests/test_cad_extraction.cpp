// CAD extraction: the procedural corpus (examples/cad_parts.h) scored against its true
// faces at the true count and with the automatic count; validity of every result (no
// region on two parts of its quadric) on the corpus, the shared meshes and tolerance runs;
// the seed and the initialisations.
#include "cad_parts.h"
#include "examples.h"
#include "export/report.h"
#include "ground_truth.h"
#include "shapes.h"
#include "fitting/fit.h"
#include "fitting/model_selection.h"
#include "fitting/samples.h"
#include "fitting/special_fit.h"
#include "geometry/features.h"
#include "geometry/model.h"
#include "geometry/rng.h"
#include "io/mesh_io.h"
#include "lloyd/lloyd.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <map>
#include <set>
#include <stdexcept>
#include <tuple>

using namespace vqsa;

namespace {

struct Outcome {
    double accuracy;
    int regions;
    int two_part;
    Result result;
    PartitionScore score;
};

Outcome run(const Part& part, const Options& options) {
    Result r = test::approximate(part.mesh, options);
    const int regions = static_cast<int>(r.proxies.size());
    PartitionScore score = score_partition(part, r.face_labels, regions);
    const int two_part = two_part_regions(part.mesh, r);
    return {score.accuracy, regions, two_part, std::move(r), std::move(score)};
}

Options counted(int proxies, std::uint64_t seed = 1) {
    Options o = test::with_proxies(proxies, seed);
    o.project = false;
    return o;
}

// The corpus's case of this part and variant (its own pose, noise and seed).
CorpusCase corpus_case(const std::string& part_name, const std::string& variant) {
    for (const CorpusCase& c : cad_corpus({part_name}))
        if (c.variant == variant) return c;
    throw std::invalid_argument("no corpus case " + part_name + " " + variant);
}

// The same case exported at another detail.
CorpusCase corpus_case(const std::string& part_name, const std::string& variant, double detail) {
    CorpusCase c = corpus_case(part_name, variant);
    c.options.detail = detail;
    return c;
}

// The corpus's case at its true count. `seed_offset`: added to the corpus's seed for the
// method's choices (the same mesh).
std::pair<Part, Outcome> corpus_case_at_true_count(const std::string& part_name, const std::string& variant,
                                                   std::uint64_t seed_offset = 0) {
    const CorpusCase c = corpus_case(part_name, variant);
    Part part = make_part(c.part, c.options);
    Outcome o = run(part, counted(static_cast<int>(part.surfaces.size()), c.options.seed + seed_offset));
    return {std::move(part), std::move(o)};
}

// Of the part's large faces (at least `large` of its triangles), how many there are and how
// many one region holds (at least `whole` of their triangles).
struct WholeFaces {
    int large = 0;
    int whole = 0;
};
WholeFaces whole_large_faces(const Part& part, const std::vector<int>& labels, double large = 0.1,
                             double whole = 0.9) {
    WholeFaces out;
    for (int face = 0; face < static_cast<int>(part.surfaces.size()); ++face) {
        std::map<int, int> regions;  // region → triangles of this face
        int triangles = 0;
        for (std::size_t t = 0; t < part.face.size(); ++t)
            if (part.face[t] == face) ++regions[labels[t]], ++triangles;
        if (triangles < large * static_cast<double>(part.face.size())) continue;
        ++out.large;
        int most = 0;
        for (const auto& [region, n] : regions) most = std::max(most, n);
        out.whole += most >= whole * triangles;
    }
    return out;
}

// Region → true face → its triangles there, over the true faces `counted` admits (all
// without it).
using FacesHeld = std::map<int, std::map<int, int>>;
FacesHeld faces_held(const Part& part, const std::vector<int>& labels, const std::function<bool(int)>& counted = {}) {
    FacesHeld held;
    for (std::size_t t = 0; t < part.face.size(); ++t)
        if (!counted || counted(part.face[t])) ++held[labels[t]][part.face[t]];
    return held;
}

// How many regions hold a tenth or more of each of two large faces (at least `large` of the
// part's triangles each).
int regions_over_two_large_faces(const Part& part, const std::vector<int>& labels, double large = 0.1) {
    std::map<int, int> triangles;  // face → its triangles
    for (int face : part.face) ++triangles[face];
    const FacesHeld held = faces_held(part, labels, [&](int face) {
        return triangles[face] >= large * static_cast<double>(part.face.size());
    });
    int count = 0;
    for (const auto& [region, faces] : held) {
        int sizeable = 0;
        for (const auto& [face, n] : faces) sizeable += n >= 0.1 * triangles[face];
        count += sizeable >= 2;
    }
    return count;
}

// Accuracy ≥ 0.97 on average and ≥ 0.90 on every mesh, no two-part region.
void expect_corpus_scores(const std::vector<Outcome>& runs, const std::vector<CorpusCase>& corpus) {
    double sum = 0;
    for (std::size_t i = 0; i < runs.size(); ++i) {
        SCOPED_TRACE(corpus[i].part + " " + corpus[i].variant);
        EXPECT_GE(runs[i].accuracy, 0.90);
        EXPECT_EQ(runs[i].two_part, 0);
        sum += runs[i].accuracy;
    }
    EXPECT_GE(sum / runs.size(), 0.97);
}

// On every patch matched cleanly to its true face (sharing 90 % of the area of each):
// counts the type right or wrong, and of the right ones checks the parameters — plane
// normal within 0.1°, radius within 0.5 % (1 % under noise), axes within 1°, cone
// half-angle within 0.5°. Under noise a plane's normal is held to what the noise allows:
// within a quarter more than the orthogonal fit to its true face's vertices.
void expect_types_and_parameters(const Part& part, const std::string& variant, const Outcome& run,
                                 std::pair<int, int>& typed) {
    const bool noisy = variant == "noisy";
    for (const ProxyResult& p : run.result.proxies) {
        const int face = run.score.face_of[p.id];
        if (face < 0 || !run.score.clean_match[p.id]) continue;
        const TrueSurface& truth = part.surfaces[face];
        ++typed.second;
        if (p.type != truth.type) continue;
        ++typed.first;
        SCOPED_TRACE(std::string("region ") + std::to_string(p.id) + " " + type_name(p.type));
        const ParameterError e = parameter_error(truth, p.shape);
        if (truth.type == QuadricType::plane) {
            double limit = 0.1;
            if (noisy) {
                const ParameterError oracle = parameter_error(truth, fit_plane_geometric(true_face_vertices(part, face))->shape);
                limit = std::max(limit, 1.25 * oracle.axis_degrees);
            }
            EXPECT_LE(e.axis_degrees, limit);
        } else if (!std::isnan(e.axis_degrees)) {
            double limit = 1.0, half_angle_limit = 0.5;
            if (noisy && truth.type == QuadricType::cone) {
                // A chamfer is a narrow band: under noise its axis and angle are about as far
                // off as the fit to exactly its true vertices, started from the truth; the few
                // faces of a neighbour its region holds (the stepped shaft's: 3 of 387) bend
                // it a little more (1.45 and 1.6 times the oracle's errors there).
                const auto oracle_fit = fit_cone_geometric(true_face_vertices(part, face), truth.axis, truth.point);
                ASSERT_TRUE(oracle_fit.has_value());
                const ParameterError oracle = parameter_error(truth, oracle_fit->shape);
                limit = std::max(limit, 1.75 * oracle.axis_degrees);
                half_angle_limit = std::max(half_angle_limit, 1.75 * oracle.half_angle_degrees);
            }
            EXPECT_LE(e.axis_degrees, limit);
            if (!std::isnan(e.half_angle_degrees)) EXPECT_LE(e.half_angle_degrees, half_angle_limit);
        }
        if (!std::isnan(e.radius_relative)) EXPECT_LE(e.radius_relative, noisy ? 0.01 : 0.005);
    }
}

}  // namespace

// Each case runs with its own seed, as bench/cad_extraction.cpp does (the numbers in
// bench/RESULTS.md).
TEST(CadExtraction, CorpusAtTheTrueCount) {
    const std::vector<CorpusCase> corpus = cad_corpus();
    std::vector<Outcome> runs;
    std::map<std::string, std::pair<int, int>> typed;  // variant → (typed right, patches)
    for (const CorpusCase& c : corpus) {
        const Part part = make_part(c.part, c.options);
        runs.push_back(run(part, counted(static_cast<int>(part.surfaces.size()), c.options.seed)));
        // Fewer only by merging pieces of one surface or slivers (decide_at_target): 15 %,
        // or one (the noisy thin plate loses a side, a strip a few facets wide).
        const int truth = static_cast<int>(part.surfaces.size());
        EXPECT_LE(runs.back().regions, truth) << c.part << " " << c.variant;
        EXPECT_GE(runs.back().regions, truth - std::max(1.0, 0.15 * truth)) << c.part << " " << c.variant;
        expect_types_and_parameters(part, c.variant, runs.back(), typed[c.variant]);
    }
    expect_corpus_scores(runs, corpus);
    // Patches typed right: ≥ 95 % on clean and irregular meshes, ≥ 90 % under noise.
    for (const auto& [variant, count] : typed) {
        SCOPED_TRACE(variant);
        EXPECT_GE(count.first, (variant == "noisy" ? 0.90 : 0.95) * count.second) << count.first << " of " << count.second;
    }
}

// The facet strip along a tangent seam (a leg of the L-bracket beside its fillet, the
// slot's walls beside its round ends) goes to the curved side, and the flat side is a
// plane, not a parabolic cylinder or a sphere bent into the strip. (Not yet on the
// irregular L-bracket: there the upper leg's region reaches several coarse facets into the
// fillet, deeper than a strip, and is typed a cylinder; bench/RESULTS.md.)
TEST(CadExtraction, TangentSeamStripsGoToTheCurvedSide) {
    for (const CorpusCase& c : cad_corpus()) {
        if (c.variant == "noisy" || (c.part != "l_bracket" && c.part != "slotted_block")) continue;
        if (c.part == "l_bracket" && c.variant == "irregular") continue;
        SCOPED_TRACE(c.part + " " + c.variant);
        const Part part = make_part(c.part, c.options);
        const Outcome o = run(part, counted(static_cast<int>(part.surfaces.size()), c.options.seed));
        EXPECT_GE(o.accuracy, 0.98);
        for (const ProxyResult& p : o.result.proxies) {
            const int face = o.score.face_of[p.id];
            ASSERT_GE(face, 0);
            if (part.surfaces[face].type == QuadricType::plane && o.score.clean_match[p.id]) {
                EXPECT_EQ(p.type, QuadricType::plane) << "region " << p.id << " is " << type_name(p.type);
            }
        }
    }
}

TEST(CadExtraction, CylindersBesideTorusFilletsHoldNoneOfThem) {
    // A turned part: a base, a cylinder, a torus fillet (no quadric holds it) up to a plane
    // shoulder, a concave one down to a neck, a top. Automatically each fillet comes out in
    // bands, and each cylinder's region held its fillet's first row of facets, which bent
    // it into an ellipsoid or a hyperboloid: the band's quadric as fitted explained none of
    // them, so the seam step kept them. Those faces have vertices off the cylinder, and the
    // band, refitted with them, holds its own faces about as well.
    std::vector<ProfilePoint> profile{{0, 0, 0}};
    add_segment(profile, 1.0, 0, 10, 0);
    add_segment(profile, 1.0, 0.8, 12, 1);
    add_arc(profile, 0.8, 0.8, 0.2, 0, M_PI / 2, 10, 2);
    add_segment(profile, 0.4, 1.0, 6, 3);
    add_arc(profile, 0.4, 1.1, 0.1, -M_PI / 2, -M_PI, 8, 4);
    add_segment(profile, 0.3, 1.6, 10, 5);
    add_segment(profile, 0.0, 1.6, 5, 6);
    const Shape part = revolve(profile, 96);
    const Result r = test::approximate(part.mesh, counted(0));
    std::map<int, std::map<int, int>> patches;  // region → patch → faces
    for (std::size_t f = 0; f < part.patch.size(); ++f) ++patches[r.face_labels[f]][part.patch[f]];
    for (const auto& [patch, radius] : {std::pair{1, 1.0}, std::pair{5, 0.3}}) {
        SCOPED_TRACE("patch " + std::to_string(patch));
        int regions = 0;
        for (const ProxyResult& p : r.proxies) {
            if (!patches[p.id].count(patch)) continue;
            ++regions;
            EXPECT_EQ(patches[p.id].size(), 1u) << "the cylinder's region holds faces of another patch";
            EXPECT_EQ(p.type, QuadricType::cylinder) << type_name(p.type);
            EXPECT_NEAR(p.shape.radius, radius, 1e-9);
        }
        EXPECT_EQ(regions, 1);
    }
}

TEST(CadExtraction, CorpusWithTheAutomaticCount) {
    const std::vector<CorpusCase> corpus = cad_corpus();
    std::vector<Outcome> runs;
    for (const CorpusCase& c : corpus) {
        SCOPED_TRACE(c.part + " " + c.variant);
        const Part part = make_part(c.part, c.options);
        runs.push_back(run(part, counted(0, c.options.seed)));
        const double truth = static_cast<double>(part.surfaces.size());
        EXPECT_LE(std::abs(runs.back().regions - truth), 0.15 * truth) << runs.back().regions << " regions";
    }
    expect_corpus_scores(runs, corpus);
}

TEST(CadExtraction, ShapesBeyondTheCorpusAreTheirFacesAutomatically) {
    // A thin tube, a pencil (a cone sharpened from its cylinder, one chart), a roof bending
    // 20° at its ridge (one chart), a hole drilled 35° off a plate's normal, a shaft with a
    // flat meeting its cylinder at 43°, an octagonal prism (sides bending 45°) with a bore, a
    // cylinder under a dome meeting it at 34°, a bar cut at 50° (its crease runs out half way
    // round), a bowl whose wall is two concentric spheres 4 % of their radius apart, a disc
    // under a paraboloid: clean, noisy and irregular, the automatic count is the face count
    // and each region one face.
    for (const CorpusCase& c : cad_corpus({"tube", "pencil", "roof_block", "oblique_hole", "d_shaft", "octagon_bore",
                                           "domed_cylinder", "angled_cut", "bowl", "dish"})) {
        SCOPED_TRACE(c.part + " " + c.variant);
        const Part part = make_part(c.part, c.options);
        const Outcome o = run(part, counted(0, c.options.seed));
        EXPECT_EQ(o.regions, static_cast<int>(part.surfaces.size()));
        EXPECT_GE(o.accuracy, 0.999);
        EXPECT_EQ(o.two_part, 0);
    }
}

TEST(CadExtraction, TheCutBarTheBowlAndTheDishAreTypedAsTheirFaces) {
    // Each region typed as the face it holds: the bowl's two spheres (radii within 1 %), the
    // cut bar's planes and cylinder, the dish's plane, cylinder and paraboloid, which no
    // elementary type holds. Under noise (0.2 % of the diagonal) the paraboloid is typed a
    // sphere: the refit takes an elementary type within the region's scatter (docs/METHOD.md
    // §6), and the best sphere strays from the paraboloid by 0.84 of the paraboloid's RMS there.
    for (const CorpusCase& c : cad_corpus({"angled_cut", "bowl", "dish"})) {
        SCOPED_TRACE(c.part + " " + c.variant);
        const Part part = make_part(c.part, c.options);
        const Outcome o = run(part, counted(static_cast<int>(part.surfaces.size()), c.options.seed));
        for (const ProxyResult& p : o.result.proxies) {
            const int face = o.score.face_of[p.id];
            ASSERT_GE(face, 0);
            const TrueSurface& truth = part.surfaces[face];
            if (c.variant == "noisy" && truth.type == QuadricType::elliptic_paraboloid) continue;
            EXPECT_EQ(type_name(p.type), std::string(type_name(truth.type))) << "region " << p.id;
            if (truth.type == QuadricType::sphere) EXPECT_NEAR(p.shape.radius, truth.radius, 0.01 * truth.radius);
        }
    }
}

TEST(CadExtraction, ASheetsTwoTriangleFacesStayApartFromItsRolledEdges) {
    // A slice of sheet rolled round at both long edges (a segment of an ABC sheet-metal
    // hinge): each flat face two long triangles tangent to a half cylinder of 63 facets. The
    // finish took such a face, an exact plane whose roughness is the sag of the bend beside
    // it, into the end face as one pair of planes (two faces are no second part by the count
    // that keeps noise out) or into its roll (a cylinder of three times the roll's radius on
    // the hinge). At 25 facets a roll (detail 0.4) the growth stopped at 5 with a roll in
    // halves, each with a face: that face's roughness was the sag of the 7° bend beside it
    // over the face's own width, as if it were a chord of the arc. Clean and irregular in
    // eight poses, and coarse in four, automatic: 6 regions, each a face, typed as it.
    // (Noisy at the corpus's 0.2 % of the diagonal, 8 % of the roll's radius and more than a
    // facet's width, it is not found: bench/RESULTS.md section 4.)
    for (std::uint64_t offset = 0; offset < 12; ++offset)
        for (const CorpusCase& c : cad_corpus({"rolled_sheet"})) {
            if (c.variant == "noisy") continue;
            SCOPED_TRACE(c.variant + " offset " + std::to_string(offset));
            PartOptions options = c.options;
            options.seed += offset;
            if (offset >= 8) options.detail = 0.4;
            const Part part = make_part(c.part, options);
            const Outcome o = run(part, counted(0, options.seed));
            EXPECT_EQ(o.regions, 6);
            EXPECT_GE(o.accuracy, 0.999);
            EXPECT_EQ(o.two_part, 0);
            for (const ProxyResult& p : o.result.proxies) {
                const int face = o.score.face_of[p.id];
                ASSERT_GE(face, 0);
                const TrueSurface& truth = part.surfaces[face];
                EXPECT_EQ(type_name(p.type), std::string(type_name(truth.type))) << "region " << p.id;
                if (truth.type == QuadricType::cylinder) EXPECT_NEAR(p.shape.radius, truth.radius, 0.01 * truth.radius);
            }
        }
}

TEST(CadExtraction, ASideOfTwoTrianglesIsNotMergedAwayWithTheCoarseCornersBesideIt) {
    // A plate's sides are two long triangles each between rounded corners of 7 facets (the
    // rounded plate at detail 0.6, beside a slab that makes it small against the whole, as a
    // pocket is in trimesh's featuretype.STL). Growing, a side's region takes the first
    // facet column of a corner; its plane then holds it only roughly, and as a handful of
    // four faces it was merged at least cost into the corner, and on into the next side:
    // one region held two sides and three corners (11 regions of 16). A handful most of
    // whose area is an exact plane of two faces or more is now that plane's. Six poses,
    // automatically: no region holds faces of two true planes. A corner that went to the side
    // beside it: the next test.
    for (std::uint64_t pose = 0; pose < 6; ++pose) {
        SCOPED_TRACE("pose " + std::to_string(pose));
        PartOptions options;
        options.random_pose = true, options.seed = 31 + pose, options.detail = 0.6;
        const Part part = make_part("rounded_plate", options);
        const Outcome o = run(part, counted(0, options.seed));
        const FacesHeld planes_in = faces_held(part, o.result.face_labels, [&](int face) {
            return part.surfaces[face].type == QuadricType::plane;
        });
        for (const auto& [region, planes] : planes_in) EXPECT_EQ(planes.size(), 1u) << "region " << region;
        EXPECT_GE(o.regions, 13);
    }
}

TEST(CadExtraction, AWallAndTheSmallLedgeBesideItAreTwoPlanes) {
    // A tooth's slanted wall (four triangles, with a step of 0.01 at its top) and the ledge
    // beside it at the step's height (three triangles, 3 % of the area), stored as an export
    // stores them, to 1e-4 of a part 3 units tall. Their vertices determine their pair of
    // planes, and the ledge held too little of it to count as a second part by its area: the
    // finish merged the two as a run of exact pieces, and the region was typed a cylinder
    // 1e-4 of the size off its faces (Mendel90's toothed y-belt clip). Twelve poses, each
    // length within 10 %: two regions, the wall and the ledge, each a plane.
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> jitter(0.9, 1.1), turn(0, 2 * M_PI), shift(-5, 5);
    for (int pose = 0; pose < 12; ++pose) {
        SCOPED_TRACE("pose " + std::to_string(pose));
        const double a = 0.555 * jitter(rng), b = 1.676 * jitter(rng), h = 2.79 * jitter(rng), step = 0.01;
        const double angle = turn(rng);
        const Vec3 along(std::cos(angle), std::sin(angle), 0), out(-std::sin(angle), std::cos(angle), 0);
        const Vec3 origin(shift(rng), shift(rng), 0);
        auto stored = [](const Vec3& p) { return Vec3(p.unaryExpr([](double x) { return std::round(x * 1e4) / 1e4; })); };
        auto wall = [&](double s, double z) { return stored(origin + s * along + Vec3(0, 0, z)); };
        auto ledge = [&](double s, double t) { return stored(origin + s * along + t * out + Vec3(0, 0, h)); };
        const Vec3 p1 = ledge(-0.328 * jitter(rng), 0.470 * jitter(rng)), p2 = ledge(-0.346 * jitter(rng), 0.434 * jitter(rng)),
                   p3 = ledge(0.573 * jitter(rng), 0.037 * jitter(rng)), c0 = wall(0, h), ca = wall(a, h);
        const std::vector<std::array<Vec3, 3>> triangles = {
            {ca, wall(0, 0), c0}, {wall(b, h + step), ca, wall(a, h + step)}, {wall(b, 0), wall(0, 0), ca},
            {wall(b, 0), ca, wall(b, h + step)}, {p1, c0, p2}, {p1, p3, c0}, {p3, ca, c0}};
        const Eigen::Matrix3d rotation = test::random_rotation(rng);
        const Vec3 translation(shift(rng), shift(rng), shift(rng));
        PolygonSoup soup;
        for (const auto& t : triangles) {
            const int first = static_cast<int>(soup.positions.size());
            for (const Vec3& p : t) soup.positions.push_back(rotation * p + translation);
            const int polygon[3] = {first, first + 1, first + 2};
            soup.add_polygon(polygon, 3);
        }
        const Mesh mesh = build_mesh(soup);
        ASSERT_EQ(mesh.face_count(), 7u);
        const Result r = test::approximate(mesh, counted(0));
        ASSERT_EQ(r.proxies.size(), 2u);
        const std::vector<int>& l = r.face_labels;
        for (int f : {1, 2, 3}) EXPECT_EQ(l[f], l[0]);
        for (int f : {5, 6}) EXPECT_EQ(l[f], l[4]);
        EXPECT_NE(l[0], l[4]);
        for (const ProxyResult& p : r.proxies) EXPECT_EQ(p.type, QuadricType::plane) << "region " << p.id;
    }
}

TEST(CadExtraction, ACornersFacetsAndTheSideTangentToItAreTwoRegions) {
    // The same plates: a side (two long triangles) and the corner it runs into at a tangent
    // (7 facets) ended one region, typed a quadric that holds neither. The bends between a
    // corner's facets give its radius; the side's bend into it gives one as many times larger
    // as the side is wider than a facet: no facet of that corner, it leaves (off_the_arc).
    // Six poses, automatically: before, every pose had two regions holding a side's
    // triangles and most of a corner's (14 regions of 16); now four poses have none (16
    // regions, accuracy 1), and two keep one such region (17).
    int both = 0;
    for (std::uint64_t pose = 0; pose < 6; ++pose) {
        PartOptions options;
        options.random_pose = true, options.seed = 31 + pose, options.detail = 0.6;
        const Part part = make_part("rounded_plate", options);
        const Outcome o = run(part, counted(0, options.seed));
        std::map<int, int> triangles;
        for (int face : part.face) ++triangles[face];
        for (const auto& [region, held] : faces_held(part, o.result.face_labels)) {
            bool side = false, corner = false;
            for (const auto& [face, n] : held) {
                const QuadricType type = part.surfaces[face].type;
                side = side || (type == QuadricType::plane && triangles[face] == 2);
                corner = corner || (type == QuadricType::cylinder && 2 * n > triangles[face]);
            }
            both += side && corner;
        }
        EXPECT_GE(o.accuracy, 0.999) << "pose " << pose;
        EXPECT_EQ(o.two_part, 0) << "pose " << pose;
    }
    EXPECT_LE(both, 2);
}

TEST(CadExtraction, PlanesBendingBelowTheCreaseAngleUnderNoiseAreRegionsOfTheirOwn) {
    // An octagonal prism's sides bend by 45°, below the crease angle: under noise one quadric
    // (a hyperboloid, an elliptic cone) held two sides within their noise, and the run stopped
    // explained with 7 to 10 regions, at its count of 11 too (accuracy 0.79 to 0.95, mean
    // 0.85 over these draws). Their normals bunch in two groups with a gap between, as no
    // curved surface's do: two planes. Eight noise draws and poses, at the count and
    // automatically.
    double sum = 0;
    int runs = 0;
    for (std::uint64_t draw = 0; draw < 8; ++draw) {
        PartOptions options;
        options.noise = 0.002, options.random_pose = true, options.seed = 101 + draw;
        const Part part = make_part("octagon_bore", options);
        for (int proxies : {11, 0}) {
            SCOPED_TRACE("draw " + std::to_string(draw) + ", " + std::to_string(proxies) + " proxies");
            const Outcome o = run(part, counted(proxies));
            EXPECT_GE(o.accuracy, 0.94);
            EXPECT_EQ(o.two_part, 0);
            sum += o.accuracy, ++runs;
        }
    }
    EXPECT_GE(sum / runs, 0.99);
}

TEST(CadExtraction, UnderNoiseAStepsEndSidesAreFacesOfTheirOwn) {
    // The step's end sides are two to six triangles each, creased all round at 90°: too few
    // faces to tell a quadric, so under noise the finish merged each into the top or the
    // bottom at least cost, the union's quadric turning through the creases within the noise
    // (automatically 4 to 6 regions of 8, accuracy 0.75 to 0.93; at the count 0.84 to 0.87,
    // no insertion going to them). A chart of two faces or more is now a face of its own
    // when it is twenty times as wide as its noise; along a noisy edge the filtered normals
    // crease strips 1.5 to 5 times the noise wide, which stay mergeable (the plate assembly
    // below).
    for (const auto& [noise, detail] : {std::pair{0.001, 1.0}, {0.001, 1.5}, {0.002, 1.0}}) {
        CorpusCase c = corpus_case("stepped_block", "noisy", detail);
        c.options.noise = noise;
        const Part part = make_part(c.part, c.options);
        SCOPED_TRACE("noise " + std::to_string(noise) + ", detail " + std::to_string(detail));
        const Outcome automatic = run(part, counted(0, c.options.seed));
        EXPECT_GE(automatic.accuracy, 0.98);
        EXPECT_EQ(automatic.two_part, 0);
        EXPECT_GE(run(part, counted(8, c.options.seed)).accuracy, 0.98);
    }
}

TEST(CadExtraction, UnderNoiseAHandfulsUnionCostCountsInTheFinishsRoom) {
    // Under noise handfuls merge one at a time, each judged by how far its Lloyd stage takes
    // the energy, all of them together within nine times the energy the finish began at.
    // What a union itself cost was outside that room, so any handful merged whatever it
    // cost: the coarse stepped block (detail 0.25, σ 0.1 %) ended automatically with the
    // step's two walls and the chamfer between them one cylinder, 2.6 % of its size off
    // them, and its right end in the top's region (5 regions of 8, accuracy 0.876; at detail
    // 0.6, 6 regions, 0.933). The cost counts now.
    for (double detail : {0.25, 0.6}) {
        CorpusCase c = corpus_case("stepped_block", "noisy", detail);
        c.options.noise = 0.001;
        const Part part = make_part(c.part, c.options);
        SCOPED_TRACE("detail " + std::to_string(detail));
        const Outcome automatic = run(part, counted(0, c.options.seed));
        EXPECT_GE(automatic.accuracy, 0.98);
        EXPECT_GE(automatic.regions, 7);
        EXPECT_EQ(automatic.two_part, 0);
    }
}

TEST(CadExtraction, UnderNoiseOnAFineTessellationGrowthEndsOnceNoMoreChartsAreFound) {
    // Meshed finely against their noise, the filtered normals crease bumps of ten faces and
    // more all round, and a few of them miss the plane below by more than chart_factor
    // times their own noise. Growth went on while any chart was misfit, to 183 regions on
    // the pencil's 3 faces (accuracy 0.39) and to 562 on the thin plate's 6 (0.06).
    for (const auto& [name, noise, detail] : {std::tuple{"pencil", 0.001, 3.0}, {"thin_plate", 0.002, 1.5}}) {
        CorpusCase c = corpus_case(name, "noisy", detail);
        c.options.noise = noise;
        const Part part = make_part(c.part, c.options);
        SCOPED_TRACE(name);
        const Outcome automatic = run(part, counted(0, c.options.seed));
        const int faces = static_cast<int>(part.surfaces.size());
        EXPECT_GE(automatic.accuracy, 0.98);
        EXPECT_LE(automatic.regions, 3 * faces);
        EXPECT_EQ(automatic.two_part, 0);
    }
}

TEST(CadExtraction, UnderNoiseAChamferStaysOnePlaneAtTheStop) {
    // Under noise a flat chamfer's general quadric can be two planes or two branches of a
    // hyperbolic cylinder within the noise, and the stop's validity splits cut along them:
    // the chamfered box at detail 1, σ 0.2 %, ended with pieces of 1 to 7 triangles inside
    // its chamfers and faces (36 regions for its 26 faces, accuracy 0.967). A region of a
    // handful of triangles must now be a whole face: one of the box's corners, a triangle.
    CorpusCase c = corpus_case("chamfered_box", "noisy", 1);
    c.options.noise = 0.002;
    const Part part = make_part(c.part, c.options);
    const Outcome automatic = run(part, counted(0, c.options.seed));
    std::map<int, int> triangles;  // true face → its triangles
    for (int face : part.face) ++triangles[face];
    const FacesHeld held = faces_held(part, automatic.result.face_labels);
    int handfuls = 0;
    for (const auto& [region, faces] : held) {
        int size = 0;
        for (const auto& [face, n] : faces) size += n;
        if (size >= 10) continue;
        SCOPED_TRACE("region " + std::to_string(region));
        ++handfuls;
        ASSERT_EQ(faces.size(), 1u);
        EXPECT_EQ(faces.begin()->second, triangles[faces.begin()->first]);
    }
    EXPECT_EQ(handfuls, 8);  // the corners
    EXPECT_GE(automatic.accuracy, 0.975);
    EXPECT_EQ(automatic.two_part, 0);
}

TEST(CadExtraction, UnderNoiseASlabBesideASmallPartKeepsItsFaces) {
    // The noise (σ 0.1 % of the whole's diagonal) is of the small rounded plate's facets'
    // own size, and the normal filter averaged every face over patches as wide as the
    // median face needs, the slab's too: its top, bottom and sides one chart, fitted as one
    // elliptic cylinder, and the automatic count stopped at 3 regions, accuracy 0.455.
    // Coarser, its faces too small for a noise of their own, the slab took the plate's,
    // read across creases the noise garbles (0.425). At detail 0.4 and σ 0.2 % its sides,
    // two thin triangles each, took the normals of patches on its top and bottom: one
    // chart, one region (0.4245).
    for (const auto [detail, noise] :
         {std::pair{0.4, 0.001}, {0.4, 0.002}, {0.6, 0.001}, {0.6, 0.002}, {1.0, 0.001}, {1.0, 0.002}}) {
        SCOPED_TRACE("detail " + std::to_string(detail) + ", noise " + std::to_string(noise));
        CorpusCase c = corpus_case("rounded_plate", "noisy", detail);
        c.options.noise = noise;
        const Part part = make_part(c.part, c.options);
        const Outcome automatic = run(part, counted(0, c.options.seed));
        EXPECT_GE(automatic.accuracy, 0.95);
        EXPECT_EQ(automatic.two_part, 0);
        // The slab's six faces (the last six: its top, bottom and four sides) are each a
        // region's own: no region holds triangles of two of them.
        const int first_slab_face = static_cast<int>(part.surfaces.size()) - 6;
        const FacesHeld slab_faces =
            faces_held(part, automatic.result.face_labels, [&](int face) { return face >= first_slab_face; });
        EXPECT_EQ(slab_faces.size(), 6u);
        for (const auto& [region, faces] : slab_faces) EXPECT_EQ(faces.size(), 1u) << "region " << region;
    }
}

TEST(CadExtraction, UnderNoiseAFaceTooSmallForANoiseOfItsOwnIsBoundedByItsPlane) {
    // The coarse countersunk plate under noise (σ 0.2 % of its diagonal): a face and the four
    // sides, four triangles each, have too few vertices with two rings of their own, and took
    // the whole mesh's noise, read mostly on the chart of the other face, the countersink and
    // the bore, whose vertices all lie beside their bends: 2.6 σ. The automatic count stopped
    // at two regions, a face with its four sides one ellipsoid (accuracy 0.770). Their faces
    // are far wider than the noise, so no noise made those charts, and each chart's noise is
    // bounded by what its own plane leaves.
    for (const double detail : {0.25, 0.4}) {
        SCOPED_TRACE("detail " + std::to_string(detail));
        CorpusCase c = corpus_case("countersunk_plate", "noisy", detail);
        c.options.noise = 0.002;
        const Part part = make_part(c.part, c.options);
        const Outcome automatic = run(part, counted(0, c.options.seed));
        EXPECT_GE(automatic.accuracy, 0.85);
        EXPECT_GE(automatic.result.proxies.size(), 4u);
        EXPECT_EQ(automatic.two_part, 0);
    }
}

TEST(CadExtraction, UnderNoiseAFaceIsNoFlatConeWhoseNappesStraddleIt) {
    // Under noise the octagon bore's face and the stepped block's bottom each came out a cone
    // of half-angle 89.8–89.9° whose apex lay beside the face (within twice the region's
    // radius of its centroid, where a region was taken to run through the apex), at half the
    // plane's RMS: the two nappes, apart by less than the noise, each held the vertices on
    // its side. A cone face lies on one nappe.
    struct Case {
        std::string part;
        double detail, noise;
    };
    for (const Case& k : {Case{"octagon_bore", 0.6, 0.001}, Case{"stepped_block", 1.0, 0.002}}) {
        SCOPED_TRACE(k.part);
        CorpusCase c = corpus_case(k.part, "noisy", k.detail);
        c.options.noise = k.noise;
        const Part part = make_part(c.part, c.options);
        const Outcome o = run(part, counted(static_cast<int>(part.surfaces.size()), c.options.seed));
        int planes = 0;
        for (const ProxyResult& p : o.result.proxies) {
            const int face = o.score.face_of[p.id];
            if (face < 0 || !o.score.clean_match[p.id] || part.surfaces[face].type != QuadricType::plane) continue;
            ++planes;
            EXPECT_EQ(p.type, QuadricType::plane) << "region " << p.id << " on face " << face << ": " << type_name(p.type);
        }
        EXPECT_GE(planes, 6);
    }
}

TEST(CadExtraction, UnderNoiseAThinPlatesRimsArePlanesByTheirEdges) {
    // A rim 0.5 % of the plate's size tall is one facet row: two rows of vertices, which
    // noise moves along normals tilted by the plate's faces, so that each vertex's move
    // across the rim goes with its move along it and the rows fold like a cylinder's
    // section. All four rims came out cylinders (σ 0.1 %); the rims' vertical edges lie on
    // the plane, and the midpoints judge among the elementary types.
    CorpusCase c = corpus_case("thin_plate", "noisy", 1.0);
    c.options.noise = 0.001;
    const Part part = make_part(c.part, c.options);
    const Outcome o = run(part, counted(static_cast<int>(part.surfaces.size()), c.options.seed));
    int planes = 0;
    for (const ProxyResult& p : o.result.proxies) {
        const int face = o.score.face_of[p.id];
        if (face >= 0 && o.score.clean_match[p.id] && p.type == QuadricType::plane) ++planes;
    }
    EXPECT_GE(planes, 5);  // the two faces and at least three of the four rims
    EXPECT_GE(o.accuracy, 0.99);
}

TEST(CadExtraction, EveryRegionOfANoisyPlateHasItsRmsMeasured) {
    // The measurement's control variate takes the whole surface's β; on a rim's few samples
    // it took the mean square below zero, and regions were reported with an RMS of 0 beside
    // a Hausdorff distance of up to 2e-3 (four of the fourteen here, and a fifth above the
    // largest distance of its samples).
    CorpusCase c = corpus_case("thin_plate", "noisy", 1.5);
    c.options.noise = 0.002;
    const Part part = make_part(c.part, c.options);
    const Result r = test::approximate(part.mesh, test::with_proxies(0, c.options.seed));
    ASSERT_TRUE(r.metrics);
    int unsampled = 0;
    for (int i = 0; i < static_cast<int>(r.proxies.size()); ++i) {
        SCOPED_TRACE("region " + std::to_string(i));
        const nlohmann::json reported = proxy_report(r, i).at("metrics");
        EXPECT_EQ(reported.at("samples").get<long>(), r.metrics->region_samples[i]);
        if (r.metrics->region_samples[i] == 0) {
            // Reported as unmeasured, not as an RMS of 0 (one of the fourteen here).
            ++unsampled;
            EXPECT_TRUE(reported.at("rms").is_null());
            EXPECT_TRUE(reported.at("hausdorff").is_null());
            continue;
        }
        EXPECT_GT(r.metrics->region_rms[i], 0);
        EXPECT_LE(r.metrics->region_rms[i], r.metrics->region_hausdorff[i]);
        EXPECT_DOUBLE_EQ(reported.at("rms").get<double>(), r.metrics->region_rms[i]);
    }
    EXPECT_GT(unsampled, 0);  // the case this test is for
}

TEST(CadExtractionHeavy, UnderNoiseStripsCreasedAlongAnEdgeAreNoFacesOfTheirOwn) {
    // Along the noisy plates' edges the filtered normals crease strips of two to ten
    // triangles all round, 1.5 to 5 times the noise wide: counted as faces of their own, as
    // the step's end sides are (above), they grew the assembly to 45 regions for its 39 faces
    // (accuracy 0.90). The rims' pieces, 10 to 13 times, are no faces either (at the seed of
    // UnderNoiseAHandOverDoesNotCarryARegionAcrossACrease they left a large face in two).
    const CorpusCase c = corpus_case("plate_assembly", "noisy");
    const Part part = make_part(c.part, c.options);
    const Outcome automatic = run(part, counted(0, c.options.seed));
    EXPECT_LE(automatic.regions, static_cast<int>(1.15 * part.surfaces.size()));
    EXPECT_GE(automatic.accuracy, 0.95);
}

TEST(CadExtraction, ACoarseTubesEndsAreChartsOfTheirOwn) {
    // A tube meshed with 16 facets round: each end is one row of triangles a wall thick,
    // too narrow for the noise the facets' curvature reads as, and took the chart of the
    // cylinder beside it. An exact tessellation has no noise: the ends are charts of their own,
    // and at its count and automatically the tube is its four faces.
    for (const CorpusCase& c : cad_corpus({"tube"})) {
        if (c.variant == "noisy") continue;
        SCOPED_TRACE(c.variant);
        PartOptions options = c.options;
        options.detail = 0.25;
        const Part part = make_part(c.part, options);
        for (int proxies : {4, 0}) {
            const Outcome o = run(part, counted(proxies, c.options.seed));
            EXPECT_EQ(o.regions, 4);
            EXPECT_GE(o.accuracy, 0.999) << proxies << " proxies";
        }
    }
}

TEST(CadExtraction, ThinPlateFacesAreTwoPlanesAndToleranceRunsAreValid) {
    // A plate 0.5 % of its size thick: its two sides are two plane regions facing away
    // from each other, at the automatic count and under a tolerance alike.
    PartOptions pose;
    pose.random_pose = true, pose.seed = 7;
    const Part plate = make_part("thin_plate", pose);
    for (const double tolerance : {0.0, 0.002, 0.005}) {
        SCOPED_TRACE(tolerance);
        Options o = counted(0);
        o.lloyd.tolerance = tolerance;
        const Result r = test::approximate(plate.mesh, o);
        EXPECT_EQ(two_part_regions(plate.mesh, r), 0);
        const PartitionScore score = score_partition(plate, r.face_labels, static_cast<int>(r.proxies.size()));
        std::set<int> sides;
        for (const ProxyResult& p : r.proxies)
            if (score.face_of[p.id] >= 0 && plate.surfaces[score.face_of[p.id]].type == QuadricType::plane &&
                p.area > 1.0 && p.type == QuadricType::plane)
                sides.insert(p.id);
        EXPECT_EQ(sides.size(), 2u);
        EXPECT_GE(score.accuracy, 0.97);
    }
    for (const std::string name : {"box_boss_hole", "flange"}) {
        Options o = counted(0);
        o.lloyd.tolerance = 0.002;
        const Part part = make_part(name, pose);
        const Result r = test::approximate(part.mesh, o);
        EXPECT_EQ(two_part_regions(part.mesh, r), 0) << name;
        EXPECT_GE(score_partition(part, r.face_labels, static_cast<int>(r.proxies.size())).accuracy, 0.95) << name;
    }
}

TEST(CadExtraction, PiecesOfOneNoisyFaceMergeAtACount) {
    // The noisy thin plate at its true count: its sides are strips a few facets wide under
    // noise of 40 % of the thickness, and one proxy went to a second piece of a large face
    // (accuracy 0.956). Two pieces whose union fits as well as they do apart, within the
    // noise of both, are one surface at a count too: every large face is one region.
    const auto [part, o] = corpus_case_at_true_count("thin_plate", "noisy");
    const WholeFaces faces = whole_large_faces(part, o.result.face_labels, 0.25, 0.99);  // not the sides
    EXPECT_EQ(faces.large, 2);
    EXPECT_EQ(faces.whole, faces.large);
    EXPECT_GE(o.accuracy, 0.97);
}

TEST(CadExtractionHeavy, PiecesOfANoisyPlaneMergeAtACountThoughEachBendsToItsNoise) {
    // The noisy plate assembly at its true count of 39: its rims, a few σ tall, hold no proxy
    // that pays, so Lloyd spends the spare proxies on pieces of the large faces. Each piece's
    // quadric bends to its own noise, up to half below the plane's error, so the pieces did
    // not fit "as well as apart" and stayed: one of the six large faces whole at each of these
    // seeds (accuracy 0.610 and 0.601). A plane holds their union within their noise.
    for (std::uint64_t offset : {0, 5}) {
        const auto [part, o] = corpus_case_at_true_count("plate_assembly", "noisy", offset);
        EXPECT_GE(o.accuracy, 0.85) << "seed offset " << offset;
        EXPECT_EQ(o.two_part, 0) << "seed offset " << offset;
        const WholeFaces faces = whole_large_faces(part, o.result.face_labels);
        EXPECT_EQ(faces.large, 6);
        EXPECT_GE(faces.whole, 5) << "seed offset " << offset;
    }
}

TEST(CadExtractionHeavy, UnderNoiseAHandOverDoesNotCarryARegionAcrossACrease) {
    // The seam step's hand-over (a region's far half made a plane, local Lloyd settling the
    // rest) is for tangent seams; local Lloyd could carry the other region across a crease,
    // over a second large face of the noisy plate assembly (2 242 faces to 3 682), and such a
    // trial, chosen, left a large face in two regions (automatic at this seed: 0.888, five of
    // the six large faces whole). What the run ends with at one seed is one draw of the
    // finish's merges (since growth under noise stops once no more charts are found, this
    // seed's ends at 0.874 with a large face in two pieces, while seed offsets 0 to 7 average
    // 0.932 as before): the test asks what the hand-over promises, that no region holds a
    // sizeable part of two large faces.
    for (const CorpusCase& c : cad_corpus({"plate_assembly"})) {
        if (c.variant != "noisy") continue;
        const Part part = make_part(c.part, c.options);
        const Outcome automatic = run(part, counted(0, c.options.seed + 3));
        EXPECT_GE(automatic.accuracy, 0.85);
        EXPECT_EQ(automatic.two_part, 0);
        EXPECT_EQ(regions_over_two_large_faces(part, automatic.result.face_labels), 0);
    }
}

TEST(CadExtraction, UnderMoreNoiseThanTheCorpussAFlangeIsStillItsFacesAutomatically) {
    // The corpus's noisy flange with half as much noise again (σ 0.3 % of the diagonal):
    // Taubin's fit to two pieces of a noisy plane is a pair of planes, a quarter to a third
    // below the plane's error, refused for its two parts, so the pieces never merged (12 to
    // 14 regions, accuracy 0.73 to 0.89 at each seed). Under noise a pair one plane of which
    // holds the union is that plane.
    for (const CorpusCase& c : cad_corpus({"flange"})) {
        if (c.variant != "noisy") continue;
        PartOptions options = c.options;
        options.noise = 1.5 * c.options.noise;
        const Part part = make_part(c.part, options);
        for (std::uint64_t offset : {0, 1, 2}) {
            const Outcome automatic = run(part, counted(0, c.options.seed + offset));
            EXPECT_EQ(automatic.regions, 10) << "seed offset " << offset;
            EXPECT_GE(automatic.accuracy, 0.99) << "seed offset " << offset;
            EXPECT_EQ(automatic.two_part, 0) << "seed offset " << offset;
        }
    }
}

TEST(CadExtraction, UnderTwiceTheCorpussNoiseTheFacesFoundKeepTheirTypes) {
    // σ 0.4 % of the diagonal: with thousands of vertices, model selection resolved quadrics
    // departing from a face's plane or cylinder by a fraction of the noise (30 of the 33
    // patches matched to a face typed right: planes as hyperboloids or parabolic cylinders,
    // cylinders as ellipsoids). A quadric within the region's scatter of an elementary type
    // is that type.
    std::pair<int, int> typed;
    for (const CorpusCase& c : cad_corpus()) {
        if (c.variant != "noisy") continue;
        PartOptions options = c.options;
        options.noise = 2 * c.options.noise;
        const Part part = make_part(c.part, options);
        const Outcome o = run(part, counted(static_cast<int>(part.surfaces.size()), c.options.seed));
        for (const ProxyResult& p : o.result.proxies) {
            const int face = o.score.face_of[p.id];
            if (face < 0 || !o.score.clean_match[p.id]) continue;
            ++typed.second;
            typed.first += p.type == part.surfaces[face].type;
            EXPECT_STREQ(type_name(p.type), type_name(part.surfaces[face].type)) << c.part << " region " << p.id;
        }
    }
    EXPECT_GE(typed.second, 30);  // of the corpus's 51 faces
}

TEST(CadExtraction, ARoundedBlockWithoutACreaseIsItsTwentySixFaces) {
    // Beyond the corpus: six planes, twelve quarter cylinders and eight sphere octants, every
    // edge tangent-continuous, so no chart separates any two faces and fitting alone must.
    for (const CorpusCase& c : cad_corpus({"rounded_block"})) {
        if (c.variant == "noisy") continue;  // NoisyFilletsStayApartFromTheirPlanesAtACount
        const Part part = make_part(c.part, c.options);
        const int faces = static_cast<int>(part.surfaces.size());
        const Outcome at_count = run(part, counted(faces, c.options.seed));
        EXPECT_GE(at_count.accuracy, 0.97) << c.variant;
        EXPECT_EQ(at_count.two_part, 0) << c.variant;
        const Outcome automatic = run(part, counted(0, c.options.seed));
        EXPECT_NEAR(automatic.regions, faces, 0.15 * faces) << c.variant;
        EXPECT_GE(automatic.accuracy, 0.95) << c.variant;
    }
}

TEST(CadExtraction, APlateAssemblysRoundedRimsAreFoundAutomatically) {
    // Beyond the corpus: three plates 3 % of their length thick, whose rims (four sides and
    // four corner cylinders, one facet tall) form one chart each. The regions of the faces
    // above and below shared each rim, facet by facet, and a single quadric fits a rim as
    // badly, so the chart's own fit did not mark it missed: 18 regions of 39 (0.946). A
    // chart whose faces turn away from the surfaces of the regions holding it now is.
    // Then a side and the facets of the corner beside it shared a region whose error the
    // free-form floor (`precision`) explained: 29 and 35 regions (0.989, 0.994). On an
    // exact export that floor is the stored precision: the corpus's bar (count within 15 %).
    // A side that kept a facet or two of the corner was typed a cone: those facets now go to
    // the corner at the stop (clean: 8 of the 22 regions on a plane face typed otherwise, now 1).
    for (const CorpusCase& c : cad_corpus({"plate_assembly"})) {
        if (c.variant == "noisy") continue;
        const Part part = make_part(c.part, c.options);
        const int faces = static_cast<int>(part.surfaces.size());
        const Outcome automatic = run(part, counted(0, c.options.seed));
        EXPECT_NEAR(automatic.regions, faces, 0.15 * faces) << c.variant;
        EXPECT_GE(automatic.accuracy, 0.99) << c.variant;
        EXPECT_EQ(automatic.two_part, 0) << c.variant;
        int on_planes = 0, not_planes = 0;
        for (const ProxyResult& p : automatic.result.proxies) {
            const int face = automatic.score.face_of[p.id];
            if (face < 0 || part.surfaces[face].type != QuadricType::plane) continue;
            ++on_planes;
            not_planes += p.type != QuadricType::plane;
        }
        if (c.variant == "clean") EXPECT_LE(not_planes, 0.15 * on_planes);
    }
}

TEST(CadExtraction, AutomaticallyTheHandfulsMergedOneByOneDoNotCompoundTheirDrift) {
    // The plate assembly coarsely exported (detail 0.25): its finish merges handfuls of faces
    // one by one, and each was let settle up to ten times the energy before it, so the room
    // compounded and the finish merged on: 30 and 27 regions of 39 (0.983, 0.986 at seed
    // offsets 0 and 1). All the handfuls' stages together now have that room once, counted
    // from where the finish began.
    CorpusCase c = corpus_case("plate_assembly", "clean", 0.25);
    c.options.random_pose = true;
    const Part part = make_part(c.part, c.options);
    const int faces = static_cast<int>(part.surfaces.size());
    for (std::uint64_t offset : {0, 1}) {
        SCOPED_TRACE("seed offset " + std::to_string(offset));
        const Outcome automatic = run(part, counted(0, c.options.seed + offset));
        EXPECT_NEAR(automatic.regions, faces, 0.15 * faces);
        EXPECT_GE(automatic.accuracy, 0.987);
        EXPECT_EQ(automatic.two_part, 0);
    }
}

TEST(CadExtraction, OnACleanMeshNoMergeIsExcusedByTheDriftOfAStageWithoutIt) {
    // The stepped shaft exported finely (detail 3, 53K triangles) and irregularly meshed:
    // clean, no noise. Two merges of its finish (two pairs at once, then one) left thousands
    // of times their margins more error unexplained than before, and each stood against a
    // Lloyd stage from the same partition without it, which had drifted up as far: the
    // finish ended at 6 regions of 7, the spherical end and the cylinder beside it one
    // ellipsoid (accuracy 0.905). Only noise excuses such a drift.
    const CorpusCase c = corpus_case("stepped_shaft", "irregular", 3);
    const Part part = make_part(c.part, c.options);
    const Outcome automatic = run(part, counted(0, c.options.seed));
    EXPECT_EQ(automatic.regions, static_cast<int>(part.surfaces.size()));
    EXPECT_GE(automatic.accuracy, 0.99);
    EXPECT_EQ(automatic.two_part, 0);
}

TEST(CadExtractionHeavy, UnderNoiseNoFlatConeHoldsBothFacesOfAPlate) {
    // Under noise a plate's two faces lie on the two nappes of a flat cone (half-angle 89.9°,
    // its apex tens of plate lengths away), which fits them as a pair of parallel planes
    // would; with its nappes not counted as parts, model selection typed such regions cones
    // and the merges took them (automatically 41 and 31 regions of 39, accuracy 0.749 and
    // 0.822 at these seeds, and up to a third of a region on the other face).
    for (const CorpusCase& c : cad_corpus({"plate_assembly"})) {
        if (c.variant != "noisy") continue;
        const Part part = make_part(c.part, c.options);
        for (std::uint64_t offset : {0, 1}) {
            const Outcome automatic = run(part, counted(0, c.options.seed + offset));
            EXPECT_GE(automatic.accuracy, 0.85) << "seed offset " << offset;
            EXPECT_EQ(automatic.two_part, 0) << "seed offset " << offset;
        }
    }
}

TEST(CadExtraction, AThinPlatesHoleIsACylinder) {
    // A hole through a plate, one facet tall: its vertices are two circles, which a
    // cylinder, a sphere and many quadrics hold exactly, and the sphere has the fewest
    // parameters. Its facets' vertical edges lie on the cylinder only.
    const Part part = make_part("plate_assembly");
    const Model model = make_model(part.mesh);
    int holes = 0;
    for (std::size_t face = 0; face < part.surfaces.size(); ++face) {
        const TrueSurface& truth = part.surfaces[face];
        if (truth.type != QuadricType::cylinder || truth.radius != 0.12) continue;
        std::vector<int> faces;
        for (std::size_t t = 0; t < part.face.size(); ++t)
            if (part.face[t] == static_cast<int>(face)) faces.push_back(static_cast<int>(t));
        const Samples s = region_samples(model, faces);
        const ModelChoice choice = select_model(s, fit_region(moments_of(model, faces)).quadric);
        EXPECT_EQ(choice.chosen.type, QuadricType::cylinder) << "face " << face << ": " << type_name(choice.chosen.type);
        EXPECT_NEAR(choice.chosen.shape.radius * model.frame.scale, 0.12, 1e-9) << "face " << face;
        ++holes;
    }
    EXPECT_EQ(holes, 5);  // the round hole and the slots' four ends
}

TEST(CadExtraction, AHexNutsCountersinksAreConesAtItsFaceCount) {
    // Beyond the corpus: a hex nut whose bore is countersunk 45° at both ends, the cones two
    // facets tall between bends of 45° (below the crease angle: one chart holds the flat
    // annuli, both cones and the bore). At its face count, clean, in a random pose, every
    // face is found and typed.
    const CorpusCase c = cad_corpus({"hex_nut"}).front();
    ASSERT_EQ(c.variant, "clean");
    const Part part = make_part(c.part, c.options);
    const Outcome o = run(part, counted(static_cast<int>(part.surfaces.size()), c.options.seed));
    EXPECT_EQ(o.regions, 11);
    EXPECT_GE(o.accuracy, 0.999);
    int cones = 0;
    for (const ProxyResult& p : o.result.proxies) {
        if (p.type == QuadricType::cylinder) EXPECT_NEAR(p.shape.radius, 0.25, 1e-6);
        if (p.type != QuadricType::cone) continue;
        ++cones;
        EXPECT_NEAR(p.shape.half_angle, std::atan(1.0), 1e-6);
    }
    EXPECT_EQ(cones, 2);
}

TEST(CadExtraction, APencilAtItsFaceCountIsItsFaces) {
    // Beyond the corpus: a cylinder sharpened to a cone's apex, irregularly meshed; the bend
    // between them (27°) is below the crease angle, so one chart holds both. Grown to its 3
    // proxies, Lloyd settled with an ellipsoid over the cylinder and half the cone, and the
    // teleport to the worst face did not pay; one more, to the faces turned away from their
    // region's surface, finds the cone.
    for (const CorpusCase& c : cad_corpus({"pencil"})) {
        if (c.variant != "irregular") continue;
        const Part part = make_part(c.part, c.options);
        const Outcome o = run(part, counted(3, c.options.seed));
        EXPECT_GE(o.accuracy, 0.99);
        std::set<QuadricType> types;
        for (const ProxyResult& p : o.result.proxies) {
            types.insert(p.type);
            if (p.type == QuadricType::cylinder) EXPECT_NEAR(p.shape.radius, 0.3, 1e-6);
            if (p.type == QuadricType::cone) EXPECT_NEAR(p.shape.half_angle, std::atan(0.5), 1e-6);
        }
        EXPECT_EQ(types, (std::set<QuadricType>{QuadricType::plane, QuadricType::cylinder, QuadricType::cone}));
    }
}

TEST(CadExtraction, CoarseIrregularPartsAtTheirCountAreTheirFaces) {
    // Coarse exports (detail 0.4, a few hundred triangles), irregularly meshed, at their
    // true counts. Grown to the count, a new proxy starts as the plane of its seed face and
    // holds one facet column exactly, while one general quadric spans two true faces. No
    // teleport moved it, but the automatic count found every face. At a fixed count the run now
    // grows past it, as the automatic count does, and merges back, keeping the result only if
    // its energy is lower. Before: the domed cylinder scored 0.707, the pencil 0.757, the
    // hex nut 0.898 and the stepped shaft 0.935.
    const std::map<std::string, std::set<QuadricType>> parts = {
        {"domed_cylinder", {QuadricType::plane, QuadricType::cylinder, QuadricType::sphere}},
        {"pencil", {QuadricType::plane, QuadricType::cylinder, QuadricType::cone}},
        {"hex_nut", {QuadricType::plane, QuadricType::cylinder, QuadricType::cone}},
        {"stepped_shaft", {QuadricType::plane, QuadricType::cylinder, QuadricType::cone, QuadricType::sphere}},
    };
    for (const auto& [name, types] : parts)
        for (const CorpusCase& c : cad_corpus({name})) {
            if (c.variant != "irregular") continue;
            PartOptions coarse = c.options;
            coarse.detail = 0.4;
            const Part part = make_part(name, coarse);
            const int faces = static_cast<int>(part.surfaces.size());
            const Outcome o = run(part, counted(faces, coarse.seed));
            EXPECT_EQ(o.regions, faces) << name;
            EXPECT_GE(o.accuracy, 0.99) << name;
            EXPECT_EQ(o.two_part, 0) << name;
            std::set<QuadricType> found;
            for (const ProxyResult& p : o.result.proxies) found.insert(p.type);
            EXPECT_EQ(found, types) << name;
        }
}

TEST(CadExtraction, AHexNutsCountersinksAreFoundAutomatically) {
    // The four bends and the rings beside them hold 63 % of the nut's chart: its noise
    // estimate was a bend's, 3.3e-3 of the size on an exact mesh, and a cone with two rows of
    // the bore passed as one explained hyperboloid (clean automatic 0.977; irregular at the
    // count stopped at 10 regions, 0.861). The chart's noise is now measured away from bends.
    for (const CorpusCase& c : cad_corpus({"hex_nut"})) {
        if (c.variant == "noisy") continue;
        const Part part = make_part(c.part, c.options);
        const int faces = static_cast<int>(part.surfaces.size());
        for (const int proxies : {faces, 0}) {
            const Outcome o = run(part, counted(proxies, c.options.seed));
            EXPECT_EQ(o.regions, faces) << c.variant << " at " << proxies;
            EXPECT_GE(o.accuracy, 0.999) << c.variant << " at " << proxies;
        }
    }
}

TEST(CadExtraction, ACoarseExportsChartHasNoNoiseBeyondItsFacetsSag) {
    // An exact export's chart that holds several surfaces (a cone sharpened from its
    // cylinder, a dome on its cylinder, a countersink one facet tall, each bend below the
    // crease angle) read its vertices' deviations, measured across those surfaces, as noise;
    // that noise is now no more than the largest sag of the chart's facets. Before: the
    // pencil at detail 0.25 stopped "fitted" at 2 regions (0.840), the irregular domed
    // cylinder at 0.25 at 2 (0.775), and the hex nut at 0.6, at its count, left its
    // countersinks' proxies slivers, the bore and both cones one hyperboloid (0.896).
    const struct {
        const char* name;
        const char* variant;
        double detail;
        bool automatic;
    } cases[] = {{"pencil", "clean", 0.25, true}, {"domed_cylinder", "irregular", 0.25, true}, {"hex_nut", "clean", 0.6, false}};
    for (const auto& k : cases) {
        const CorpusCase c = corpus_case(k.name, k.variant, k.detail);
        const Part part = make_part(c.part, c.options);
        const int faces = static_cast<int>(part.surfaces.size());
        const Outcome o = run(part, counted(k.automatic ? 0 : faces, c.options.seed));
        EXPECT_EQ(o.regions, faces) << k.name;
        EXPECT_GE(o.accuracy, 0.999) << k.name;
        EXPECT_EQ(o.two_part, 0) << k.name;
    }
}

TEST(CadExtraction, AnExactRegionOnTwoFacesACreaseApartIsSplitHoweverFewFacesTheSecondHas) {
    // The rounded plate at detail 0.4, at its true count: the plate's bottom (12 triangles)
    // and one of its sides (2 triangles, 90° from it) ended one region, which a pair of
    // planes held exactly; the side's two triangles were too few to count as a second part
    // at the stop, and the refit typed the region an elliptic cone (accuracy 0.969).
    for (const char* variant : {"clean", "irregular"}) {
        const CorpusCase c = corpus_case("rounded_plate", variant, 0.4);
        const Part part = make_part(c.part, c.options);
        const int faces = static_cast<int>(part.surfaces.size());
        const Outcome o = run(part, counted(faces, c.options.seed));
        EXPECT_EQ(o.regions, faces) << variant;
        EXPECT_GE(o.accuracy, 0.999) << variant;
        EXPECT_EQ(o.two_part, 0) << variant;
    }
}

TEST(CadExtraction, AChamferedBoxsStripsAndCornersAreFound) {
    // Beyond the corpus: every edge of a box chamfered 45°, the strips two facets wide
    // between bends below the crease angle (one chart), and the corners single triangles:
    // 26 planes, each a region, at the count and automatic, clean and irregular. (Under the
    // corpus's noise a quadric bends over a strip within the noise: bench/RESULTS.md §4.)
    for (const CorpusCase& c : cad_corpus({"chamfered_box"})) {
        if (c.variant == "noisy") continue;
        const Part part = make_part(c.part, c.options);
        const int faces = static_cast<int>(part.surfaces.size());
        ASSERT_EQ(faces, 26);
        for (const int proxies : {faces, 0}) {
            const Outcome o = run(part, counted(proxies, c.options.seed));
            EXPECT_EQ(o.regions, faces) << c.variant << " at " << proxies;
            EXPECT_GE(o.accuracy, 0.999) << c.variant << " at " << proxies;
            for (const ProxyResult& p : o.result.proxies)
                EXPECT_EQ(p.type, QuadricType::plane) << c.variant << " at " << proxies << ", region " << p.id;
        }
    }
}

TEST(CadExtraction, AFacetColumnBesideItsPlaneGoesBackToItsFillet) {
    // The app's own example (canonical pose, seed 1, automatic count): a plane face and the
    // first facet column of the fillet beside it lie exactly on a pair of planes, the column
    // 4 % of the region (too small to split off), so that pair kept it, and the refit typed
    // the plane a cylinder of radius 780 (type RMS 4.9e-4 of the size). The column now goes
    // back to the fillet at the stop: every region is an exact plane, cylinder or sphere.
    const Part part = make_part("rounded_block");
    const Result r = test::approximate(part.mesh, counted(0));
    EXPECT_EQ(r.proxies.size(), part.surfaces.size());
    for (const ProxyResult& p : r.proxies) {
        EXPECT_TRUE(p.type == QuadricType::plane || p.type == QuadricType::cylinder || p.type == QuadricType::sphere)
            << "region " << p.id << ": " << type_name(p.type);
        EXPECT_LT(p.type_rms, 1e-9) << "region " << p.id << ": " << type_name(p.type);
    }
}

TEST(CadExtraction, ACoarseExportsHolesAreOneRegionEach) {
    // The flange meshed as a CAD export with a coarse angular tolerance (detail 0.4, 1 056
    // triangles): its bolt holes are 12-gons whose facets bend by 14-40°. Bends beyond half
    // the crease angle counted as a chamfer's edges, so the holes had no tessellation error
    // allowed and each ended in three regions (22 in all, accuracy 0.919 automatic). Chords
    // of a polygonal arc then counted as chords: two regions per hole (16, accuracy 0.960),
    // which the finish did not merge, as each half's faces sag from the whole hole's
    // cylinder several times more than from the quadric bent to their own chords. Their
    // vertices lie on that cylinder: one region per hole.
    // Coarser still (detail 0.25, 672 triangles), each hole is one facet deep: its two
    // rings of vertices lie on every quadric of a pencil (its cylinder, the pair of planes
    // through them, hyperboloids), so they determined none, no run of its facets merged,
    // and the holes ended in pieces (19 regions, accuracy 0.974). The facets choose among
    // the pencil: one region per hole.
    PartOptions options = cad_corpus({"flange"}).front().options;  // clean
    for (double detail : {0.4, 0.25}) {
        options.detail = detail;
        const Part part = make_part("flange", options);
        const Outcome automatic = run(part, counted(0, options.seed));
        EXPECT_EQ(automatic.regions, static_cast<int>(part.surfaces.size())) << "detail " << detail;
        EXPECT_GE(automatic.accuracy, 0.99) << "detail " << detail;
        EXPECT_EQ(automatic.two_part, 0) << "detail " << detail;
        const Outcome at_count = run(part, counted(static_cast<int>(part.surfaces.size()), options.seed));
        EXPECT_GE(at_count.accuracy, 0.99) << "detail " << detail;
    }

    // The irregular L-bracket at that detail, at its true count: one general quadric took
    // a plane with the fillet's facets beside it (accuracy 0.920); the fillet's pieces now
    // join on their vertices and the plane stays a plane.
    for (const CorpusCase& c : cad_corpus({"l_bracket"})) {
        if (c.variant != "irregular") continue;
        PartOptions coarse = c.options;
        coarse.detail = 0.4;
        const Part bracket = make_part("l_bracket", coarse);
        const Outcome counted_bracket = run(bracket, counted(static_cast<int>(bracket.surfaces.size()), coarse.seed));
        EXPECT_GE(counted_bracket.accuracy, 0.99);
        EXPECT_EQ(counted_bracket.two_part, 0);
        // Automatic, the fillet's six facets ended as six exact planes (14 regions, accuracy
        // 0.956): two rows of vertices determine no quadric, so no pair of them merged. A run
        // of them does: one cylinder.
        const Outcome automatic_bracket = run(bracket, counted(0, coarse.seed));
        EXPECT_EQ(automatic_bracket.regions, static_cast<int>(bracket.surfaces.size()));
        EXPECT_GE(automatic_bracket.accuracy, 0.99);
        EXPECT_EQ(automatic_bracket.two_part, 0);
    }
}

TEST(CadExtraction, AFaceOfTwoTrianglesIsAPlaneOfItsOwn) {
    // A box exported as 12 triangles, in a random pose: each face is two triangles, fewer
    // than a quadric needs, and the finish merged every such region into a neighbour at
    // least cost, whatever the error: one cylinder (relative RMS 0.17). At the count (6),
    // its 2-face charts got no seed and the run stopped at 5 regions, two across an edge.
    // An exact plane of two triangles or more is told: its own region, its own chart.
    PolygonSoup soup;
    const Eigen::Matrix3d R = Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()).toRotationMatrix();
    for (int k = 0; k < 8; ++k) soup.positions.push_back(R * Vec3(2.0 * (k >> 2), 1.5 * ((k >> 1) & 1), k & 1) + Vec3(3, -1, 2));
    const int quads[6][4] = {{0, 1, 3, 2}, {4, 6, 7, 5}, {0, 4, 5, 1}, {2, 3, 7, 6}, {0, 2, 6, 4}, {1, 5, 7, 3}};
    for (const auto& q : quads) soup.add_polygon(q, 4);
    const Mesh box = build_mesh(soup);
    ASSERT_EQ(box.face_count(), 12u);
    for (int proxies : {0, 6}) {
        SCOPED_TRACE(proxies);
        const Result r = test::approximate(box, counted(proxies));
        ASSERT_EQ(r.proxies.size(), 6u);
        for (const ProxyResult& p : r.proxies) EXPECT_EQ(p.type, QuadricType::plane);
        // Each region is the two triangles of one face (the fan of quad q: 2q, 2q + 1).
        for (int q = 0; q < 6; ++q) EXPECT_EQ(r.face_labels[2 * q], r.face_labels[2 * q + 1]);
        EXPECT_EQ(std::set<int>(r.face_labels.begin(), r.face_labels.end()).size(), 6u);
    }
}

TEST(CadExtraction, ARibsTriangularSideIsAFaceOfItsOwn) {
    // A disc plate (a coarse n-gon prism) with a rib across its top: the rib's sides are one
    // triangle each, creased all round, as OpenSCAD exports them (Mendel90's fan bracket). A
    // chart of one face was never told, and a region of one face, its noise borrowed from
    // the prism's sag, was a handful: the finish merged a side, or both, across its 90°
    // creases into the disc's top, in four of these eight shapes.
    struct Shape {
        int n;
        double half_width, height;
    };
    for (const Shape& shape : {Shape{64, 0.5, 24}, Shape{64, 1.5, 8}, Shape{32, 1.5, 10}, Shape{96, 0.5, 16},
                               Shape{48, 1, 12}, Shape{40, 2, 18}, Shape{80, 1, 20}, Shape{32, 1, 16}}) {
        SCOPED_TRACE(testing::Message() << shape.n << "-gon, rib " << shape.half_width << " x " << shape.height);
        const Eigen::Matrix3d R = Eigen::AngleAxisd(0.9, Vec3(2, -1, 3).normalized()).toRotationMatrix();
        const double radius = 10, length = 6, w = shape.half_width;
        PolygonSoup soup;
        auto vertex = [&](double x, double y, double z) {
            soup.positions.push_back(R * Vec3(x, y, z) + Vec3(1, 2, -3));
            return static_cast<int>(soup.positions.size()) - 1;
        };
        auto triangle = [&](int a, int b, int c) {
            const int t[3] = {a, b, c};
            soup.add_polygon(t, 3);
        };
        std::vector<int> top, bottom;
        for (int k = 0; k < shape.n; ++k) {
            const double a = 2 * M_PI * k / shape.n;
            top.push_back(vertex(radius * std::cos(a), radius * std::sin(a), 0));
            bottom.push_back(vertex(radius * std::cos(a), radius * std::sin(a), -2));
        }
        // The rib's footprint, counter-clockwise from +z; the disc's top fans from its rim to
        // the footprint corner nearest in angle, so that the rib's edges are the top's too.
        const double corners[4][2] = {{w, -length}, {w, length}, {-w, length}, {-w, -length}};
        int foot[4];
        for (int c = 0; c < 4; ++c) foot[c] = vertex(corners[c][0], corners[c][1], 0);
        auto nearest = [&](double a) {
            int best = 0;
            for (int c = 1; c < 4; ++c)
                if (std::abs(std::remainder(a - std::atan2(corners[c][1], corners[c][0]), 2 * M_PI)) <
                    std::abs(std::remainder(a - std::atan2(corners[best][1], corners[best][0]), 2 * M_PI)))
                    best = c;
            return best;
        };
        for (int k = 0; k < shape.n; ++k) {
            const int next = (k + 1) % shape.n, c0 = nearest(2 * M_PI * k / shape.n), c1 = nearest(2 * M_PI * next / shape.n);
            triangle(top[k], top[next], foot[c0]);
            if (c1 != c0) triangle(foot[c0], top[next], foot[c1]);
        }
        for (int k = 1; k + 1 < shape.n; ++k) triangle(bottom[0], bottom[k + 1], bottom[k]);
        for (int k = 0; k < shape.n; ++k) {
            const int next = (k + 1) % shape.n;
            triangle(top[k], bottom[k], bottom[next]), triangle(top[k], bottom[next], top[next]);
        }
        const int ridge[2] = {vertex(-w, -length, shape.height), vertex(w, -length, shape.height)};
        const int first_rib_face = static_cast<int>(soup.polygon_count());
        triangle(foot[0], foot[1], ridge[1]);  // side x = +w
        triangle(foot[3], ridge[0], foot[2]);  // side x = -w
        triangle(foot[3], foot[0], ridge[1]), triangle(foot[3], ridge[1], ridge[0]);  // back
        triangle(foot[1], foot[2], ridge[0]), triangle(foot[1], ridge[0], ridge[1]);  // slope
        const Mesh mesh = build_mesh(soup);
        ASSERT_EQ(static_cast<int>(mesh.face_count()), first_rib_face + 6);
        const Result r = test::approximate(mesh, counted(0));
        for (int side : {first_rib_face, first_rib_face + 1})
            EXPECT_EQ(std::count(r.face_labels.begin(), r.face_labels.end(), r.face_labels[side]), 1) << side;
        // Disc top, bottom and side, the rib's sides, back and slope, where the slope meets
        // the top at a crease (a lower one bends below the crease angle, and may be taken as
        // a facet of an arc: another case).
        if (std::atan2(shape.height, 2 * length) > 50 * M_PI / 180) EXPECT_EQ(r.proxies.size(), 7u);
    }
}

TEST(CadExtraction, ACoarseCylindersCapsFannedFromTheRimAreNotMergedIntoItsSide) {
    // A cylinder of one facet row whose caps are polygons fanned from a rim vertex, as CAD
    // exporters write them (an ABB robot base's boss, 24 facets): every vertex of a cap lies
    // on the side's rims, so the finish's run of exact pieces tried cap and side as one
    // surface, and the cap's faces, which cut across the cylinder, were held to the
    // tessellation's deviation over both, the median of the faces' largest sagitta: every
    // cap face borders the rim, and so do half the side's, so the median was the rim
    // crease's. Cap and side became one region, typed an ellipsoid or a plane 0.13 to 0.24 of
    // the radius off its faces. Each piece must now also sag as a smooth surface's facets do:
    // within the deviation over the edges that are no creases, or within 16 times the least
    // RMS of the others (the cap's is a thousand times the side's). Random poses,
    // 16 to 48 facets, 0.4 and 1.5 times the radius tall: three regions, each one true face.
    // What is left: at 12 facets and 0.4 of the radius tall, a quadric of the rims' pencil
    // passes within the facets' own sag of both, and they still merge (0.2 tall, the side's
    // facets stay planes of their own).
    std::mt19937 rng(7);
    for (const int around : {16, 24, 48}) {
        for (const double height : {0.4, 1.5}) {
            SCOPED_TRACE(std::to_string(around) + " facets, height " + std::to_string(height));
            const Eigen::Matrix3d R = test::random_rotation(rng);
            const Vec3 t(0.3, -1.2, 2.0);
            PolygonSoup soup;
            for (int ring = 0; ring < 2; ++ring)
                for (int k = 0; k < around; ++k) {
                    const double a = 2 * M_PI * k / around;
                    soup.positions.push_back(R * Vec3(std::cos(a), std::sin(a), ring * height) + t);
                }
            std::vector<int> face_of_triangle;  // 0 the side, 1 and 2 the caps
            for (int k = 0; k < around; ++k) {
                const int quad[4] = {k, (k + 1) % around, around + (k + 1) % around, around + k};
                soup.add_polygon(quad, 4);
                face_of_triangle.insert(face_of_triangle.end(), 2, 0);
            }
            std::vector<int> bottom, top;
            for (int k = 0; k < around; ++k) bottom.push_back(around - 1 - k), top.push_back(around + k);
            soup.add_polygon(bottom.data(), around);
            soup.add_polygon(top.data(), around);
            face_of_triangle.insert(face_of_triangle.end(), around - 2, 1);
            face_of_triangle.insert(face_of_triangle.end(), around - 2, 2);
            const Mesh mesh = build_mesh(soup);
            ASSERT_EQ(mesh.face_count(), face_of_triangle.size());
            const Result r = test::approximate(mesh, counted(0));
            ASSERT_EQ(r.proxies.size(), 3u);
            std::map<int, std::set<int>> faces_in;  // region → the true faces it holds
            for (std::size_t f = 0; f < face_of_triangle.size(); ++f) faces_in[r.face_labels[f]].insert(face_of_triangle[f]);
            for (const ProxyResult& p : r.proxies) {
                ASSERT_EQ(faces_in[p.id].size(), 1u) << "region " << p.id << " holds faces of two true faces";
                if (*faces_in[p.id].begin() == 0) {
                    EXPECT_EQ(p.type, QuadricType::cylinder) << type_name(p.type);
                    EXPECT_NEAR(p.shape.radius, 1.0, 1e-6);
                } else {
                    EXPECT_EQ(p.type, QuadricType::plane) << type_name(p.type);
                }
            }
        }
    }
}

// A box with every edge chamfered at 45° (26 faces: 6 sides, 12 chamfers, 8 corner
// triangles), in the pose `rotation`, each face a polygon fanned from its first corner: 44
// triangles. No edge bends by the crease angle but the corners' (55°), so one chart holds
// nearly all of it.
struct LabelledSoup {
    PolygonSoup soup;
    std::vector<int> face_of_triangle;  // per fanned triangle: its true face, the polygon
};
LabelledSoup chamfered_box(const Eigen::Matrix3d& rotation) {
    const double a = 1.0, b = 0.7, c = 0.4, d = 0.1;
    PolygonSoup soup;
    // Point k of corner (sx, sy, sz): on the side normal to axis k, beside that corner.
    auto point = [](int sx, int sy, int sz, int k) { return 3 * (4 * (sx > 0) + 2 * (sy > 0) + (sz > 0)) + k; };
    for (int corner = 0; corner < 8; ++corner)
        for (int k = 0; k < 3; ++k) {
            Vec3 p(a - d, b - d, c - d);
            p[k] += d;
            const Vec3 sign((corner & 4) ? 1 : -1, (corner & 2) ? 1 : -1, (corner & 1) ? 1 : -1);
            soup.positions.push_back(rotation * p.cwiseProduct(sign) + Vec3(-2, 5, 1));
        }
    std::vector<std::vector<int>> polygons;
    for (int k = 0; k < 3; ++k)
        for (int s : {-1, 1}) {
            // The side normal to axis k at sign s, and the chamfers and corners by it.
            const int u = (k + 1) % 3, v = (k + 2) % 3;
            auto at = [&](int su, int sv, int which) {
                int signs[3];
                signs[k] = s, signs[u] = su, signs[v] = sv;
                return point(signs[0], signs[1], signs[2], which);
            };
            polygons.push_back({at(-1, -1, k), at(1, -1, k), at(1, 1, k), at(-1, 1, k)});
            for (int su : {-1, 1})  // the chamfer between this side and side u of sign su, along v
                polygons.push_back({at(su, -1, k), at(su, 1, k), at(su, 1, u), at(su, -1, u)});
        }
    for (int corner = 0; corner < 8; ++corner) polygons.push_back({3 * corner, 3 * corner + 1, 3 * corner + 2});
    EXPECT_EQ(polygons.size(), 26u);
    std::vector<int> face_of_triangle;
    for (std::size_t k = 0; k < polygons.size(); ++k) {
        soup.add_polygon(polygons[k].data(), polygons[k].size());
        face_of_triangle.insert(face_of_triangle.end(), polygons[k].size() - 2, static_cast<int>(k));
    }
    return {std::move(soup), std::move(face_of_triangle)};
}

TEST(CadExtraction, ACoarseExportHasNoNoise) {
    // The chamfered box's vertices' deviations from a quadric through two rings were the
    // chamfers themselves, read as noise of 8 % of the size: the run stopped at one sphere,
    // every region "explained". An exact tessellation (its faces coplanar with neighbours to
    // the stored precision) has no noise to measure.
    const PolygonSoup soup = chamfered_box(Eigen::AngleAxisd(1.1, Vec3(-2, 1, 3).normalized()).toRotationMatrix()).soup;
    const Mesh box = build_mesh(soup);
    ASSERT_EQ(box.face_count(), 44u);
    const Model model = make_model(box);
    const Features features = detect_features(model);
    for (int f = 0; f < model.face_count(); ++f) EXPECT_LE(features.roughness[f], kStoredPrecision) << "face " << f;
    // The same box with its vertices moved by up to 1e-4 of its size is no exact export.
    PolygonSoup noisy = soup;
    SplitMix64 rng(5);
    const auto offset = [&] { return 2e-4 * (static_cast<double>(rng.below(1u << 20)) / (1u << 20) - 0.5); };
    for (Vec3& p : noisy.positions) p += Vec3(offset(), offset(), offset());
    const Model noisy_model = make_model(build_mesh(noisy));
    const Features noisy_features = detect_features(noisy_model);
    EXPECT_GT(*std::max_element(noisy_features.roughness.begin(), noisy_features.roughness.end()), kStoredPrecision);
}

// Each region of `r` is one true face of the chamfered box, and a plane, and no face is split.
void expect_the_boxs_faces(const LabelledSoup& truth, const Mesh& box, const Result& r, int pose) {
    ASSERT_EQ(r.proxies.size(), 26u) << "pose " << pose;
    std::vector<int> face_of_region(26, -1);
    std::vector<char> face_taken(26, 0);
    for (int f = 0; f < static_cast<int>(box.face_count()); ++f) {
        const int face = truth.face_of_triangle[box.source_face[f]];
        int& region_face = face_of_region[r.face_labels[f]];
        if (region_face < 0) {
            EXPECT_FALSE(face_taken[face]) << "pose " << pose << ": face " << face << " split";
            region_face = face, face_taken[face] = 1;
        }
        EXPECT_EQ(region_face, face) << "pose " << pose << ": region " << r.face_labels[f] << " over two faces";
    }
    for (const ProxyResult& p : r.proxies) EXPECT_EQ(p.type, QuadricType::plane) << "pose " << pose;
}

// The chamfered box in `poses` random poses, each approximated with `options`.
void expect_the_boxs_faces_in_random_poses(int poses, std::uint64_t seed, const Options& options) {
    SplitMix64 rng(seed);
    const auto uniform = [&] { return static_cast<double>(rng.below(1u << 20)) / (1u << 20); };
    for (int pose = 0; pose < poses; ++pose) {
        const Vec3 axis = Vec3(uniform() - 0.5, uniform() - 0.5, uniform() - 0.5).normalized();
        const LabelledSoup truth = chamfered_box(Eigen::AngleAxisd(6.28 * uniform(), axis).toRotationMatrix());
        const Mesh box = build_mesh(truth.soup);
        ASSERT_EQ(box.face_count(), 44u);
        expect_the_boxs_faces(truth, box, test::approximate(box, options), pose);
    }
}

TEST(CadExtraction, AtItsTrueCountAChamferedBoxIsItsFaces) {
    // Insertions seeded a plane region's worst face counted with its neighbours: the chamfer
    // beside a corner triangle, not the corner; that proxy took the chamfer and left the corner
    // to the region bent over both: in five random poses the box ended with 19 or 20
    // regions, some over two faces. Without noise a lone face of large error is a face.
    expect_the_boxs_faces_in_random_poses(5, 11, counted(26));
}

TEST(CadExtraction, AutomaticallyAChamferedBoxIsItsFacesInEveryPose) {
    // Its chamfers bend by 45°, below the crease angle: no charts, and growth goes by
    // insertions alone. In 6 of 30 poses, three insertions in a row from one to seven
    // proxies bought less than 5 % each (two of them raised the energy: Lloyd settled
    // worse than before), growth stopped, and the finish merged the lot into one sphere.
    // Without noise an insertion that leaves more error than before has found a worse
    // partition, not the last surface: it does not count against growing.
    expect_the_boxs_faces_in_random_poses(30, 12, counted(0));
}

// A prism 28 × 20 × 7.6 over a rectangle whose corners are rounded to a radius of 3 in 10
// facets each, in the pose `rotation`: 10 faces (4 sides, 4 corners, 2 caps), each side and
// facet one quad, each cap one polygon.
LabelledSoup rounded_prism(const Eigen::Matrix3d& rotation) {
    const double width = 28, depth = 20, radius = 3, height = 7.6;
    const int facets = 10;
    std::vector<Vec3> outline;
    for (int corner = 0; corner < 4; ++corner) {
        const double x = (corner == 0 || corner == 3 ? 1 : -1) * (width / 2 - radius);
        const double y = (corner < 2 ? 1 : -1) * (depth / 2 - radius);
        for (int k = 0; k <= facets; ++k) {
            const double angle = 1.5707963267948966 * (corner + static_cast<double>(k) / facets);
            outline.push_back(Vec3(x + radius * std::cos(angle), y + radius * std::sin(angle), 0));
        }
    }
    const int n = static_cast<int>(outline.size());
    PolygonSoup soup;
    for (double z : {0.0, height})
        for (const Vec3& p : outline) soup.positions.push_back(rotation * (p + Vec3(0, 0, z)) + Vec3(3, -1, 2));
    std::vector<int> face_of_triangle;
    auto add = [&](std::vector<int> polygon, int face) {
        soup.add_polygon(polygon.data(), polygon.size());
        face_of_triangle.insert(face_of_triangle.end(), polygon.size() - 2, face);
    };
    // Outline point i is the k-th of corner i / 11; the quad from i to i + 1 is a facet of
    // that corner, or (k = 10) the side after it.
    for (int i = 0; i < n; ++i) {
        const int j = (i + 1) % n, corner = i / (facets + 1), k = i % (facets + 1);
        add({i, j, n + j, n + i}, k == facets ? 4 + corner : corner);
    }
    std::vector<int> bottom, top;
    for (int i = 0; i < n; ++i) bottom.push_back(n - 1 - i), top.push_back(n + i);
    add(bottom, 8);
    add(top, 9);
    return {std::move(soup), std::move(face_of_triangle)};
}

TEST(CadExtraction, AHandfulOverASideAndTheFacetsBesideItParts) {
    // Growing, a side's region (two long triangles) took the first facets of the coarse
    // corners beside it. Fitted by a plane, as a handful is, its error was far too small for
    // an insertion to pay, and beside the seam its faces' roughness counted as noise: the
    // run ended with it, 3 or 4 regions of 9 or 10 over two true faces in each of 8 poses.
    // Its coplanar pieces now part at the stop, and the facets join their corners: none in
    // 6 poses. In the other two a corner is still split between the sides beside it, each
    // part too large for a handful (9 regions, 2 over two faces).
    SplitMix64 rng(17);
    int exact_poses = 0;
    const auto uniform = [&] { return static_cast<double>(rng.below(1u << 20)) / (1u << 20); };
    for (int pose = 0; pose < 8; ++pose) {
        const Vec3 axis = Vec3(uniform() - 0.5, uniform() - 0.5, uniform() - 0.5).normalized();
        const LabelledSoup truth = rounded_prism(Eigen::AngleAxisd(6.28 * uniform(), axis).toRotationMatrix());
        const Mesh prism = build_mesh(truth.soup);
        const Result r = test::approximate(prism, counted(0));
        std::map<int, std::set<int>> faces_in;  // region → the true faces it holds
        for (int f = 0; f < static_cast<int>(prism.face_count()); ++f)
            faces_in[r.face_labels[f]].insert(truth.face_of_triangle[prism.source_face[f]]);
        int over_two = 0;
        for (const auto& [region, faces] : faces_in) over_two += faces.size() > 1;
        EXPECT_LE(over_two, 2) << "pose " << pose;
        exact_poses += over_two == 0 && r.proxies.size() == 10;
    }
    EXPECT_GE(exact_poses, 6);
}

TEST(CadExtraction, AStepsChamferLeavesItsWallButACoarseCornersColumnStays) {
    // Two walls in strips of full-height triangles and the chamfer between them, bent by 37°
    // (below the crease angle), in one chart. Automatically, at details up to 1, the chamfer
    // and the longer wall ended as one exact hyperboloid through the wall's two edges (7
    // regions of 8, accuracy 0.9895): their vertices determine no quadric, and two planes
    // say as much in fewer numbers. On the irregular mesh rounding made the hyperboloid
    // look determined: a second quadric 2e-9 from the vertices, far within the stored
    // precision, was taken for none.
    for (double detail : {0.6, 1.0, 1.5}) {
        for (bool irregular : {false, true}) {
            PartOptions options;
            options.detail = detail;
            options.irregular = irregular;
            options.random_pose = true;
            options.seed = 5;
            const Part part = make_part("stepped_block", options);
            ASSERT_EQ(part.surfaces.size(), 8u);
            const std::string where = "detail " + std::to_string(detail) + (irregular ? " irregular" : " clean");
            const Outcome at_count = run(part, counted(8));
            EXPECT_GE(at_count.accuracy, 0.999) << where;
            const Outcome automatic = run(part, counted(0));
            EXPECT_EQ(automatic.regions, 8) << where;
            EXPECT_GE(automatic.accuracy, 0.999) << where;
            EXPECT_EQ(automatic.two_part, 0) << where;
        }
    }
    // The same two pieces without the inflection: a plate's side one facet tall and the
    // column of a coarse corner beside it, whose next column bends on the same way, stay
    // one region (the plate assembly at detail 0.25: 55 regions for its 39 faces when any
    // two pieces left).
    const CorpusCase c = corpus_case("plate_assembly", "clean", 0.25);
    const Part part = make_part(c.part, c.options);
    const Outcome automatic = run(part, counted(0, c.options.seed));
    EXPECT_LE(automatic.regions, static_cast<int>(1.15 * part.surfaces.size()));
    EXPECT_GE(automatic.accuracy, 0.98);
}

TEST(CadExtraction, ACoarseLBracketsLegLeavesTheQuadricOfItsFillet) {
    // The L-bracket exported coarsely (detail 0.25): growth ended with a leg's face, an exact
    // plane, and the fillet's facets beside it in one curved region, 8 regions of 9
    // (accuracy 0.9375 at seed offsets 0 and 1). At the stop, a piece of exactly coplanar
    // faces that is no strip now leaves such a region when that lowers its error.
    const CorpusCase c = corpus_case("l_bracket", "clean", 0.25);
    const Part part = make_part(c.part, c.options);
    for (std::uint64_t offset : {0, 1}) {
        const Outcome automatic = run(part, counted(0, c.options.seed + offset));
        EXPECT_EQ(automatic.regions, static_cast<int>(part.surfaces.size())) << "seed offset " << offset;
        EXPECT_GE(automatic.accuracy, 0.99) << "seed offset " << offset;
    }
}

TEST(CadExtraction, ACoarseExportsSmallFacesMakeItExact) {
    // abc_round_cap.stl: a notch in its rim is six faces of two to six triangles. Merged into
    // their neighbours at least cost, they bent the inner disc into an elliptic paraboloid
    // (17 regions, projected RMS 1.4e-4, Hausdorff 5.2e-3); kept, every region is exact.
    const Mesh mesh = read_mesh_file(test::shared_mesh("abc_round_cap.stl"));
    Options o = counted(0);
    o.project = true;
    const Result r = test::approximate(mesh, o);
    ASSERT_TRUE(r.metrics.has_value());
    EXPECT_LT(r.metrics->rms, 1e-6);
    EXPECT_LT(r.metrics->hausdorff, 1e-6);
    EXPECT_EQ(two_part_regions(mesh, r), 0);
}

TEST(CadExtraction, ACoarseSpheresCapsAreNotTakenByTheFacesTheyCross) {
    // csg.off: a cube ∪ sphere and a cube ∩ sphere, the sphere 1 066 vertices in all (facets
    // bending by up to 40°). Automatic, each face of the union, with the sphere's cap through
    // it, was one cone or hyperboloid region (13 regions, 5 planes, 1 sphere); its facets now
    // count as chords of the sphere, and the caps are spheres of their own (17 regions,
    // 10 planes, 4 spheres; 12 planes and 7 sphere pieces in truth). Until a region's facet
    // strip on a second plane went to its neighbour at the stop, one face of the cube, with
    // a ring of the sphere's facets, was typed a sphere (9 planes, 5 spheres): it is an
    // exact plane now. The tessellation's unevenness once counted as noise (an umbrella's
    // second difference), and one cube face with its cap ended as one cone: measured by
    // local quadric fits (METHOD §3) it is no noise, and every piece is found (12 planes,
    // 6 spheres, the intersection's sphere an ellipsoid).
    const Mesh mesh = read_mesh_file(test::shared_mesh("csg.off"));
    const Result r = test::approximate(mesh, counted(0));
    int planes = 0, spheres = 0;
    for (const ProxyResult& p : r.proxies) planes += p.type == QuadricType::plane, spheres += p.type == QuadricType::sphere;
    EXPECT_EQ(planes, 12);
    EXPECT_GE(spheres, 6);
    EXPECT_LE(r.proxies.size(), 19u);
    EXPECT_EQ(two_part_regions(mesh, r), 0);
}

TEST(CadExtraction, NoisyFilletsStayApartFromTheirPlanesAtACount) {
    // Under noise of 4 % of the fillets' radius one general quadric bends round a fillet and
    // its plane within the noise of both, as well as they fit apart: at a count such pairs
    // merged until 12 regions were left of 26 (accuracy 0.56). A union must also be the type
    // the larger region is (a plane stays a plane), which keeps them apart. Still short of
    // the corpus's bar (bench/RESULTS.md §4): the Lloyd partition itself, within the noise,
    // does not follow the tangent seams (0.6148 until the noise was measured by local
    // quadric fits, METHOD §3: 0.5905).
    const std::vector<CorpusCase> cases = cad_corpus({"rounded_block"});
    const auto noisy = std::find_if(cases.begin(), cases.end(), [](const CorpusCase& c) { return c.variant == "noisy"; });
    const Part part = make_part(noisy->part, noisy->options);
    const Outcome o = run(part, counted(static_cast<int>(part.surfaces.size()), noisy->options.seed));
    EXPECT_GE(o.regions, 16);
    EXPECT_GE(o.accuracy, 0.58);
    EXPECT_EQ(o.two_part, 0);
}

TEST(CadExtraction, ProxiesSpentBadlyUnderNoiseAreSpentAgainByAWideTeleport) {
    // The noisy stepped shaft with the method's seed one past the corpus's: at its true count
    // the chamfer's cone was shared three ways and one region bent over a cylinder and half
    // the cone (RMS 2.4 × its noise), and no single teleport paid (accuracy 0.9408). Four
    // proxies more and four merges back find its seven faces, as the automatic count does.
    const Outcome o = corpus_case_at_true_count("stepped_shaft", "noisy", 1).second;
    EXPECT_GE(o.accuracy, 0.99);
    EXPECT_EQ(o.regions, 7);
    EXPECT_EQ(o.two_part, 0);
}

TEST(CadExtraction, UnderNoiseTheMergeBackToTheCountDoesNotJoinTwoFacesAcrossACrease) {
    // Merging back to the count took the cheapest union, and under noise two faces at a
    // sharp crease fit one quadric within the noise: the noisy slotted block at seed offset
    // 4 kept two sides of the block as one eccentric elliptic cone (crease vertices missed
    // by 11 σ) while its slot's flat wall held two proxies (accuracy 0.9149); the noisy hex
    // nut, at every seed, its bottom and one flat side as one region (0.9158).
    const Outcome slotted = corpus_case_at_true_count("slotted_block", "noisy", 4).second;
    EXPECT_GE(slotted.accuracy, 0.99);
    EXPECT_EQ(slotted.regions, 10);
    for (std::uint64_t offset = 0; offset < 2; ++offset) {
        SCOPED_TRACE("hex nut, seed offset " + std::to_string(offset));
        const Outcome o = corpus_case_at_true_count("hex_nut", "noisy", offset).second;
        EXPECT_GE(o.accuracy, 0.999);
        EXPECT_EQ(o.regions, 11);
    }
}

TEST(CadExtraction, ANoisyFilletSplitBetweenTwoBentRegionsIsHandedToOne) {
    // Under noise the L-bracket's fillet was split at every seed between a region bending
    // over one leg and half of it (an elliptic paraboloid) and one holding the other half
    // (accuracy 0.9649), each within its noise. The hand-over (post/seams.h) makes the leg a
    // plane and the fillet one cylinder.
    const std::vector<CorpusCase> cases = cad_corpus({"l_bracket"});
    const auto noisy = std::find_if(cases.begin(), cases.end(), [](const CorpusCase& c) { return c.variant == "noisy"; });
    const Part part = make_part(noisy->part, noisy->options);
    for (std::uint64_t offset = 0; offset < 4; ++offset) {
        SCOPED_TRACE("seed offset " + std::to_string(offset));
        const Outcome o = run(part, counted(static_cast<int>(part.surfaces.size()), noisy->options.seed + offset));
        EXPECT_GE(o.accuracy, 0.985);
        int fillets = 0;
        for (const ProxyResult& p : o.result.proxies) {
            const int face = o.score.face_of[p.id];
            if (face < 0 || part.surfaces[face].type != QuadricType::cylinder) continue;
            ++fillets;
            ASSERT_EQ(p.type, QuadricType::cylinder) << type_name(p.type);
            // It reaches a facet row into each leg, where plane and cylinder part by less than
            // the noise, and flattens by that much (bench/RESULTS.md §4).
            EXPECT_LT(parameter_error(part.surfaces[face], p.shape).radius_relative, 0.05);
        }
        EXPECT_EQ(fillets, 1);
    }
}

TEST(CadExtraction, BandsAndStripsOneFacetAcrossAreTheSurfacesTheirEdgesLieOn) {
    // abc_round_cap.stl's four bands, one row of facets each, were spheres through their two
    // circles of vertices, which the STL's float coordinates leave 1e-8 off every candidate:
    // two are cylinders (1.5 inch), two 15° cones.
    const Mesh cap = read_mesh_file(test::shared_mesh("abc_round_cap.stl"));
    const Result r = test::approximate(cap, counted(0));
    int cones = 0, cylinders = 0;
    for (const ProxyResult& p : r.proxies) {
        EXPECT_NE(p.type, QuadricType::sphere) << "region " << p.id;
        if (p.type == QuadricType::cone) {
            ++cones;
            EXPECT_NEAR(p.shape.half_angle * 180 / M_PI, 15, 1e-3);
        }
        if (p.type == QuadricType::cylinder) ++cylinders;
    }
    EXPECT_EQ(cones, 2);
    EXPECT_EQ(cylinders, 4);
    // The noisy L-bracket's end faces, one facet wide: the end that was an elliptic paraboloid
    // through its two noisy rows of vertices is a plane.
    const auto [part, o] = corpus_case_at_true_count("l_bracket", "noisy");
    int planes = 0;
    for (const ProxyResult& p : o.result.proxies) {
        const int face = o.score.face_of[p.id];
        if (face < 0 || !o.score.clean_match[p.id] || part.surfaces[face].type != QuadricType::plane) continue;
        EXPECT_EQ(p.type, QuadricType::plane) << "region " << p.id << " of " << p.faces << " faces";
        ++planes;
    }
    EXPECT_GE(planes, 7);
}

TEST(CadExtractionHeavy, SharedMeshesAtThePapersCountsHaveNoTwoPartRegion) {
    const std::pair<const char*, int> meshes[] = {
        {"fandisk.off", 22}, {"joint.off", 30},          {"csg.off", 10},          {"block.off", 20},
        {"casting.off", 30}, {"pinion.off", 30},         {"cylinder_capped.off", 3}, {"abc_pipe_junction.stl", 20},
        {"abc_round_cap.stl", 15}, {"mask.off", 6},      {"chess_pawn.stl", 12},   {"rocker_arm.obj", 20}};
    for (const auto& [name, count] : meshes) {
        SCOPED_TRACE(name);
        const Mesh mesh = read_mesh_file(test::shared_mesh(name));
        const Result r = test::approximate(mesh, counted(count));
        // A count is a maximum: a mesh whose every region its noise explains stops earlier.
        EXPECT_LE(static_cast<int>(r.proxies.size()), count);
        EXPECT_EQ(two_part_regions(mesh, r), 0);
        for (const ProxyResult& p : r.proxies)
            EXPECT_TRUE(p.type != QuadricType::intersecting_planes && p.type != QuadricType::parallel_planes &&
                        p.type != QuadricType::empty)
                << "region " << p.id << " is " << type_name(p.type);
    }
}

TEST(CadExtractionHeavy, SharedCadMeshesWithTheAutomaticCountHaveNoTwoPartRegion) {
    for (const char* name : {"fandisk.off", "joint.off", "block.off", "casting.off", "pinion.off", "cylinder_capped.off",
                             "abc_pipe_junction.stl", "abc_round_cap.stl"}) {
        SCOPED_TRACE(name);
        const Mesh mesh = read_mesh_file(test::shared_mesh(name));
        const Result r = test::approximate(mesh, counted(0));
        EXPECT_EQ(two_part_regions(mesh, r), 0);
        EXPECT_TRUE(r.stop_reason == StopReason::fitted || r.stop_reason == StopReason::no_gain);
    }
}

TEST(CadExtraction, GrowthCountsTheInsertionsThatDoNotPayFromTheLastRepairThatDid) {
    // Three insertions in a row that do not pay end the growth, but a repair between them
    // that lowers the energy by `min_gain` shows that Lloyd was stuck, not that the surfaces
    // were found: the count starts again after it. Before, the rocker arm stopped one
    // insertion after such a repair (87 regions; now 94, RMS 10 % lower). Each operation's
    // event carries the error of the partition it started from, so a teleport's gain is
    // read off the next event.
    const Mesh mesh = read_mesh_file(test::shared_mesh("rocker_arm.obj"));
    std::vector<std::pair<std::string, double>> events;  // operation, settled RMS before it
    const Result r = test::approximate(mesh, counted(0), [&](const Progress& p) {
        if (p.stage == Stage::lloyd && p.settled_proxies > 0 && std::string(p.phase) != "lloyd")
            events.emplace_back(p.phase, p.settled_rms);
        return true;
    });
    ASSERT_EQ(r.stop_reason, StopReason::no_gain);
    const double min_gain = LloydOptions{}.min_gain;
    int paid_repairs = 0, insertions_after = 0;
    for (std::size_t i = 0; i + 1 < events.size(); ++i) {
        if (events[i].first == "insert") ++insertions_after;
        const double before = events[i].second, after = events[i + 1].second;
        if (events[i].first == "teleport" && after * after < (1 - min_gain) * before * before)
            ++paid_repairs, insertions_after = 0;
    }
    EXPECT_GT(paid_repairs, 0);
    EXPECT_GE(insertions_after, 3);
}

TEST(CadExtraction, WithoutTheRefitNoRegionNamesTwoPartsEither) {
    // Without the refit a region keeps the quadric Lloyd fitted, which may lie on a second
    // part by less than Lloyd's split threshold, or be a pair of planes whose one plane holds
    // the faces: casting.off at 40 had two regions on two parts and three named plane pairs.
    // Such a region is typed as the refit would type it; the others keep Lloyd's quadric.
    const Mesh mesh = read_mesh_file(test::shared_mesh("casting.off"));
    for (const int count : {40, 0}) {
        SCOPED_TRACE(count);
        Options o = counted(count);
        o.refit = false;
        const Result r = test::approximate(mesh, o);
        EXPECT_EQ(two_part_regions(mesh, r), 0);
        int kept = 0;
        for (const ProxyResult& p : r.proxies) {
            EXPECT_TRUE(p.type != QuadricType::intersecting_planes && p.type != QuadricType::parallel_planes &&
                        p.type != QuadricType::empty)
                << "region " << p.id << " is " << type_name(p.type);
            kept += !p.special_fit;
        }
        // Most regions keep the quadric Lloyd fitted: the typing is no refit in disguise.
        EXPECT_GE(kept, 0.85 * static_cast<double>(r.proxies.size()));
    }
}

// block.off made noisy along its normals (σ `noise` of its diagonal, draws 1–3), each draw
// run with the automatic count and passed to `check` with the share of its area that lies
// within one crease chart of the clean export.
void for_each_noisy_block(double noise, const std::function<void(const Mesh&, const Result&, double)>& check) {
    const Mesh clean = read_mesh_file(test::shared_mesh("block.off"));
    const Model model = make_model(clean);
    const Features charts = detect_features(model);
    for (std::uint64_t draw : {1, 2, 3}) {
        SCOPED_TRACE(draw);
        Mesh noisy = clean;
        add_normal_noise(noisy, noise, draw);
        const Result r = test::approximate(noisy, counted(0));
        check(noisy, r, area_within_one_chart(model, charts.chart, r.face_labels, static_cast<int>(r.proxies.size())));
    }
}

TEST(CadExtraction, ANoisyCoarseExportKeepsItsRegionsBetweenItsCreases) {
    // block.off made noisy along its normals (σ 0.1 % of its diagonal, three draws), its
    // regions held to the crease charts of the clean export. Its CAD edges carry slivers
    // 1e-4 wide, which the noise turns into chains of faces creased on most sides; a region
    // whose least error (weighted by area) lay on such a sliver flooded only a handful of
    // faces from it, and a hole's quadric took both holes and then a face of the block: at
    // draw 2, 15 % of the area lay in regions across creases (a cone, paraboloids and
    // hyperboloids among them), and draw 1 ended with 24 regions. A seed now needs a
    // crease-free neighbourhood of a surface's worth of faces (docs/METHOD.md §4).
    const std::size_t clean_regions =
        test::approximate(read_mesh_file(test::shared_mesh("block.off")), counted(0)).proxies.size();
    for_each_noisy_block(0.001, [&](const Mesh& noisy, const Result& r, double within_one_chart) {
        EXPECT_GE(within_one_chart, 0.99);
        EXPECT_LE(r.proxies.size(), clean_regions + 3);
        EXPECT_GE(r.proxies.size() + 2, clean_regions);
        for (const ProxyResult& p : r.proxies)
            EXPECT_TRUE(p.type == QuadricType::plane || p.type == QuadricType::cylinder) << type_name(p.type);
        EXPECT_EQ(two_part_regions(noisy, r), 0);
    });
}

TEST(CadExtraction, UnderNoiseAQuadricBentThroughACreaseIsTwoPlanes) {
    // block.off with noise of 0.2 % of its diagonal, draws 1–3: at draw 1 the block's front
    // and bottom faces were one region, a hyperbolic paraboloid at 1.3 σ RMS (within the
    // noise it explains): 0.9325 of the area within one clean crease chart. Its faces' normals
    // fall in two groups a right angle apart, each held by its plane as closely as by the
    // quadric: two planes (docs/METHOD.md §5).
    for_each_noisy_block(0.002, [](const Mesh& noisy, const Result& r, double within_one_chart) {
        EXPECT_GE(within_one_chart, 0.995);
        for (const ProxyResult& p : r.proxies) EXPECT_NE(p.type, QuadricType::hyperbolic_paraboloid);
        EXPECT_EQ(two_part_regions(noisy, r), 0);
    });
}

TEST(CadExtractionHeavy, AFinelyMeshedPartUnderNoiseOfItsFacesWidthStaysAFewRegions) {
    // abc_pipe_junction.stl (37K faces) with noise along its normals of 0.2 % of its
    // diagonal, about the width of its faces: every face's normal turned at random, false
    // creases everywhere (20 000, against 1 100 clean) cut the part into 3 300 charts, and
    // the automatic count grew into them until the iteration cap, 1 400 regions in 96 s.
    // Faces now start from the mean normal of their most consistent patch, wide enough for
    // the noise (docs/METHOD.md §3).
    // At draw 2 the run then grew to 155 regions and merged back to 68 in 1 713 iterations,
    // its main cylinder in strips: 601 of 692 finishing merges were undone, most of them for
    // error that Lloyd left unexplained elsewhere with or without the merge. A merge is now
    // judged against the same Lloyd stage without it (docs/METHOD.md §7).
    const Mesh clean = read_mesh_file(test::shared_mesh("abc_pipe_junction.stl"));
    const std::size_t clean_regions = test::approximate(clean, counted(0)).proxies.size();
    Mesh noisy = clean;
    add_normal_noise(noisy, 0.002, 2);
    const Model model = make_model(noisy);
    const Features features = detect_features(model);
    EXPECT_LE(features.chart_count, 100);
    const Result r = test::approximate(noisy, counted(0));
    EXPECT_NE(r.stop_reason, StopReason::max_iterations);
    EXPECT_LE(r.iterations, 1000);
    EXPECT_LE(2 * r.proxies.size(), 3 * clean_regions) << r.proxies.size() << " regions, " << clean_regions << " clean";
    EXPECT_EQ(two_part_regions(noisy, r), 0);
}

TEST(CadExtraction, CrossingHolesStayTwoRegionsWithTheAutomaticCount) {
    // block.off's two holes, along x and along y, cross: their cylinders meet along curves
    // where an ellipsoid passes within the coarse tessellation's noise of both, and the
    // finishing merges used to join pieces of the two holes, after which that quadric took
    // both (one region of RMS 0.9 on a 38-unit part). A merge is now undone when, Lloyd
    // settled, it leaves more error unexplained than the noise it was allowed.
    const Mesh mesh = read_mesh_file(test::shared_mesh("block.off"));
    const Result r = test::approximate(mesh, counted(0));
    // A hole's faces face across its axis: normal ⊥ the axis, off the two other axes.
    std::vector<std::array<double, 2>> hole_area(r.proxies.size(), {0, 0});
    std::array<double, 2> total{0, 0};
    for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
        const Triangle& t = mesh.triangles[f];
        const Vec3 c = (mesh.vertices[t[1]] - mesh.vertices[t[0]]).cross(mesh.vertices[t[2]] - mesh.vertices[t[0]]);
        const Vec3 n = c.normalized();
        for (int axis : {0, 1}) {
            const int other = 1 - axis;
            if (std::abs(n[axis]) < 0.05 && std::abs(n[other]) > 0.1 && std::abs(n[2]) > 0.1) {
                hole_area[r.face_labels[f]][axis] += c.norm() / 2;
                total[axis] += c.norm() / 2;
            }
        }
    }
    ASSERT_GT(total[0], 0);
    ASSERT_GT(total[1], 0);
    std::vector<double> radii;
    for (std::size_t i = 0; i < r.proxies.size(); ++i) {
        EXPECT_LT(std::min(hole_area[i][0] / total[0], hole_area[i][1] / total[1]), 0.05)
            << "region " << i << " spans both holes";
        // Each piece of a hole is a cylinder, although the tessellation pulls its vertices
        // towards the axis by up to its facets' sagitta in a pattern a nine-parameter quadric
        // follows (docs/METHOD.md §6).
        if (std::max(hole_area[i][0] / total[0], hole_area[i][1] / total[1]) < 0.2) continue;
        EXPECT_STREQ(type_name(r.proxies[i].type), "cylinder") << "region " << i;
        radii.push_back(r.proxies[i].shape.radius);
    }
    ASSERT_GE(radii.size(), 2u);
    const auto [smallest, largest] = std::minmax_element(radii.begin(), radii.end());
    EXPECT_LT(*largest / *smallest, 1.01) << "the holes are of one radius";
}

TEST(CadExtractionHeavy, TheSeedPicksSeedFacesAndTheSameSeedGivesTheSameLabels) {
    const Mesh bunny = read_mesh_file(test::shared_mesh("bunny_closed.off"));
    const Result a = test::approximate(bunny, counted(20)), again = test::approximate(bunny, counted(20));
    EXPECT_EQ(a.labels, again.labels);
    Options other = counted(20);
    other.lloyd.seed = 2;
    const Result b = test::approximate(bunny, other);
    EXPECT_NE(a.labels, b.labels);
    // On a CAD part the seed moves seeds within their charts, not the faces found.
    PartOptions pose;
    pose.random_pose = true;
    const Part part = make_part("box_boss_hole", pose);
    for (const std::uint64_t seed : {1u, 2u, 3u}) {
        Options o = counted(9);
        o.lloyd.seed = seed;
        EXPECT_GE(run(part, o).accuracy, 0.97) << "seed " << seed;
    }
}

TEST(CadExtraction, ThePapersInitialisationStaysSelectableAndValid) {
    PartOptions pose;
    pose.random_pose = true;
    const Part part = make_part("l_bracket", pose);
    Options paper = counted(9), features = counted(9);
    paper.lloyd.init = Initialization::paper;
    const Result p = test::approximate(part.mesh, paper), f = test::approximate(part.mesh, features);
    EXPECT_NE(p.lloyd_labels, f.lloyd_labels);
    EXPECT_EQ(two_part_regions(part.mesh, p), 0);
    EXPECT_EQ(p.proxies.size(), 9u);
}

TEST(CadExtraction, NoProxyStaysStuckOnAHandfulOfFaces) {
    // The box with a boss at its true count once kept a proxy on three faces while the
    // boss's side and top shared one region. Every region now holds a true face.
    for (const bool irregular : {false, true}) {
        PartOptions o;
        o.random_pose = true, o.irregular = irregular, o.seed = 11;
        const Part part = make_part("box_boss_hole", o);
        const Result r = test::approximate(part.mesh, counted(static_cast<int>(part.surfaces.size())));
        const PartitionScore score = score_partition(part, r.face_labels, static_cast<int>(r.proxies.size()));
        for (const ProxyResult& p : r.proxies) {
            EXPECT_GE(score.face_of[p.id], 0) << "region " << p.id << " (" << p.faces << " faces) matches no face";
            EXPECT_GT(p.faces, 20) << "region " << p.id;
        }
    }
    // The noisy slotted block (the corpus's case) kept one on three faces while one
    // elliptic cone, within σ of both, took two of the block's sides: every region within
    // its noise, only the side's chart, owned by no proxy, tells where the proxy belongs.
    // The cone turns over several faces, so no crease edge sees it bend; it misses the
    // crease's vertices by 11 σ, which no false crease does (rounds_off): 0.9312 → 0.9941.
    {
        const auto [part, o] = corpus_case_at_true_count("slotted_block", "noisy");
        EXPECT_GE(o.accuracy, 0.95);
        for (const ProxyResult& p : o.result.proxies) EXPECT_GT(p.faces, 20) << "region " << p.id;
    }
    // Homer at the paper's count kept one on a single face: a fold-over 1/50 the median
    // size, creased against all its neighbours, which as the least-error face of any region
    // became its seed and, flooded from, shrank the region to itself.
    const Mesh homer = read_mesh_file(test::shared_mesh("homer.obj"));
    const Result r = test::approximate(homer, counted(61));
    for (const ProxyResult& p : r.proxies) EXPECT_GE(p.faces, 10) << "homer region " << p.id;
}

TEST(CadExtractionHeavy, AFineTurnedPartWithTheAutomaticCountIsItsSixSurfaces) {
    // At 320K faces the sphere's region once took a strip of the tangent cylinder below it
    // (its quadric bent, RMS under the `precision` floor) and left a 43-face region of the
    // exact sphere at the pole: 7 regions, growth ended as fitted. The pole's proxy explains
    // nothing while the bent region carries error its noise does not explain: it is stuck,
    // whatever the floor says, and is moved there.
    const Result r = test::approximate(example_mesh("turned_part:320000"), counted(0));
    ASSERT_EQ(r.proxies.size(), 6u);
    EXPECT_EQ(r.stop_reason, StopReason::fitted);
    std::map<QuadricType, int> types;
    for (const ProxyResult& p : r.proxies) ++types[p.type];
    const std::map<QuadricType, int> expected{{QuadricType::plane, 2}, {QuadricType::cylinder, 2},
                                              {QuadricType::cone, 1}, {QuadricType::sphere, 1}};
    EXPECT_EQ(types, expected);
    // On its own surface a region's facets leave at most 1.5e-5 (part 2 long); the bent one left 2.1e-4.
    for (const ProxyResult& p : r.proxies) EXPECT_LT(p.rms_error, 5e-5) << "region " << p.id << " spans two surfaces";
}

TEST(CadExtraction, AboveTheTrueCountNoSliverIsLeft) {
    // Asked for more proxies than the part has surfaces, the run used to end with the extra
    // ones on slivers of a few faces beside exact surfaces (the app's default example, a
    // turned part at 7, had a 2-face plane). Such slivers go to the surface they lie on,
    // and the run reports fewer proxies, as fitted.
    const int min_faces = LloydOptions{}.min_quadric_faces;
    for (const bool irregular : {false, true}) {
        PartOptions o;
        o.random_pose = true, o.irregular = irregular, o.seed = 5;
        for (const char* name : {"box_boss_hole", "stepped_shaft", "flange"}) {
            const Part part = make_part(name, o);
            const int truth = static_cast<int>(part.surfaces.size());
            const Result r = test::approximate(part.mesh, counted(truth + 3));
            const PartitionScore score = score_partition(part, r.face_labels, static_cast<int>(r.proxies.size()));
            EXPECT_LE(r.proxies.size(), static_cast<std::size_t>(truth + 3)) << name;
            if (r.proxies.size() < static_cast<std::size_t>(truth + 3)) EXPECT_EQ(r.stop_reason, StopReason::fitted) << name;
            EXPECT_GE(score.accuracy, 0.97) << name << (irregular ? " irregular" : "");
            for (const ProxyResult& p : r.proxies) EXPECT_GE(p.faces, min_faces) << name << " region " << p.id;
        }
    }
    const Result example = test::approximate(example_mesh("turned_part"), counted(7));
    EXPECT_EQ(example.proxies.size(), 6u);
    EXPECT_EQ(example.stop_reason, StopReason::fitted);
    // Far above the count (50 on five surfaces), the pieces left over include rings of a
    // sphere's tessellation, one facet wide: exactly cones, so their own fits said they lay
    // on no sphere, and 23 regions were left at 20K faces. Judged against the sphere's own
    // faces instead, they go to it.
    for (const char* axle : {"axle:10000", "axle:20000"}) {
        const Result r = test::approximate(example_mesh(axle), counted(50));
        EXPECT_EQ(r.proxies.size(), 5u) << axle;
        EXPECT_EQ(r.stop_reason, StopReason::fitted) << axle;
    }
}

TEST(CadExtraction, AboveTheTrueCountGrowthStopsOnceInsertionsBuyNothing) {
    // The turned part is exact at a dozen proxies; asked for 50, the run went on inserting
    // up to 50 (pieces of exact surfaces, as good as whole), tried its teleports and merged
    // the pieces back: twice the Lloyd iterations for the same 6 surfaces. Three insertions
    // in a row that buy nothing, every region explained, end the growth.
    const Model model = make_model(example_mesh("turned_part:40000"));
    LloydOptions options;
    options.proxies = 50;
    Lloyd lloyd(model, options);
    std::size_t most = 0;
    while (lloyd.step()) most = std::max(most, lloyd.proxies().size());
    EXPECT_EQ(lloyd.stop_reason(), StopReason::fitted);
    EXPECT_EQ(lloyd.proxies().size(), 6u);
    EXPECT_LT(lloyd.rms(), 1e-4);  // the facets' sagitta; a region over two surfaces leaves 1e-2
    EXPECT_LT(most, 30u);  // 51 before (50, and one more for each teleport)
}

TEST(CadExtraction, NoInsertionSeedsAFaceTwice) {
    // An insertion batch seeds the charts no region explains first, then the regions that
    // err most, each at its worst face. That face could be one a chart's insertion had just
    // seeded: two seeds on one face, and the flooding left one of the proxies without a
    // face. It stayed so, reported as a region, until the finish fitted its empty face set
    // and the run failed ("cannot fit a region of zero area", a 3D printer part exported
    // by OpenSCAD). After every step each proxy must have a seed face of its own, on the
    // rounded plate's corpus cases at seed offsets that drew such batches.
    for (const CorpusCase& c : cad_corpus({"rounded_plate"}))
        for (double detail : {1.0, 0.4})
            for (std::uint64_t offset : {1, 2, 6}) {
                SCOPED_TRACE(c.variant + ", detail " + std::to_string(detail) + ", seed offset " + std::to_string(offset));
                PartOptions part_options = c.options;
                part_options.random_pose = true, part_options.detail = detail;
                const Part part = make_part(c.part, part_options);
                const Model model = make_model(part.mesh);
                LloydOptions options;
                options.seed = c.options.seed + offset;
                Lloyd lloyd(model, options);
                bool seeds_apart = true;
                while (seeds_apart && lloyd.step()) {
                    std::set<int> seeds;
                    for (const Proxy& p : lloyd.proxies()) seeds_apart = seeds_apart && p.seed >= 0 && seeds.insert(p.seed).second;
                }
                EXPECT_TRUE(seeds_apart) << "after iteration " << lloyd.iterations();
            }
}

TEST(CadExtraction, AutomaticallyTheFinishMergesPiecesOfSurfacesSeveralAtATime) {
    // Growth past a part's surfaces leaves pieces of them, which the finish merges back.
    // One pair per Lloyd stage, a part grown to a thousand regions (an 84K-face counter)
    // ran into the iteration cap; pairs that share no region now merge together, their
    // stage judged as one merge. The axle grows to 12 regions on its 5 surfaces: 7 stages
    // of one merge each before.
    const Model model = make_model(example_mesh("axle:20000"));
    Lloyd lloyd(model, LloydOptions{});
    std::size_t before = 0, most = 0, stages = 0;
    while (lloyd.step()) {
        const std::size_t count = lloyd.proxies().size();
        if (lloyd.last_operation() == Operation::merge) {
            ++stages;
            EXPECT_LT(count, before);
        }
        before = count, most = std::max(most, count);
    }
    EXPECT_EQ(lloyd.stop_reason(), StopReason::fitted);
    ASSERT_EQ(lloyd.proxies().size(), 5u);
    EXPECT_LT(lloyd.rms(), 1e-4);  // exact surfaces; a region over two leaves 1e-2
    EXPECT_GT(most, 8u);           // it did grow past its surfaces
    EXPECT_LT(stages, most - 5);   // fewer stages than merges
}

TEST(CadExtraction, AutomaticallyAnExactExportsHandfulsMergeSeveralAtATime) {
    // Regions of a handful of faces (fewer than min_quadric_faces) go to the neighbour they
    // cost least, once no two regions lie on one surface. One per Lloyd stage, a gear set of
    // 112 parts (43K faces) grown to 1 967 regions ran into the iteration cap with 730 of
    // them merged; on an exact tessellation several now merge together. The plate assembly
    // (exact, in its canonical pose) merges ten in one stage. A stage's merges are read off
    // the partition: a region made of two regions of the step before. (casting.off was the
    // case until 2026-11-29, three at once; since two faces in one plane are an exact plane
    // whatever the roughness beside them, fewer of its regions are handfuls, two at once.)
    const Model model = make_model(make_part("plate_assembly", PartOptions{}).mesh);
    Lloyd lloyd(model, LloydOptions{});
    ASSERT_TRUE(lloyd.features().exact);
    const int handful = LloydOptions{}.min_quadric_faces;
    std::vector<int> labels;
    std::vector<Proxy> proxies;
    int most = 0;  // handfuls merged by one stage that merged nothing else
    while (lloyd.step()) {
        if (lloyd.last_operation() == Operation::merge && !labels.empty()) {
            std::map<int, std::set<int>> from;
            for (std::size_t f = 0; f < labels.size(); ++f) from[lloyd.labels()[f]].insert(labels[f]);
            int pairs = 0, with_handful = 0;
            for (const auto& [region, before] : from) {
                if (before.size() < 2) continue;
                ++pairs;
                with_handful += std::any_of(before.begin(), before.end(), [&](int r) { return proxies[r].faces < handful; });
            }
            if (pairs == with_handful) most = std::max(most, pairs);
        }
        labels = lloyd.labels(), proxies = lloyd.proxies();
    }
    EXPECT_EQ(lloyd.stop_reason(), StopReason::fitted);
    EXPECT_GE(most, 3);
}

TEST(CadExtraction, ASplitAtTheStopLeavesNoRegionInPieces) {
    // At the stop, a region on two parts of its quadric gives its second part to a new
    // region; neither part need be connected. A region in pieces was left to the smoothing,
    // which gave each piece but the largest to the neighbour it shares most edges with:
    // Mendel90's motor bracket had a facet bending 23° off a plate's side, at either end of
    // it, and one went to the side, which the refit then typed a cylinder (projected RMS
    // 20 times its Lloyd partition's). Under noise the second part is mostly faces the noise
    // put there, which must not become regions either. Each case left a region in pieces.
    struct Case {
        std::string part;
        double detail;
        int proxies;  // 0: automatic
    };
    for (const Case& c : {Case{"l_bracket", 1, 9}, Case{"plate_assembly", 0.4, 0}, Case{"chamfered_box", 1, 26},
                          Case{"rolled_sheet", 0.4, 6}}) {
        SCOPED_TRACE(c.part);
        PartOptions po;
        po.detail = c.detail, po.noise = 0.002, po.random_pose = true;
        const Part part = make_part(c.part, po);
        const Result r = test::approximate(part.mesh, counted(c.proxies));
        const int regions = static_cast<int>(r.proxies.size());
        // Pieces that meet at a vertex are one: a split may take every other triangle of a
        // facet row (a chamfer's), which the smoothing joins.
        std::vector<int> root(part.mesh.face_count());
        std::function<int(int)> find = [&](int f) { return root[f] == f ? f : root[f] = find(root[f]); };
        std::map<std::pair<int, int>, int> at;  // (vertex, region) → a face
        for (int f = 0; f < part.mesh.face_count(); ++f) {
            root[f] = f;
            for (int v : part.mesh.triangles[f]) {
                const auto [it, first] = at.insert({{v, r.lloyd_face_labels[f]}, f});
                if (!first) root[find(f)] = find(it->second);
            }
        }
        std::map<int, std::set<int>> pieces;
        for (int f = 0; f < part.mesh.face_count(); ++f) pieces[r.lloyd_face_labels[f]].insert(find(f));
        for (const auto& [region, roots] : pieces) EXPECT_EQ(roots.size(), 1u) << "region " << region;
        // Nor did the noise's faces become regions: the count stays near the part's faces.
        if (c.proxies > 0) EXPECT_LE(regions, c.proxies + 2);
        else EXPECT_LE(regions, static_cast<int>(1.15 * part.surfaces.size()));
    }
}
