#include "fitting/distance.h"
#include "lloyd/engine.h"
#include "io/mesh_io.h"
#include "geometry/model.h"
#include "shapes.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <map>
#include <set>

using namespace vqsa;

namespace {

// Fraction of the area whose region is, by majority, the region of its true patch.
double area_on_true_patch(const Engine& engine, const Shape& shape) {
    const Model& m = engine.model();
    std::map<std::pair<int, int>, double> overlap;  // (region, patch) → area
    for (int f = 0; f < m.face_count(); ++f) overlap[{engine.face_labels()[f], shape.patch[f]}] += m.areas[f];
    std::map<int, std::pair<double, int>> best;  // region → (area, patch)
    for (const auto& [key, area] : overlap)
        if (area > best[key.first].first) best[key.first] = {area, key.second};
    double right = 0;
    std::set<int> patches_used;
    for (const auto& [region, winner] : best) {
        right += winner.first;
        patches_used.insert(winner.second);
    }
    // Each patch must have its own region, else a single region could claim everything.
    return patches_used.size() == best.size() ? right / m.total_area : 0.0;
}

bool regions_connected(const Engine& engine) {
    const Model& m = engine.model();
    const std::vector<int>& labels = engine.face_labels();
    std::vector<int> seen(m.face_count(), 0);
    std::set<int> visited_regions;
    for (int f = 0; f < m.face_count(); ++f) {
        if (seen[f]) continue;
        if (!visited_regions.insert(labels[f]).second) return false;  // a second piece of a region
        std::vector<int> stack{f};
        seen[f] = 1;
        while (!stack.empty()) {
            const int g = stack.back();
            stack.pop_back();
            for (int e = m.graph.begin(g); e < m.graph.end(g); ++e) {
                const int n = m.graph.neighbor[e];
                if (!seen[n] && labels[n] == labels[g]) seen[n] = 1, stack.push_back(n);
            }
        }
    }
    return true;
}

EngineOptions with_proxies(int n, std::uint64_t seed = 1) {
    EngineOptions o;
    o.proxies = n;
    o.seed = seed;
    return o;
}

}  // namespace

TEST(Engine, CapsuleSplitsIntoCylinderAndTwoCaps) {
    std::mt19937 rng(2);
    for (int pose = 0; pose < 3; ++pose) {
        Shape capsule = make_capsule(0.7, 2.0, 64, 16);
        transform(capsule.mesh, test::random_rotation(rng), Vec3(1, -2, 0.5) * pose);
        Engine engine(capsule.mesh, with_proxies(3, pose + 1));
        engine.run();
        ASSERT_EQ(engine.proxies().size(), 3u);
        EXPECT_GE(area_on_true_patch(engine, capsule), 0.98) << "pose " << pose;
        EXPECT_TRUE(regions_connected(engine));
    }
}

TEST(Engine, ClosedCylinderSplitsIntoSideAndTwoDisks) {
    std::mt19937 rng(4);
    for (int pose = 0; pose < 3; ++pose) {
        Shape cylinder = make_closed_cylinder(0.5, 1.5, 64, 12);
        transform(cylinder.mesh, test::random_rotation(rng), Vec3(-3, 0.5, 2) * pose);
        Engine engine(cylinder.mesh, with_proxies(3, pose + 7));
        engine.run();
        ASSERT_EQ(engine.proxies().size(), 3u);
        EXPECT_GE(area_on_true_patch(engine, cylinder), 0.98) << "pose " << pose;
        int planes = 0;
        for (int i = 0; i < 3; ++i) planes += engine.classification(i).type == QuadricType::plane;
        EXPECT_EQ(planes, 2);
    }
}

TEST(Engine, SameSeedSameLabelsAndEveryComponentGetsAProxy) {
    // Three separate parts: two capsules and a closed cylinder, side by side.
    PolygonSoup soup;
    append(soup, make_capsule(0.5, 1, 32, 8).mesh);
    append(soup, make_capsule(0.3, 2, 32, 8).mesh, Vec3(3, 0, 0));
    append(soup, make_closed_cylinder(0.4, 1, 32, 6).mesh, Vec3(0, 4, 0));
    const Mesh mesh = build_mesh(soup);

    Engine first(mesh, with_proxies(8, 42)), second(mesh, with_proxies(8, 42));
    first.run();
    second.run();
    EXPECT_EQ(first.model().component_count, 3);
    EXPECT_EQ(first.labels(), second.labels());
    std::set<int> regions_per_component[3];
    for (int f = 0; f < first.model().face_count(); ++f)
        regions_per_component[first.model().component[f]].insert(first.face_labels()[f]);
    for (const auto& regions : regions_per_component) EXPECT_GE(regions.size(), 1u);
    EXPECT_TRUE(regions_connected(first));

    // Fewer proxies than components still covers every component.
    Engine few(mesh, with_proxies(1));
    few.run();
    EXPECT_EQ(few.proxies().size(), 3u);
    for (int l : few.labels()) EXPECT_GE(l, 0);
}

TEST(Engine, FandiskReachesTwentyTwoProxiesWithConnectedRegions) {
    const Mesh mesh = read_mesh_file(test::shared_mesh("fandisk.off"));
    int insertions = 0, events = 0;
    Engine engine(mesh, with_proxies(22));
    engine.run([&](const ProgressEvent& e, const Engine& eng) {
        ++events;
        insertions += e.phase == Phase::insert;
        EXPECT_EQ(e.proxies, static_cast<int>(eng.proxies().size()));
        return true;
    });
    EXPECT_EQ(engine.stop_reason(), StopReason::proxies);
    EXPECT_EQ(engine.proxies().size(), 22u);
    EXPECT_GT(insertions, 10);
    EXPECT_GT(events, insertions);
    EXPECT_TRUE(regions_connected(engine));
    // Planar VSA with 80 proxies reaches about 1.4e-3 of the diagonal; quadrics at 22 do much better.
    EXPECT_LT(engine.rms(), 1.5e-3);
    const std::vector<int> labels = engine.labels();
    ASSERT_EQ(labels.size(), 12946u);
    for (int l : labels) ASSERT_TRUE(l >= 0 && l < 22);
}

TEST(Engine, StopsOnToleranceAndReportsIt) {
    Shape capsule = make_capsule(0.7, 2.0, 48, 12);
    EngineOptions o;
    o.tolerance = 1e-3;
    Engine engine(capsule.mesh, o);
    engine.run();
    EXPECT_EQ(engine.stop_reason(), StopReason::tolerance);
    EXPECT_LE(engine.rms(), 1e-3);
}

TEST(Engine, CancelFromTheCallbackStopsWithAConsistentPartition) {
    Shape capsule = make_capsule(0.7, 2.0, 48, 12);
    Engine engine(capsule.mesh, with_proxies(12));
    int calls = 0;
    engine.run([&](const ProgressEvent&, const Engine&) { return ++calls < 5; });
    EXPECT_EQ(engine.stop_reason(), StopReason::cancelled);
    EXPECT_EQ(calls, 5);
    for (int l : engine.face_labels()) EXPECT_TRUE(l >= 0 && l < static_cast<int>(engine.proxies().size()));
}

TEST(Engine, IterationCapIsHonoured) {
    Shape capsule = make_capsule(0.7, 2.0, 48, 12);
    EngineOptions o = with_proxies(30);
    o.max_iterations = 7;
    Engine engine(capsule.mesh, o);
    engine.run();
    EXPECT_EQ(engine.stop_reason(), StopReason::max_iterations);
    EXPECT_LE(engine.iterations(), 8);
}

TEST(Engine, RejectsBadOptions) {
    Shape capsule = make_capsule(0.7, 2.0, 16, 4);
    EngineOptions none;
    EXPECT_THROW(Engine(capsule.mesh, none), std::invalid_argument);
    EngineOptions negative;
    negative.tolerance = -1;
    EXPECT_THROW(Engine(capsule.mesh, negative), std::invalid_argument);
    EXPECT_THROW(Engine(capsule.mesh, with_proxies(1000000)), std::invalid_argument);
}

TEST(Engine, ResultsAreInInputCoordinates) {
    // The same shape, scaled and moved: quadrics follow, relative errors do not change.
    Shape a = make_closed_cylinder(0.5, 1.5, 48, 8), b = a;
    transform(b.mesh, Eigen::Matrix3d::Identity() * 1000.0, Vec3(1e5, -2e5, 3e5));
    Engine ea(a.mesh, with_proxies(3)), eb(b.mesh, with_proxies(3));
    ea.run();
    eb.run();
    // The same partition (rounding may renumber the regions).
    std::map<int, int> to_b;
    for (int f = 0; f < ea.model().face_count(); ++f) {
        const auto [it, inserted] = to_b.try_emplace(ea.face_labels()[f], eb.face_labels()[f]);
        ASSERT_EQ(it->second, eb.face_labels()[f]) << "face " << f;
    }
    ASSERT_EQ(to_b.size(), 3u);
    EXPECT_NEAR(ea.rms(), eb.rms(), 1e-9);
    for (int i = 0; i < 3; ++i) {
        const Classification ca = ea.classification(i), cb = eb.classification(to_b[i]);
        EXPECT_EQ(ca.type, cb.type);
        if (ca.type == QuadricType::cylinder) EXPECT_NEAR(cb.radius, 1000 * ca.radius, 1e-6 * cb.radius);
        // Every input vertex of the region satisfies the input-frame quadric.
        const Quadric q = eb.input_quadric(to_b[i]);
        for (int f = 0; f < eb.model().face_count(); f += 37)
            if (eb.face_labels()[f] == to_b[i])
                EXPECT_LT(taubin_distance(q, b.mesh.vertices[b.mesh.triangles[f][0]]), 1e-3 * 1000);
    }
}

TEST(Engine, ARegionOnTwoPlanesIsSplit) {
    // An open "L": two perpendicular rectangles sharing an edge. One quadric fits
    // both exactly, as a pair of intersecting planes: invalid, so it must be split.
    PolygonSoup soup;
    const Shape floor = make_grid([](double u, double v) { return Vec3(u, v, 0); }, 0, 1, 0, 1, 20, 20);
    const Shape wall = make_grid([](double u, double v) { return Vec3(u, 0, v); }, 0, 1, 0, 1, 20, 20);
    append(soup, floor.mesh);
    append(soup, wall.mesh);
    const Mesh mesh = build_mesh(soup);
    ASSERT_EQ(make_model(mesh).component_count, 1);

    bool split_seen = false;
    Engine engine(mesh, with_proxies(2));
    engine.run([&](const ProgressEvent& e, const Engine&) {
        split_seen |= e.phase == Phase::split;
        return true;
    });
    EXPECT_TRUE(split_seen);
    ASSERT_EQ(engine.proxies().size(), 2u);
    // Each plane is one region, and both are planes.
    const std::vector<int>& labels = engine.face_labels();
    const int floor_faces = static_cast<int>(floor.mesh.triangles.size());
    for (int f = 0; f < engine.model().face_count(); ++f) EXPECT_EQ(labels[f], labels[f < floor_faces ? 0 : floor_faces]);
    EXPECT_NE(labels[0], labels[floor_faces]);
    for (int i = 0; i < 2; ++i) EXPECT_EQ(engine.classification(i).type, QuadricType::plane);
    EXPECT_LT(engine.rms(), 1e-9);
}

TEST(Engine, TeleportsNeverLeaveTheEnergyHigher) {
    const Mesh mesh = read_mesh_file(test::shared_mesh("fandisk.off"));
    double before_teleports = -1;
    int teleports = 0;
    Engine engine(mesh, with_proxies(22));
    engine.run([&](const ProgressEvent& e, const Engine& eng) {
        teleports += e.phase == Phase::teleport;
        // The last converged state at the target count, before any teleport.
        if (e.phase == Phase::lloyd && e.proxies == 22 && teleports == 0) before_teleports = eng.energy();
        return true;
    });
    ASSERT_GT(teleports, 0);
    ASSERT_GT(before_teleports, 0);
    EXPECT_LE(engine.energy(), before_teleports);
}

TEST(Engine, NonManifoldEdgesAndOpenBoundariesWork) {
    // Three fins on one edge (a non-manifold edge), each an open square sheet.
    PolygonSoup soup;
    for (int k = 0; k < 3; ++k) {
        const double a = 2 * M_PI * k / 3;
        const Vec3 out(std::cos(a), std::sin(a), 0);
        append(soup, make_grid([&](double u, double v) -> Vec3 { return Vec3(0, 0, v) + u * out; }, 0, 1, 0, 1, 8, 8).mesh);
    }
    const Mesh mesh = build_mesh(soup);
    const Model model = make_model(mesh);
    ASSERT_EQ(model.component_count, 1);
    Engine engine(mesh, with_proxies(3));
    engine.run();
    ASSERT_EQ(engine.proxies().size(), 3u) << stop_reason_name(engine.stop_reason()) << " rms " << engine.rms();
    EXPECT_TRUE(regions_connected(engine));
    // Each fin is a plane of its own.
    const int per_fin = static_cast<int>(mesh.triangles.size()) / 3;
    std::set<int> fin_labels;
    for (int k = 0; k < 3; ++k) {
        const int label = engine.face_labels()[k * per_fin];
        fin_labels.insert(label);
        for (int f = k * per_fin; f < (k + 1) * per_fin; ++f) EXPECT_EQ(engine.face_labels()[f], label);
    }
    EXPECT_EQ(fin_labels.size(), 3u);
    EXPECT_LT(engine.rms(), 1e-9);
}
