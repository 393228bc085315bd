// Distortion-minimising flooding (lloyd/flooding.h): the order it takes faces in, the
// determinism everything else relies on, fixed faces and creases.
#include "lloyd/flooding.h"
#include "shapes.h"

#include <gtest/gtest.h>

#include <algorithm>

using namespace vqsa;

namespace {

// A sheet bent along u = 0.5: flat (z = 0) for u < 0.5, rising at 45° beyond. The grid
// has a line at u = 0.5, so no face straddles the fold.
struct BentSheet {
    Mesh mesh = make_grid([](double u, double v) { return Vec3(u, v, std::max(0.0, u - 0.5)); }, 0, 1, 0, 1, 16, 8).mesh;
    Model model = make_model(mesh);

    bool right(int face) const { return model.frame.to_input(model.barycentres[face]).x() > 0.5; }
    Vec3 unit(const Vec3& input) const { return model.frame.to_unit(input); }
    // The face whose barycentre is nearest to p (input coordinates).
    int face_near(const Vec3& p) const {
        int best = 0;
        for (int f = 1; f < model.face_count(); ++f)
            if ((model.barycentres[f] - unit(p)).norm() < (model.barycentres[best] - unit(p)).norm()) best = f;
        return best;
    }
    std::vector<char> fold_creases() const {
        std::vector<char> crease(model.graph.neighbor.size(), 0);
        for (int f = 0; f < model.face_count(); ++f)
            for (int e = model.graph.begin(f); e < model.graph.end(f); ++e) crease[e] = right(f) != right(model.graph.neighbor[e]);
        return crease;
    }
    std::vector<int> flood(const std::vector<Quadric>& proxies, const std::vector<int>& seeds,
                           const std::vector<char>* crease = nullptr, std::vector<int> labels = {}) const {
        if (labels.empty()) labels.assign(model.face_count(), -1);
        FaceErrors errors;
        errors.reset(model, proxies);
        Flooding flooding;
        flooding.run(model, errors, seeds, labels, crease);
        return labels;
    }
};

const Vec3 kUp(0, 0, 1);
const Vec3 kRightNormal = Vec3(-1, 0, 1).normalized();

}  // namespace

TEST(Flooding, EachFaceGoesToThePlaneItLiesOn) {
    const BentSheet sheet;
    const std::vector<Quadric> planes = {Quadric::plane(kUp, sheet.unit({0.25, 0.5, 0})),
                                         Quadric::plane(kRightNormal, sheet.unit({0.75, 0.5, 0.25}))};
    // The flat proxy's seed is next to the fold, the other's at the far end: a breadth-first
    // flood would give the flat proxy half the slope; this one grows every region over its
    // zero-error faces before any face of positive error is taken.
    const std::vector<int> labels = sheet.flood(planes, {sheet.face_near({0.45, 0.5, 0}), sheet.face_near({0.98, 0.5, 0.48})});
    for (int f = 0; f < sheet.model.face_count(); ++f) ASSERT_EQ(labels[f], sheet.right(f) ? 1 : 0) << "face " << f;
}

TEST(Flooding, TiesAreBrokenTheSameWayEveryTime) {
    // Both proxies are the same plane under the flat half: every error ties there, and the
    // heap's total order (error, face, proxy) decides alone.
    const BentSheet sheet;
    const Quadric flat = Quadric::plane(kUp, sheet.unit({0.25, 0.5, 0}));
    const std::vector<int> seeds = {sheet.face_near({0.1, 0.1, 0}), sheet.face_near({0.1, 0.9, 0})};
    const std::vector<int> first = sheet.flood({flat, flat}, seeds);
    for (int run = 0; run < 3; ++run) EXPECT_EQ(sheet.flood({flat, flat}, seeds), first);
    // Every face is reached, by both proxies, and each region is connected.
    EXPECT_EQ(std::count(first.begin(), first.end(), -1), 0);
    for (int p = 0; p < 2; ++p) {
        EXPECT_GT(std::count(first.begin(), first.end(), p), 0);
        std::vector<char> seen(first.size(), 0);
        std::vector<int> stack = {seeds[p]};
        seen[seeds[p]] = 1;
        int reached = 0;
        while (!stack.empty()) {
            const int f = stack.back();
            stack.pop_back();
            ++reached;
            for (int e = sheet.model.graph.begin(f); e < sheet.model.graph.end(f); ++e) {
                const int n = sheet.model.graph.neighbor[e];
                if (!seen[n] && first[n] == p) seen[n] = 1, stack.push_back(n);
            }
        }
        EXPECT_EQ(reached, std::count(first.begin(), first.end(), p)) << "region " << p << " is not connected";
    }
}

TEST(Flooding, FixedFacesBlockTheFlood) {
    // A wall of fixed faces across the sheet at u ≈ 0.5: one seed on the left reaches
    // nothing beyond it.
    const BentSheet sheet;
    std::vector<int> labels(sheet.model.face_count(), -1);
    for (int f = 0; f < sheet.model.face_count(); ++f) {
        const double x = sheet.model.frame.to_input(sheet.model.barycentres[f]).x();
        if (x > 0.5 - 1.0 / 16 && x < 0.5) labels[f] = 7;
    }
    const Quadric flat = Quadric::plane(kUp, sheet.unit({0.25, 0.5, 0}));
    const std::vector<int> out = sheet.flood({flat}, {sheet.face_near({0.02, 0.5, 0})}, nullptr, labels);
    for (int f = 0; f < sheet.model.face_count(); ++f) {
        const double x = sheet.model.frame.to_input(sheet.model.barycentres[f]).x();
        if (labels[f] == 7) EXPECT_EQ(out[f], 7);
        else EXPECT_EQ(out[f], x < 0.5 ? 0 : -1) << "face " << f;
    }
}

TEST(Flooding, FacesAcrossACreaseComeAfterTheRest) {
    // Proxy 0 is the flat half's plane; proxy 1, seeded at the right end, is a plane that
    // fits the right half worse than proxy 0 does. Without creases proxy 0 spills over the
    // fold; with the fold a crease, proxy 1 reaches every right face without crossing one
    // and takes them all.
    const BentSheet sheet;
    const std::vector<Quadric> planes = {Quadric::plane(kUp, sheet.unit({0.25, 0.5, 0})),
                                         Quadric::plane(Vec3(1, 0, 1).normalized(), sheet.unit({0.5, 0.5, 0}))};
    const std::vector<int> seeds = {sheet.face_near({0.02, 0.5, 0}), sheet.face_near({0.98, 0.5, 0.48})};
    const std::vector<int> plain = sheet.flood(planes, seeds);
    int spilled = 0;
    for (int f = 0; f < sheet.model.face_count(); ++f) spilled += sheet.right(f) && plain[f] == 0;
    EXPECT_GT(spilled, 0);
    const std::vector<char> crease = sheet.fold_creases();
    const std::vector<int> creased = sheet.flood(planes, seeds, &crease);
    for (int f = 0; f < sheet.model.face_count(); ++f) ASSERT_EQ(creased[f], sheet.right(f) ? 1 : 0) << "face " << f;
}
