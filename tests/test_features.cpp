// Creases and roughness (geometry/features.h): what a tessellation's facets count as.
#include "cad_parts.h"
#include "geometry/features.h"
#include "geometry/model.h"
#include "io/mesh.h"
#include "shapes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

using namespace vqsa;

namespace {

// The small rounded plate beside its slab, in a random pose, under noise of σ `noise` of the
// whole's diagonal. The slab's faces are the part's last six: its top, bottom and sides.
struct PlateAndSlab {
    Part part;
    Model model;
    Features features;
    int first_slab_face;
};

PlateAndSlab noisy_rounded_plate(double detail, double noise) {
    PartOptions options;
    options.detail = detail, options.noise = noise, options.random_pose = true;
    PlateAndSlab out{make_part("rounded_plate", options), {}, {}, 0};
    out.model = make_model(out.part.mesh);
    out.features = detect_features(out.model);
    out.first_slab_face = static_cast<int>(out.part.surfaces.size()) - 6;
    return out;
}

}  // namespace

TEST(Features, FacetsOfACoarseCylinderAreChordsNotChamferEdges) {
    // A 12-gon cylinder, as a CAD export with a coarse angular tolerance meshes a small hole:
    // its facets bend by 30°, more than half the crease angle. Each bend has a bend beside
    // it, the same way, one facet over: chords of an arc, so the facets stand off the
    // cylinder by their sagitta and their roughness says so (before: only the chart's
    // roughness, ~0 on a clean mesh, and a coarse hole's pieces could never merge).
    const double radius = 0.5, height = 1.5;
    const int around = 12;
    const Model model = make_model(make_closed_cylinder(radius, height, around, 4).mesh);
    const Features features = detect_features(model);
    const double unit = 1 / model.frame.scale;  // the unit frame: the longest bounding-box side is 1
    const double sagitta = radius * (1 - std::cos(M_PI / around)) * unit;
    int side = 0;
    for (int f = 0; f < model.face_count(); ++f) {
        const Vec3 n = (model.points[model.triangles[f][1]] - model.points[model.triangles[f][0]])
                           .cross(model.points[model.triangles[f][2]] - model.points[model.triangles[f][0]]);
        if (std::abs(n.normalized().z()) > 0.5) continue;  // a cap
        ++side;
        EXPECT_GT(features.roughness[f], 0.25 * sagitta) << "face " << f;
        EXPECT_LT(features.roughness[f], 2 * sagitta) << "face " << f;
    }
    EXPECT_GT(side, 0);
}

TEST(Features, RoughnessDoesNotDependOnThePose) {
    // A face in one plane with a neighbour (as no noise leaves it) beside a bend takes the
    // sag of the facet across the bend, not of its own width. It was found flat only when
    // the two normals were bitwise equal, as an axis-aligned export's are: turned, the
    // rolled sheet's two long faces took a 7° turn over their whole width, 30 times the
    // sag, and the procedural parts' random poses measured another mesh than their own.
    for (const char* name : {"rolled_sheet", "plate_assembly"}) {
        for (const bool irregular : {false, true}) {
            std::vector<double> roughness[2];
            for (const bool pose : {false, true}) {
                PartOptions options;
                options.random_pose = pose, options.irregular = irregular;
                const Model model = make_model(make_part(name, options).mesh);
                const Features features = detect_features(model);
                for (double r : features.roughness) roughness[pose].push_back(r * model.frame.scale);
            }
            ASSERT_EQ(roughness[0].size(), roughness[1].size());
            for (std::size_t f = 0; f < roughness[0].size(); ++f)
                ASSERT_NEAR(roughness[0][f], roughness[1][f], 1e-3 * roughness[0][f] + 1e-9)
                    << name << (irregular ? " irregular" : "") << ", face " << f;
        }
    }
}

TEST(Features, ArcFacetsAreTheFacetsOfCurvedSurfacesNotFlatFacesBetweenCreases) {
    // A coarse arc's facets are exact planes, each off its arc by its sag; a face of a few
    // triangles between creases is an exact plane and no facet (Lloyd::merge_handful tells
    // the two apart by this flag). A tube's walls, a hex nut's bore and countersinks are
    // facets; their flat faces, and every face of a box whose edges are 45° chamfers, are not.
    for (const std::string name : {"tube", "hex_nut", "chamfered_box"})
        for (double detail : {1.0, 0.4}) {
            SCOPED_TRACE(name + ", detail " + std::to_string(detail));
            PartOptions options;
            options.detail = detail, options.random_pose = true;
            const Part part = make_part(name, options);
            const Features features = detect_features(make_model(part.mesh));
            int flat = 0, flagged_flat = 0, curved = 0, flagged_curved = 0;
            for (std::size_t t = 0; t < part.face.size(); ++t) {
                const bool plane = part.surfaces[part.face[t]].type == QuadricType::plane;
                (plane ? flat : curved) += 1;
                (plane ? flagged_flat : flagged_curved) += features.arc_facet[t];
            }
            EXPECT_GT(flat, 0);
            EXPECT_EQ(flagged_flat, 0);
            EXPECT_EQ(flagged_curved, curved);
        }
}

TEST(Features, AnInexactCoarseTessellationKeepsItsCreaseCharts) {
    // A coarse hex nut (168 triangles; half its links bend by more than 21°, beyond the
    // normal filter's range) as a decimated or re-exported CAD mesh has it: the top face
    // exact, every other vertex off by up to 1e-5 of the size, so that less than half the
    // faces lie in one plane with a neighbour to the stored precision and the mesh is no
    // exact tessellation. Its bends were then read as noise of the faces' own width (which
    // smooths the normals over rings of faces), and one of its seven crease charts went:
    // a robot's tool flange, 19 % of its faces exactly flat, kept 7 of its 340 charts and
    // ended with its face, bore and 40 holes in one region. Such noise leaves no two faces
    // in one plane to the stored precision.
    PartOptions options;
    options.detail = 0.25;
    const Part exact = make_part("hex_nut", options);
    Part inexact = exact;
    double top = -1e300;
    for (const Vec3& p : inexact.mesh.vertices) top = std::max(top, p.z());
    for (std::size_t i = 0; i < inexact.mesh.vertices.size(); ++i) {
        Vec3& p = inexact.mesh.vertices[i];
        const double k = static_cast<double>(i) + 1;
        if (p.z() < top) p += 1e-5 * Vec3(std::sin(12.9898 * k), std::sin(78.233 * k), std::sin(37.719 * k));
    }
    const Features reference = detect_features(make_model(exact.mesh));
    const Features features = detect_features(make_model(inexact.mesh));
    ASSERT_TRUE(reference.exact);
    EXPECT_FALSE(features.exact);
    EXPECT_EQ(features.chart_count, reference.chart_count);
    EXPECT_EQ(reference.chart_count, 7);
}

TEST(Features, AFaceWideAgainstTheNoiseKeepsItsOwnNormal) {
    // Noise of the faces' own size on the small rounded plate makes the filter start each
    // face from the mean normal of a patch around it; its rings were set once for the whole
    // mesh, by the median face, so the slab beside the plate, its triangles hundreds of times
    // wider than the noise, took patches of six rings too: its top, bottom and sides one
    // normal, one chart, and Lloyd fitted the slab as one elliptic cylinder.
    const auto [part, model, features, first_slab_face] = noisy_rounded_plate(1, 0.001);
    ASSERT_EQ(static_cast<std::size_t>(model.face_count()), part.face.size());
    int slab = 0;
    for (int f = 0; f < model.face_count(); ++f) {
        if (part.face[f] < first_slab_face) continue;
        ++slab;
        EXPECT_GT(features.normals[f].dot(area_normal(model, f).normalized()), std::cos(10 * M_PI / 180)) << "face " << f;
    }
    EXPECT_EQ(slab, 48);
}

TEST(Features, APartWithoutANoiseOfItsOwnTakesWhatItsPlanesLeave) {
    // A slab beside a small noisy plate, apart from it: no vertex of the slab (its faces a
    // dozen triangles or two) has the two rings of a local fit, so its charts took the
    // whole mesh's median, read on the plate, whose facets the noise garbles across its
    // creases: 4.5 σ, within which one elliptic cylinder explained the whole slab.
    const double noise = 0.001;
    const auto [part, model, features, first_slab_face] = noisy_rounded_plate(0.6, noise);
    const double sigma = noise * bounding_box(part.mesh).diagonal();
    int slab = 0;
    for (int f = 0; f < model.face_count(); ++f) {
        if (part.face[f] < first_slab_face) continue;
        ++slab;
        // A locally exact surface leaves 0.9 σ; the limit, from 16 degrees of freedom, is
        // 1.3 times the estimate.
        EXPECT_LT(features.roughness[f] * model.frame.scale, 1.5 * sigma) << "face " << f;
        EXPECT_GT(features.roughness[f] * model.frame.scale, 0.5 * sigma) << "face " << f;
    }
    EXPECT_EQ(slab, 32);
}

TEST(Features, AThinStripBetweenWideFacesKeepsItsOwnNormal) {
    // Noise of the small rounded plate's facets' size (σ 0.2 % of the whole's diagonal)
    // makes the filter start every narrow face from the mean normal of the most consistent
    // patch near it. The slab's sides are two triangles each, 0.5 tall against the slab's
    // 7 × 5: the most consistent patch near them lay on the top or the bottom, 90° away, and
    // the top's chart took a triangle of each of two sides. A side's own normal is within a
    // few degrees of the truth: each slab face must be charts of its own.
    const auto [part, model, features, first_slab_face] = noisy_rounded_plate(0.4, 0.002);
    std::vector<int> face_of_chart(features.chart_count, -1);
    int slab = 0;
    for (int f = 0; f < model.face_count(); ++f) {
        if (part.face[f] < first_slab_face) continue;
        ++slab;
        int& owner = face_of_chart[features.chart[f]];
        if (owner < 0) owner = part.face[f];
        EXPECT_EQ(owner, part.face[f]) << "triangle " << f << " shares a chart with another face";
    }
    EXPECT_EQ(slab, 32);
}

TEST(Features, AnExportMostOfWhoseAreaIsFlatIsExactHoweverFineItsDetail) {
    // A CAD export meshes a plane with the fewest triangles its outline allows and curved
    // detail as finely as its tolerance asks: Voron's z belt clip has 39 % of its faces but
    // 87 % of its area in one plane with a neighbour, its belt teeth and chamfers the rest.
    // Counted by faces it was no exact tessellation, its charts' noise was read off where
    // its surfaces meet (1.8e-3 of its size, beyond `precision`: a noisy mesh), and its
    // automatic run stopped at 24 regions, several over three planes each. A coarse
    // chamfered box beside a finely meshed saddle (z = xy, no two of its faces in one
    // plane) is the same mix: a handful of flat faces holding most of the area.
    PartOptions options;
    options.detail = 0.25;
    const Mesh part = make_part("chamfered_box", options).mesh;
    const BoundingBox box = bounding_box(part);
    PolygonSoup soup;
    append(soup, part);
    const double size = box.diagonal();
    append(soup,
           make_grid([&](double u, double v) { return Vec3(u, v, u * v / size); }, 0, 0.3 * size, 0, 0.3 * size, 40, 40)
               .mesh,
           Vec3(box.max.x() + 0.2 * size, box.min.y(), box.min.z()));
    const Mesh mesh = build_mesh(soup);
    const Model model = make_model(mesh);
    int flat_faces = 0;
    double flat_area = 0;
    for (int f = 0; f < model.face_count(); ++f)
        if (coplanar_with_a_neighbour(model, f)) ++flat_faces, flat_area += model.areas[f];
    ASSERT_LT(2 * flat_faces, model.face_count());
    ASSERT_GT(2 * flat_area, model.total_area);
    EXPECT_TRUE(detect_features(model).exact);

    // Noise leaves no face in one plane with another, however the area lies.
    Mesh noisy = mesh;
    add_normal_noise(noisy, 1e-5, 1);
    EXPECT_FALSE(detect_features(make_model(noisy)).exact);
}
