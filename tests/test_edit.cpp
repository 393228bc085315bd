// Edits of a finished result (edit/edit.h, Pipeline::edit): each operation on the
// procedural CAD corpus fixes the case it is meant for; locks hold; undo, redo and replay
// give back identical labels; edits that do not apply say why and change nothing.
#include "cad_parts.h"
#include "edit/edit.h"
#include "ground_truth.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <memory>
#include <set>

using namespace vqsa;

namespace {

Options without_projection(int proxies) {
    Options o = test::with_proxies(proxies);
    o.project = false;
    return o;
}

Result finish(Pipeline& p) {
    p.run();
    return p.result();
}

Result edited(Pipeline& p, const Edit& e) {
    p.edit(e);
    return finish(p);
}

// Pairs of regions (a < b) that share an edge.
std::set<std::pair<int, int>> adjacent_pairs(const Mesh& mesh, const std::vector<int>& labels) {
    std::map<std::pair<int, int>, int> first;  // edge → face
    std::set<std::pair<int, int>> pairs;
    for (int f = 0; f < static_cast<int>(mesh.triangles.size()); ++f)
        for (int k = 0; k < 3; ++k) {
            const int u = mesh.triangles[f][k], v = mesh.triangles[f][(k + 1) % 3];
            const auto [it, added] = first.emplace(std::minmax(u, v), f);
            if (!added && labels[it->second] != labels[f])
                pairs.insert(std::minmax(labels[it->second], labels[f]));
        }
    return pairs;
}

// A kept face (model order) of true face `face`, in the input's order, away from its edges
// (the middle one in index order).
int input_face_on(const Part& part, int face) {
    std::vector<int> faces;
    for (int t = 0; t < static_cast<int>(part.face.size()); ++t)
        if (part.face[t] == face) faces.push_back(t);
    return part.mesh.source_face[faces[faces.size() / 2]];
}

// The first region matched (score.face_of) to a true face of `type`, or -1.
int region_on(const Part& part, const PartitionScore& score, int regions, QuadricType type) {
    for (int i = 0; i < regions; ++i)
        if (score.face_of[i] >= 0 && part.surfaces[score.face_of[i]].type == type) return i;
    return -1;
}

Part posed(const std::string& name, double noise = 0) {
    PartOptions o;
    o.random_pose = true;
    o.seed = 5;
    o.noise = noise;
    return make_part(name, o);
}

}  // namespace

// A region that spans a plane and the cylinder beside it, split at a face of the
// cylinder, gives both faces back; so does a split at the region's worst face.
TEST(Edit, SplitSeparatesARegionSpanningTwoFaces) {
    const Part part = posed("box_boss_hole");
    const int truth = static_cast<int>(part.surfaces.size());
    Pipeline p(part.mesh, without_projection(truth));
    const Result r = finish(p);
    const PartitionScore score = score_partition(part, r.face_labels, truth);
    ASSERT_GE(score.accuracy, 0.97);
    int plane = -1, cylinder = -1;
    for (const auto& [a, b] : adjacent_pairs(part.mesh, r.face_labels))
        for (const auto& [x, y] : {std::pair{a, b}, std::pair{b, a}})
            if (plane < 0 && r.proxies[x].type == QuadricType::plane && r.proxies[y].type == QuadricType::cylinder)
                plane = x, cylinder = y;
    ASSERT_GE(plane, 0);
    const int cylinder_face = score.face_of[cylinder];

    const Result merged = edited(p, Edit::merge(plane, cylinder));
    ASSERT_EQ(merged.proxies.size(), r.proxies.size() - 1);
    const int region = plane < cylinder ? plane : plane - 1;
    EXPECT_LT(score_partition(part, merged.face_labels, truth - 1).accuracy, 0.97);
    const Result split = edited(p, Edit::split(region, input_face_on(part, cylinder_face)));
    ASSERT_EQ(static_cast<int>(split.proxies.size()), truth);
    EXPECT_GE(score_partition(part, split.face_labels, truth).accuracy, 0.97);
    EXPECT_EQ(split.proxies[region].type, QuadricType::plane);
    EXPECT_EQ(split.proxies.back().type, QuadricType::cylinder);
    EXPECT_EQ(two_part_regions(part.mesh, split), 0);

    ASSERT_TRUE(p.undo());
    const Result at_worst = edited(p, Edit::split(region));
    EXPECT_GE(score_partition(part, at_worst.face_labels, truth).accuracy, 0.97);
}

// Two regions on one true cylinder (a split of it), merged, make one cylinder of the true
// radius.
TEST(Edit, MergeOfTwoPiecesOfACylinderIsOneCylinder) {
    const Part part = posed("stepped_shaft", 0.002);
    const int truth = static_cast<int>(part.surfaces.size());
    Pipeline p(part.mesh, without_projection(truth));
    const Result r = finish(p);
    const PartitionScore score = score_partition(part, r.face_labels, truth);
    const int cylinder = region_on(part, score, truth, QuadricType::cylinder);
    ASSERT_GE(cylinder, 0);
    const TrueSurface& s = part.surfaces[score.face_of[cylinder]];

    const Result split = edited(p, Edit::split(cylinder, input_face_on(part, score.face_of[cylinder])));
    ASSERT_EQ(static_cast<int>(split.proxies.size()), truth + 1);
    const int pieces[2] = {split.proxies[cylinder].faces, split.proxies.back().faces};
    EXPECT_GE(std::min(pieces[0], pieces[1]), r.proxies[cylinder].faces / 10) << pieces[0] << " + " << pieces[1];

    const Result merged = edited(p, Edit::merge(cylinder, truth));
    ASSERT_EQ(static_cast<int>(merged.proxies.size()), truth);
    const ProxyResult& one = merged.proxies[cylinder];
    ASSERT_EQ(one.type, QuadricType::cylinder) << type_name(one.type);
    EXPECT_EQ(one.faces, pieces[0] + pieces[1]);
    EXPECT_LE(std::abs(one.shape.radius - s.radius) / s.radius, 0.005) << one.shape.radius << " vs " << s.radius;
}

// The chamfer's cone, imposed as a general quadric and then as a cone, comes back with the
// true half-angle.
TEST(Edit, SetTypeImposesTheType) {
    const Part part = posed("stepped_shaft");
    const int truth = static_cast<int>(part.surfaces.size());
    Pipeline p(part.mesh, without_projection(truth));
    const Result r = finish(p);
    const PartitionScore score = score_partition(part, r.face_labels, truth);
    const int cone = region_on(part, score, truth, QuadricType::cone);  // the shaft has one
    ASSERT_GE(cone, 0);
    const TrueSurface& s = part.surfaces[score.face_of[cone]];

    const Result general = edited(p, Edit::set_type(cone, ImposedType::quadric));
    EXPECT_FALSE(general.proxies[cone].special_fit);
    EXPECT_EQ(general.proxies[cone].imposed, ImposedType::quadric);
    const Result as_cone = edited(p, Edit::set_type(cone, ImposedType::cone));
    const ProxyResult& c = as_cone.proxies[cone];
    ASSERT_EQ(c.type, QuadricType::cone);
    EXPECT_TRUE(c.special_fit);
    const ParameterError e = parameter_error(s, c.shape);
    EXPECT_LE(e.half_angle_degrees, 0.5);
    EXPECT_LE(e.axis_degrees, 1.0);
    // A later edit elsewhere keeps the type imposed.
    const int other = cone == 0 ? 1 : 0;
    const Result later = edited(p, Edit::split(other));
    EXPECT_EQ(later.proxies[cone].type, QuadricType::cone);
    // A plane imposed on the cone is a plane.
    EXPECT_EQ(edited(p, Edit::set_type(cone, ImposedType::plane)).proxies[cone].type, QuadricType::plane);
}

// A locked region keeps its faces and quadric through merges, splits and seeds around it.
TEST(Edit, LockedRegionStaysAsItIs) {
    const Part part = posed("l_bracket", 0.002);
    const int truth = static_cast<int>(part.surfaces.size());
    Pipeline p(part.mesh, without_projection(truth));
    const Result r = finish(p);
    const int locked = 0;
    edited(p, Edit::lock(locked));
    std::vector<int> neighbours;
    for (const auto& [a, b] : adjacent_pairs(part.mesh, r.face_labels))
        if (a == locked) neighbours.push_back(b);
    ASSERT_GE(neighbours.size(), 2u);
    const auto faces_of = [](const Result& x, int region) {
        std::vector<int> f;
        for (std::size_t t = 0; t < x.face_labels.size(); ++t)
            if (x.face_labels[t] == region) f.push_back(static_cast<int>(t));
        return f;
    };
    edited(p, Edit::split(neighbours[0]));
    edited(p, Edit::set_type(neighbours[1], ImposedType::quadric));
    int seed = -1;
    for (std::size_t t = 0; t < r.face_labels.size() && seed < 0; ++t)
        if (r.face_labels[t] == neighbours[1]) seed = part.mesh.source_face[t];
    const Result after = edited(p, Edit::add_seed(seed));
    EXPECT_EQ(after.proxies.size(), r.proxies.size() + 2);
    EXPECT_TRUE(after.proxies[locked].locked);
    EXPECT_EQ(faces_of(after, locked), faces_of(r, locked));
    EXPECT_EQ(after.proxies[locked].quadric.c, r.proxies[locked].quadric.c);
    EXPECT_NE(test::invalid_argument_of([&] { p.edit(Edit::split(locked)); }).find("locked"), std::string::npos);
    EXPECT_NE(test::invalid_argument_of([&] { p.edit(Edit::merge(locked, neighbours[0])); }).find("locked"),
              std::string::npos);
    const Result unlocked = edited(p, Edit::unlock(locked));
    EXPECT_FALSE(unlocked.proxies[locked].locked);
    EXPECT_EQ(unlocked.face_labels, after.face_labels);
}

// The recorded edits applied to a fresh run give the same labels; undo and redo step
// through the states; a cancelled edit leaves none.
TEST(Edit, ReplayUndoRedoAndCancel) {
    const Part part = posed("flange");
    Options options = test::with_proxies(0);
    Pipeline p(part.mesh, options);
    const Result first = finish(p);
    ASSERT_GE(first.proxies.size(), 4u);
    const auto pairs = adjacent_pairs(part.mesh, first.face_labels);
    edited(p, Edit::merge(pairs.begin()->first, pairs.begin()->second));
    edited(p, Edit::split(0));
    edited(p, Edit::lock(1));
    edited(p, Edit::set_type(2, ImposedType::quadric));
    const Result last = edited(p, Edit::add_seed(part.mesh.source_face[part.mesh.triangles.size() / 3]));
    ASSERT_EQ(last.edits.size(), 5u);
    ASSERT_EQ(last.timing.edits.size(), 5u);
    EXPECT_FALSE(last.projected.empty());
    ASSERT_TRUE(last.metrics.has_value());

    Pipeline replay(part.mesh, options);
    replay.run();
    for (const Edit& e : edits_from_json(nlohmann::json::parse(R"({"edits": )" + [&] {
             nlohmann::json list = nlohmann::json::array();
             for (const Edit& e : last.edits) list.push_back(edit_to_json(e));
             return list.dump();
         }() + "}")))
        edited(replay, e);
    EXPECT_EQ(replay.result().labels, last.labels);
    EXPECT_EQ(replay.result().edits, last.edits);

    for (int i = 0; i < 5; ++i) ASSERT_TRUE(p.undo());
    EXPECT_FALSE(p.undo());
    EXPECT_EQ(p.result().labels, first.labels);
    EXPECT_TRUE(p.result().edits.empty());
    for (int i = 0; i < 5; ++i) ASSERT_TRUE(p.redo());
    EXPECT_FALSE(p.redo());
    EXPECT_EQ(p.result().labels, last.labels);

    // Cancelled at its first step, an edit leaves the result as it was (and nothing to redo
    // is lost by it: it was never made).
    p.edit(Edit::split(0));
    p.run([](const Progress&) { return false; });
    EXPECT_EQ(p.result().labels, last.labels);
    EXPECT_EQ(p.result().edits.size(), 5u);
}

TEST(Edit, EditsThatDoNotApplySayWhyAndChangeNothing) {
    const Part part = posed("box_boss_hole");
    Pipeline p(part.mesh, without_projection(0));
    EXPECT_NE(test::invalid_argument_of([&] { p.edit(Edit::split(0)); }).find("finished run"), std::string::npos);
    const Result r = finish(p);
    const int n = static_cast<int>(r.proxies.size());
    const auto pairs = adjacent_pairs(part.mesh, r.face_labels);
    int far_a = -1, far_b = -1;
    for (int a = 0; a < n && far_a < 0; ++a)
        for (int b = a + 1; b < n && far_a < 0; ++b)
            if (!pairs.count({a, b})) far_a = a, far_b = b;
    ASSERT_GE(far_a, 0);
    int outside = 0;  // a kept face not in region 0
    while (r.face_labels[outside] == 0) ++outside;
    const std::vector<std::pair<std::string, Edit>> cases = {
        {"does not exist", Edit::split(n)},
        {"not adjacent", Edit::merge(far_a, far_b)},
        {"two different regions", Edit::merge(1, 1)},
        {"does not exist", Edit::add_seed(static_cast<int>(part.mesh.input_face_count))},
        {"is not in region", Edit::split(0, part.mesh.source_face[outside])},
    };
    for (const auto& [message, e] : cases) {
        SCOPED_TRACE(edit_to_json(e).dump());
        EXPECT_NE(test::invalid_argument_of([&] { p.edit(e); }).find(message), std::string::npos);
    }
    EXPECT_TRUE(p.done());
    EXPECT_EQ(p.result().labels, r.labels);
    EXPECT_TRUE(p.result().edits.empty());
}

TEST(Edit, JsonRoundTripAndErrors) {
    for (const Edit& e : {Edit::split(3), Edit::split(3, 120), Edit::merge(2, 5), Edit::set_type(1, ImposedType::cone),
                          Edit::set_type(1, ImposedType::none), Edit::lock(4), Edit::unlock(4), Edit::add_seed(812)})
        EXPECT_EQ(edit_from_json(edit_to_json(e)), e) << edit_to_json(e).dump();
    const std::map<std::string, std::string> bad = {
        {R"({"region": 1})", "an \"op\""},
        {R"({"op": "explode", "region": 1})", "unknown edit 'explode'"},
        {R"({"op": "split"})", "needs \"region\""},
        {R"({"op": "split", "region": -1})", "non-negative integer"},
        {R"({"op": "merge", "regions": [1]})", "[a, b]"},
        {R"({"op": "set_type", "region": 1, "type": "torus"})", "unknown type 'torus'"},
        {R"({"op": "add_seed", "face": 1.5})", "non-negative integer"},
    };
    for (const auto& [text, message] : bad) {
        SCOPED_TRACE(text);
        EXPECT_NE(test::invalid_argument_of([&] { edit_from_json(nlohmann::json::parse(text)); }).find(message),
                  std::string::npos);
    }
    EXPECT_NE(test::invalid_argument_of([&] { edits_from_json(nlohmann::json::parse(R"([{"op": "lock", "region": 1}, {"op": "x"}])")); })
                  .find("edit 1:"),
              std::string::npos);
}
