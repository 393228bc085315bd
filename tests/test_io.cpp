#include "io/mesh_io.h"
#include "geometry/model.h"
#include "shapes.h"
#include "test_support.h"

#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

using namespace vqsa;

namespace {

Mesh read_text(const std::string& name, const std::string& text) {
    return read_mesh(name, reinterpret_cast<const std::uint8_t*>(text.data()), text.size());
}

// The error message of reading `text` as `name`, or "" if it reads.
std::string read_error(const std::string& name, const std::string& text) {
    try {
        read_text(name, text);
    } catch (const MeshReadError& e) {
        return e.what();
    }
    return "";
}

const Mesh& sample() {
    static const Mesh mesh = make_capsule(0.5, 1.0, 12, 4).mesh;
    return mesh;
}

std::string to_off(const Mesh& m) {
    std::ostringstream s;
    s.precision(17);
    s << "OFF\n" << m.vertices.size() << " " << m.triangles.size() << " 0\n";
    for (const Vec3& p : m.vertices) s << p.x() << " " << p.y() << " " << p.z() << "\n";
    for (const Triangle& t : m.triangles) s << "3 " << t[0] << " " << t[1] << " " << t[2] << "\n";
    return s.str();
}

std::string to_obj(const Mesh& m) {
    std::ostringstream s;
    s.precision(17);
    s << "# comment\no sample\n";
    for (const Vec3& p : m.vertices) s << "v " << p.x() << " " << p.y() << " " << p.z() << "\nvn 0 0 1\n";
    for (const Triangle& t : m.triangles) s << "f " << t[0] + 1 << "//1 " << t[1] + 1 << "//1 " << t[2] + 1 << "//1\n";
    return s.str();
}

template <typename T>
void put(std::string& out, T value, bool big_endian) {
    char raw[sizeof(T)];
    std::memcpy(raw, &value, sizeof(T));
    if (big_endian) std::reverse(raw, raw + sizeof(T));
    out.append(raw, sizeof(T));
}

std::string to_ply(const Mesh& m, const std::string& format) {
    std::ostringstream h;
    h << "ply\nformat " << format << " 1.0\ncomment test\nelement vertex " << m.vertices.size()
      << "\nproperty double x\nproperty double y\nproperty double z\nproperty uchar red\n"
      << "element face " << m.triangles.size() << "\nproperty list uchar int vertex_indices\nend_header\n";
    std::string out = h.str();
    if (format == "ascii") {
        std::ostringstream s;
        s.precision(17);
        for (const Vec3& p : m.vertices) s << p.x() << " " << p.y() << " " << p.z() << " 200\n";
        for (const Triangle& t : m.triangles) s << "3 " << t[0] << " " << t[1] << " " << t[2] << "\n";
        return out + s.str();
    }
    const bool big = format == "binary_big_endian";
    for (const Vec3& p : m.vertices) {
        for (int k = 0; k < 3; ++k) put<double>(out, p[k], big);
        put<std::uint8_t>(out, 200, big);
    }
    for (const Triangle& t : m.triangles) {
        put<std::uint8_t>(out, 3, big);
        for (int k = 0; k < 3; ++k) put<std::int32_t>(out, t[k], big);
    }
    return out;
}

std::string to_binary_stl(const Mesh& m, const std::string& header_start) {
    std::string out = header_start;
    out.resize(80, ' ');
    put<std::uint32_t>(out, static_cast<std::uint32_t>(m.triangles.size()), false);
    for (const Triangle& t : m.triangles) {
        for (int k = 0; k < 3; ++k) put<float>(out, 0.f, false);
        for (int v : t)
            for (int k = 0; k < 3; ++k) put<float>(out, static_cast<float>(m.vertices[v][k]), false);
        put<std::uint16_t>(out, 0, false);
    }
    return out;
}

std::string to_ascii_stl(const Mesh& m) {
    std::ostringstream s;
    s.precision(9);
    s << "solid test\n";
    for (const Triangle& t : m.triangles) {
        s << " facet normal 0 0 0\n  outer loop\n";
        for (int v : t) s << "   vertex " << m.vertices[v].x() << " " << m.vertices[v].y() << " " << m.vertices[v].z() << "\n";
        s << "  endloop\n endfacet\n";
    }
    s << "endsolid test\n";
    return s.str();
}

// A glTF with the mesh under a node that translates it by (10, 0, 0).
std::string to_gltf(const Mesh& m, bool binary) {
    tinygltf::Model model;
    tinygltf::Buffer buffer;
    std::string bytes;
    for (const Vec3& p : m.vertices)
        for (int k = 0; k < 3; ++k) put<float>(bytes, static_cast<float>(p[k]), false);
    const std::size_t positions = bytes.size();
    for (const Triangle& t : m.triangles)
        for (int v : t) put<std::uint32_t>(bytes, static_cast<std::uint32_t>(v), false);
    buffer.data.assign(bytes.begin(), bytes.end());
    model.buffers.push_back(buffer);
    tinygltf::BufferView pv, iv;
    pv.buffer = iv.buffer = 0;
    pv.byteLength = positions;
    iv.byteOffset = positions;
    iv.byteLength = bytes.size() - positions;
    model.bufferViews = {pv, iv};
    tinygltf::Accessor pa, ia;
    pa.bufferView = 0;
    pa.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
    pa.type = TINYGLTF_TYPE_VEC3;
    pa.count = m.vertices.size();
    ia.bufferView = 1;
    ia.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
    ia.type = TINYGLTF_TYPE_SCALAR;
    ia.count = 3 * m.triangles.size();
    model.accessors = {pa, ia};
    tinygltf::Primitive primitive;
    primitive.attributes["POSITION"] = 0;
    primitive.indices = 1;
    primitive.mode = TINYGLTF_MODE_TRIANGLES;
    tinygltf::Mesh mesh;
    mesh.primitives.push_back(primitive);
    model.meshes.push_back(mesh);
    tinygltf::Node node;
    node.mesh = 0;
    node.translation = {10, 0, 0};
    model.nodes.push_back(node);
    tinygltf::Scene scene;
    scene.nodes = {0};
    model.scenes.push_back(scene);
    model.defaultScene = 0;
    model.asset.version = "2.0";
    std::ostringstream out;
    tinygltf::TinyGLTF writer;
    writer.WriteGltfSceneToStream(&model, out, false, binary);
    return out.str();
}

}  // namespace

TEST(Readers, EverySharedMeshLoadsWithItsKnownCounts) {
    struct Known {
        const char* file;
        int vertices, faces, components;
    };
    const Known known[] = {
        {"fandisk.off", 6475, 12946, 1},        {"block.off", 2132, 4272, 1},
        {"casting.off", 5096, 10224, 1},        {"rocker_arm.obj", 10044, 20088, 1},
        {"pinion.off", 10369, 20738, 1},        {"joint.off", 20902, 41808, 1},
        {"csg.off", 1066, 2124, 2},             {"chess_pawn.stl", 8621, 17238, 2},
        {"abc_pipe_junction.stl", 18646, 37288, 1}, {"abc_round_cap.stl", 1529, 3058, 1},
        {"cylinder_capped.off", 4802, 9600, 1}, {"sphere.stl", 3083, 6162, 1},
        {"bunny.obj", 35947, 69451, 1},         {"bunny_closed.off", 35396, 70788, 1},
        {"homer.obj", 6002, 12000, 1},          {"mask.off", 31762, 62467, 1},
    };
    for (const Known& k : known) {
        SCOPED_TRACE(k.file);
        const Mesh mesh = read_mesh_file(test::shared_mesh(k.file));
        EXPECT_EQ(mesh.input_vertex_count, k.vertices);
        EXPECT_EQ(mesh.input_face_count, k.faces);
        EXPECT_GE(static_cast<int>(mesh.triangles.size()), k.faces - 20);  // only slivers may be dropped
        EXPECT_EQ(make_model(mesh).component_count, k.components);
    }
}

TEST(Readers, EveryFormatReadsTheSameMesh) {
    const Mesh& m = sample();
    const BoundingBox box = bounding_box(m);
    const std::pair<std::string, std::string> files[] = {
        {"a.off", to_off(m)},
        {"a.obj", to_obj(m)},
        {"a.ply", to_ply(m, "ascii")},
        {"a.ply", to_ply(m, "binary_little_endian")},
        {"a.PLY", to_ply(m, "binary_big_endian")},
        {"a.stl", to_ascii_stl(m)},
        {"a.stl", to_binary_stl(m, "binary")},
        {"a.stl", to_binary_stl(m, "solid but binary")},
        {"a.glb", to_gltf(m, true)},
        {"a.gltf", to_gltf(m, false)},
    };
    for (const auto& [name, text] : files) {
        SCOPED_TRACE(name + " " + text.substr(0, 30));
        const Mesh r = read_text(name, text);
        EXPECT_EQ(r.triangles.size(), m.triangles.size());
        EXPECT_EQ(r.vertices.size(), m.vertices.size());
        const bool moved = name.find(".gl") != std::string::npos;
        const BoundingBox rb = bounding_box(r);
        EXPECT_LT((rb.min - box.min - Vec3(moved ? 10 : 0, 0, 0)).norm(), 1e-6);
        EXPECT_LT((rb.max - box.max - Vec3(moved ? 10 : 0, 0, 0)).norm(), 1e-6);
    }
}

TEST(Readers, PolygonsAreFannedAndDegenerateFacesDropped) {
    // A quad, a pentagon with a repeated vertex, a collinear triangle; OBJ negative indices.
    const std::string obj =
        "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 2 0 0\n"
        "f 1 2 3 4\nf -4 -1 -2 -2 -3\nf 1 2 5\n";
    const Mesh m = read_text("poly.obj", obj);
    EXPECT_EQ(m.input_face_count, 2 + 3 + 1);
    // The pentagon fans into (2,5,4) (2,4,4) (2,4,3): one with a repeated vertex; (1,2,5) is collinear.
    EXPECT_EQ(m.triangles.size(), 4u);
    EXPECT_EQ(m.source_face, (std::vector<int>{0, 1, 2, 4}));
}

TEST(Readers, AConcavePolygonIsCutInsideItAndABackslashContinuesItsLine) {
    // A wall round a notch, as Rhino writes it: one face of eight vertices, its line continued
    // with a backslash (CRLF). Fanned from its first vertex, a triangle covered the notch.
    const std::string obj =
        "v 0 0 5\r\nv 3 0 5\r\nv 3 1 5\r\nv 1 1 5\r\nv 1 2 5\r\nv 3 2 5\r\nv 3 3 5\r\nv 0 3 5\r\n"
        "f 1/1/1 2/2/2 3/3/3 4/4/4 \\\r\n5/5/5 6/6/6 7/7/7 8/8/8\r\n";
    for (const bool reversed : {false, true}) {
        std::string text = obj;
        if (reversed) text.replace(text.find("f 1/1/1"), std::string::npos, "f 8 7 6 5 4 \\\n 3 2 1\n");
        const Mesh m = read_text("wall.obj", text);
        ASSERT_EQ(m.triangles.size(), 6u) << "reversed " << reversed;
        double area = 0;
        Vec3 normal = Vec3::Zero();
        for (const Triangle& t : m.triangles) {
            const Vec3 a = m.vertices[t[0]], b = m.vertices[t[1]], c = m.vertices[t[2]];
            const Vec3 n = (b - a).cross(c - a);
            area += n.norm() / 2;
            normal += n;
            const Vec3 centre = (a + b + c) / 3;
            EXPECT_FALSE(centre.x() > 1 && centre.y() > 1 && centre.y() < 2) << "a triangle in the notch";
        }
        EXPECT_NEAR(area, 7, 1e-12);  // 3 × 3 less the notch: no triangle outside the wall
        EXPECT_NEAR(normal.norm() / 2, 7, 1e-12);  // and all facing one way
        EXPECT_EQ(normal.z() > 0, !reversed);
    }
    EXPECT_NE(read_error("bad.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 \\ 3\n").find("bad face vertex"), std::string::npos);
}

TEST(Readers, OffQuirksFromTheSharedMeshes) {
    // Counts on the keyword line, CRLF, comments, blank lines, exponents like 1e-006, colours.
    const std::string off = "OFF 4 2 0\r\n# comment\r\n\r\n  \r\n0 0 0\r\n1e-006 0 1\r\n1 1 0 255 0 0\r\n"
                            "0 1 0\r\n3 0 1 2\r\n3 0 2 3 0.5 0.5 0.5\r\n";
    const Mesh m = read_text("q.off", off);
    EXPECT_EQ(m.triangles.size(), 2u);
    EXPECT_EQ(m.vertices[1].x(), 1e-6);
}

TEST(Readers, BadInputGivesAClearErrorNamingTheFile) {
    const std::string off = to_off(sample()), stl = to_binary_stl(sample(), "x"), ply = to_ply(sample(), "binary_little_endian");
    const struct {
        std::string name, text, expected;
    } cases[] = {
        {"empty.off", "", "empty"},
        {"empty.stl", "", "empty"},
        {"garbage.off", "\x7f\x45\x4c\x46 binary junk \x01\x02", "not an off file"},
        {"garbage.obj", "\x01\x02\x03 nothing here", "no vertices or faces"},
        {"garbage.ply", "\x01\x02\x03", "not a ply file"},
        {"garbage.stl", std::string(200, '\x07'), "binary stl header announces"},
        {"garbage.glb", "glTF\x02\x00\x00\x00 junk", "glb"},
        {"garbage.gltf", "{ not json", "json"},
        {"truncated.stl", stl.substr(0, stl.size() - 30), "truncated"},
        {"truncated.ply", ply.substr(0, ply.size() - 7), "truncated"},
        {"truncated.off", off.substr(0, off.size() / 2), "end of file"},
        {"nan.off", "OFF\n3 1 0\n0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n", "not a finite number"},
        {"inf.obj", "v 0 0 0\nv 1 0 inf\nv 0 1 0\nf 1 2 3\n", "not a finite number"},
        {"overflow.off", "OFF\n3 1 0\n1e308 0 0\n-1e308 0 0\n0 1e308 0\n3 0 1 2\n", "beyond"},
        {"range.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n", "out of range"},
        {"negative.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 -1 2\n", "out of range"},
        {"range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n", "out of range"},
        {"huge.off", "OFF\n1000000000000 1000000000000 0\n0 0 0\n", "more than the file can hold"},
        {"huge.ply", "ply\nformat ascii 1.0\nelement vertex 1000000000000\nproperty float x\nproperty float y\n"
                     "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n",
         "more than the file can hold"},
        {"flat.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n2 0 0\n3 0 1 2\n", "degenerate"},
        {"nofaces.off", "OFF\n3 0 0\n0 0 0\n1 0 0\n2 0 0\n", "no faces"},
        {"mesh.xyz", "1 2 3", "unknown format"},
        {"noextension", "1 2 3", "no extension"},
    };
    for (const auto& c : cases) {
        const std::string message = read_error(c.name, c.text);
        SCOPED_TRACE(c.name + ": " + message);
        ASSERT_FALSE(message.empty());
        EXPECT_EQ(message.rfind(c.name + ": ", 0), 0u);
        std::string lower = message;
        std::transform(lower.begin(), lower.end(), lower.begin(), ::tolower);
        EXPECT_NE(lower.find(c.expected), std::string::npos);
    }
    try {
        read_mesh_file("/nonexistent/missing.off");
        FAIL() << "no error";
    } catch (const MeshReadError& e) {
        EXPECT_STREQ(e.what(), "/nonexistent/missing.off: cannot open the file");
    }
    try {
        read_mesh_file(VQSA_SHARED_MESHES);
        FAIL() << "no error";
    } catch (const MeshReadError& e) {
        EXPECT_EQ(std::string(e.what()), std::string(VQSA_SHARED_MESHES) + ": is a directory, not a mesh file");
    }
}

// Inputs the fuzzers found (tests/fuzz/regressions): each must read or fail cleanly, fast.
TEST(Readers, FuzzerFindingsFailCleanly) {
    const std::string dir = std::string(VQSA_SOURCE_DIR) + "/tests/fuzz/regressions";
    int files = 0;
    for (const auto& entry : std::filesystem::directory_iterator(dir)) {
        ++files;
        SCOPED_TRACE(entry.path().filename().string());
        try {
            read_mesh_file(entry.path().string());
        } catch (const MeshReadError&) {
        }
    }
    EXPECT_GE(files, 2);
}

TEST(Readers, NulBytesEndNoTokenForever) {
    const std::string stl = std::string("solid t\n facet normal 0 0 0\n  outer loop\n   vertex 0 0 0\n   vertex 1 0 0\n"
                                        "   vertex 0 1 0\n  endl") + '\0' + "oop\n endfacet\nendsolid\n";
    EXPECT_FALSE(read_error("nul.stl", stl).empty());
    const std::string off = std::string("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2") + '\0';
    read_error("nul.off", off);  // reads or fails; must return
}
