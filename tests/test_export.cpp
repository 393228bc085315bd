#include "export/gltf_export.h"
#include "export/palette.h"
#include "io/mesh_io.h"
#include "export/report.h"
#include "shapes.h"
#include "test_support.h"

#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include <cstring>
#include <filesystem>
#include <fstream>

using namespace vqsa;

namespace {

// Every GLB the tests write lands here; the node tests run the Khronos validator on them.
std::string keep(const std::string& name, const std::string& bytes) {
    std::filesystem::create_directories(VQSA_TEST_OUTPUT);
    const std::string path = std::string(VQSA_TEST_OUTPUT) + "/" + name;
    std::ofstream(path, std::ios::binary) << bytes;
    return path;
}

tinygltf::Model parse(const std::string& bytes) {
    tinygltf::TinyGLTF loader;
    loader.SetImageLoader([](tinygltf::Image*, const int, std::string*, std::string*, int, int, const unsigned char*,
                             int, void*) { return true; },
                          nullptr);
    tinygltf::Model model;
    std::string err, warn;
    EXPECT_TRUE(loader.LoadBinaryFromMemory(&model, &err, &warn, reinterpret_cast<const unsigned char*>(bytes.data()),
                                            static_cast<unsigned>(bytes.size())))
        << err;
    return model;
}

template <typename T>
T element(const tinygltf::Model& m, const tinygltf::Accessor& a, std::size_t i) {
    const tinygltf::BufferView& v = m.bufferViews[a.bufferView];
    const std::size_t stride = v.byteStride ? v.byteStride : sizeof(T);
    T value;
    std::memcpy(&value, m.buffers[v.buffer].data.data() + v.byteOffset + a.byteOffset + i * stride, sizeof(T));
    return value;
}

// The region of every triangle of a primitive, read from _FEATURE_ID_0 through the indices.
std::vector<int> triangle_regions(const tinygltf::Model& m, const tinygltf::Primitive& p) {
    const tinygltf::Accessor& ids = m.accessors[p.attributes.at("_FEATURE_ID_0")];
    const tinygltf::Accessor& indices = m.accessors[p.indices];
    std::vector<int> regions;
    for (std::size_t t = 0; t < indices.count / 3; ++t) {
        std::vector<int> corner;
        for (int k = 0; k < 3; ++k) {
            const std::size_t v = indices.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT
                                      ? element<std::uint32_t>(m, indices, 3 * t + k)
                                      : element<std::uint16_t>(m, indices, 3 * t + k);
            corner.push_back(ids.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT ? int(element<float>(m, ids, v))
                                                                                 : element<std::uint16_t>(m, ids, v));
        }
        EXPECT_TRUE(corner[0] == corner[1] && corner[1] == corner[2]) << "region id varies inside triangle " << t;
        regions.push_back(corner[0]);
    }
    return regions;
}

// Reads the GLB back and checks it against the run's own report.
void check_round_trip(const Mesh& mesh, const Result& result, const std::string& bytes) {
    const tinygltf::Model m = parse(bytes);
    const nlohmann::json report = make_report(result);
    const int regions = static_cast<int>(report["proxies"].size());

    ASSERT_EQ(m.nodes.size(), result.projected.empty() ? 1u : 2u);
    EXPECT_EQ(m.nodes[0].name, "input");
    const tinygltf::Primitive& primitive = m.meshes[0].primitives[0];
    const tinygltf::Value& features = primitive.extensions.at("EXT_mesh_features");
    EXPECT_EQ(features.Get("featureIds").Get(0).Get("featureCount").GetNumberAsInt(), regions);
    const tinygltf::Value& table = m.extensions.at("EXT_structural_metadata").Get("propertyTables").Get(0);
    EXPECT_EQ(table.Get("count").GetNumberAsInt(), regions);

    // Face → region, in the input's face order, as the report's labels.
    const std::vector<int> per_triangle = triangle_regions(m, primitive);
    ASSERT_EQ(per_triangle.size(), mesh.triangles.size());
    const std::vector<int> labels = report["labels"];
    for (std::size_t k = 0; k < per_triangle.size(); ++k) ASSERT_EQ(per_triangle[k], labels[mesh.source_face[k]]);
    if (m.nodes.size() == 2) EXPECT_EQ(triangle_regions(m, m.meshes[1].primitives[0]), per_triangle);

    // The extras and the property table carry the report's coefficients.
    const tinygltf::Value& extras = m.meshes[0].extras.Get("regions");
    ASSERT_EQ(static_cast<int>(extras.ArrayLen()), regions);
    const tinygltf::Value& column = table.Get("properties").Get("coefficients");
    const tinygltf::BufferView& view = m.bufferViews[column.Get("values").GetNumberAsInt()];
    for (int r = 0; r < regions; ++r) {
        EXPECT_EQ(extras.Get(r).Get("type").Get<std::string>(), report["proxies"][r]["type"]);
        for (int c = 0; c < 10; ++c) {
            const double expected = report["proxies"][r]["coefficients"][c];
            EXPECT_EQ(extras.Get(r).Get("coefficients").Get(c).GetNumberAsDouble(), expected);
            double stored;
            std::memcpy(&stored, m.buffers[0].data.data() + view.byteOffset + (10 * r + c) * 8, 8);
            EXPECT_EQ(stored, expected);
        }
    }
    EXPECT_EQ(m.scenes[0].extras.Get("generator").Get<std::string>(), "vqsa");
}

// Runs, exports, keeps the GLB for the validator and checks the round trip.
std::string export_checked(const Mesh& mesh, const Options& options, const std::string& name) {
    const Result result = test::approximate(mesh, options);
    const std::string bytes = export_glb(mesh, result);
    keep(name, bytes);
    check_round_trip(mesh, result, bytes);
    return bytes;
}

}  // namespace

TEST(Export, FandiskRoundTrip) {
    export_checked(read_mesh_file(test::shared_mesh("fandisk.off")), test::with_proxies(22), "fandisk.glb");
}

TEST(Export, LargeMeshUsesThirtyTwoBitIndices) {
    Shape grid = make_grid([](double u, double v) { return Vec3(u, v, 0.3 * std::sin(3 * u) * std::cos(2 * v)); }, 0, 3,
                           0, 2, 330, 220);
    ASSERT_GT(grid.mesh.vertices.size(), 65535u);
    Options o = test::with_proxies(4);
    o.measure = false;
    const tinygltf::Model m = parse(export_checked(grid.mesh, o, "large_grid.glb"));
    EXPECT_EQ(m.accessors[m.meshes[0].primitives[0].indices].componentType, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT);
}

TEST(Export, SeveralComponentsAndDroppedFaces) {
    PolygonSoup soup;
    append(soup, make_capsule(0.5, 1, 24, 6).mesh);
    append(soup, make_closed_cylinder(0.4, 1, 24, 4).mesh, Vec3(3, 0, 0));
    const int degenerate[3] = {0, 0, 1};  // a face that repeats a vertex: dropped, label -1
    soup.add_polygon(degenerate, 3);
    const Mesh mesh = build_mesh(soup);
    ASSERT_EQ(mesh.input_face_count, static_cast<int>(mesh.triangles.size()) + 1);
    const tinygltf::Model m = parse(export_checked(mesh, test::with_proxies(6), "two_parts.glb"));
    EXPECT_EQ(m.scenes[0].extras.Get("dropped_faces").Get(0).GetNumberAsInt(), mesh.input_face_count - 1);
}

TEST(Export, WithoutProjectionOnlyTheInputNode) {
    Shape capsule = make_capsule(0.5, 1, 24, 6);
    Options o = test::with_proxies(3);
    o.project = false;
    export_checked(capsule.mesh, o, "capsule_unprojected.glb");
}

// Any two of the first regions' colours must be told apart on a shaded mesh, whatever
// their ids: neighbours on the mesh may have any ids. (The golden-ratio hue palette this
// replaced gave ids 0 and 34 nearly the same colour: 0.004 apart.)
TEST(Palette, TheFirstRegionsColoursAreFarApart) {
    for (const auto& [count, least] : std::vector<std::pair<int, double>>{{16, 0.09}, {32, 0.06}, {64, 0.04}}) {
        double closest = 1;
        for (int i = 0; i < count; ++i)
            for (int j = 0; j < i; ++j) closest = std::min(closest, vqsa::color_difference(vqsa::region_color(i), vqsa::region_color(j)));
        EXPECT_GE(closest, least) << "among the first " << count << " regions";
    }
    // Light enough to show shading, coloured enough not to pass for the unlabelled grey.
    for (int i = 0; i < vqsa::kRegionPaletteSize; ++i) {
        const vqsa::Vec3 lab = vqsa::oklab(vqsa::region_color(i));
        EXPECT_GE(lab.x(), 0.6) << i;
        EXPECT_LE(lab.x(), 0.84) << i;
        EXPECT_GE(std::hypot(lab.y(), lab.z()), 0.079) << i;
    }
}
