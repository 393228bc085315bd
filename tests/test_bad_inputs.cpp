// The bad-input corpus (tests/bad_inputs): each file fails with a clear message or runs
// to finite results. The WASM build is held to the same file in tests/node.
#include "export/gltf_export.h"
#include "export/report.h"
#include "io/mesh_io.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

using namespace vqsa;

namespace {

const std::string corpus = VQSA_BAD_INPUTS;

bool all_finite(const nlohmann::json& j) {
    if (j.is_number_float()) return std::isfinite(j.get<double>());
    if (j.is_array() || j.is_object()) {
        for (const auto& v : j)
            if (!all_finite(v)) return false;
    }
    return true;
}

std::string lower(std::string s) {
    for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return s;
}

}  // namespace

TEST(BadInputs, EachFailsClearlyOrRunsToFiniteResults) {
    std::ifstream in(corpus + "/expected.json");
    ASSERT_TRUE(in) << corpus;
    const nlohmann::json expected = nlohmann::json::parse(in);
    ASSERT_GE(expected.size(), 20u);
    for (const auto& [name, want] : expected.items()) {
        SCOPED_TRACE(name);
        const std::string path = corpus + "/" + name;
        if (want.contains("error")) {
            try {
                read_mesh_file(path);
                ADD_FAILURE() << "read without error";
            } catch (const MeshReadError& e) {
                const std::string message = e.what();
                EXPECT_EQ(message.rfind(path + ": ", 0), 0u) << message;
                EXPECT_EQ(message.find("cannot open"), std::string::npos) << "the corpus file is missing";
                EXPECT_NE(lower(message).find(want["error"].get<std::string>()), std::string::npos) << message;
            }
            continue;
        }
        const Mesh mesh = read_mesh_file(path);
        EXPECT_EQ(static_cast<int>(mesh.triangles.size()), want["faces_used"].get<int>());
        const Result result = test::approximate(mesh, test::with_proxies(want["request"]));
        EXPECT_EQ(static_cast<int>(result.proxies.size()), want["proxies"].get<int>());
        const nlohmann::json report = make_report(result);
        EXPECT_TRUE(all_finite(report)) << report.dump().substr(0, 400);
        ASSERT_TRUE(result.metrics.has_value());
        for (int l : result.face_labels) ASSERT_GE(l, 0);
        for (const Vec3& p : result.projected) ASSERT_TRUE(p.allFinite());
        EXPECT_GT(export_glb(mesh, result).size(), 100u);
    }
}

TEST(BadInputs, FarAndTinyMeshesGiveTheSameShapeAtTheirScale) {
    const Mesh far = read_mesh_file(corpus + "/far_away.off"), tiny = read_mesh_file(corpus + "/tiny.off");
    const Result a = test::approximate(far, test::with_proxies(3)), b = test::approximate(tiny, test::with_proxies(3));
    for (const Result* e : {&a, &b}) {
        int planes = 0, cylinders = 0;
        for (int i = 0; i < 3; ++i) {
            const Classification& c = e->proxies[i].shape;
            planes += c.type == QuadricType::plane;
            if (c.type == QuadricType::cylinder) {
                ++cylinders;
                const double scale = e == &a ? 1.0 : 1e-6;
                // A 32-gon inscribed in the unit circle: the best cylinder sits between apothem and radius.
                EXPECT_NEAR(c.radius / scale, 0.99, 0.012);
            }
        }
        EXPECT_EQ(planes, 2);
        EXPECT_EQ(cylinders, 1);
    }
}

TEST(BadInputs, OptionsOutOfRangeAreRejected) {
    const Mesh mesh = read_mesh_file(corpus + "/far_away.off");
    auto message = [&](const Options& o) { return test::invalid_argument_of([&] { Pipeline p(mesh, o); }); };
    Options automatic;  // no count and no tolerance: the count is chosen, not an error
    EXPECT_EQ(message(automatic), "");
    Options count = test::with_proxies(-1);
    EXPECT_NE(message(count).find("proxies"), std::string::npos);
    Options negative;
    negative.lloyd.tolerance = -0.1;
    EXPECT_NE(message(negative).find("tolerance"), std::string::npos);
    Options huge = test::with_proxies(1000000);
    EXPECT_NE(message(huge).find("exceeds the number of faces"), std::string::npos);
    Options rings = test::with_proxies(3);
    rings.smoothing.rings = 0;
    EXPECT_NE(message(rings).find("rings"), std::string::npos);
    Options lambda = test::with_proxies(3);
    lambda.smoothing.lambda = std::nan("");
    EXPECT_NE(message(lambda).find("lambda"), std::string::npos);
}
