// Writing meshes (io/mesh_write.h): every format reads back to the same mesh.
#include "io/mesh_io.h"
#include "io/mesh_write.h"
#include "shapes.h"

#include <gtest/gtest.h>

using namespace vqsa;

TEST(MeshWrite, EveryFormatReadsBackExactly) {
    const Mesh mesh = make_capsule(0.5, 1.0, 12, 4).mesh;
    for (const char* name : {"out.obj", "out.ply", "out.off", "OUT.PLY"}) {
        const std::string bytes = write_mesh(name, mesh.vertices, mesh.triangles);
        const Mesh back = read_mesh(name, reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
        ASSERT_EQ(back.vertices.size(), mesh.vertices.size()) << name;
        ASSERT_EQ(back.triangles.size(), mesh.triangles.size()) << name;
        // Positions round-trip to the last bit (binary doubles, or 17 significant digits).
        for (std::size_t v = 0; v < mesh.vertices.size(); ++v) ASSERT_EQ(back.vertices[v], mesh.vertices[v]) << name;
        for (std::size_t t = 0; t < mesh.triangles.size(); ++t) ASSERT_EQ(back.triangles[t], mesh.triangles[t]) << name;
    }
}

TEST(MeshWrite, UnknownExtensionsAreRefused) {
    const Mesh mesh = make_capsule(0.5, 1.0, 6, 2).mesh;
    EXPECT_THROW(write_mesh("out.stl", mesh.vertices, mesh.triangles), std::invalid_argument);
    EXPECT_THROW(write_mesh("out", mesh.vertices, mesh.triangles), std::invalid_argument);
}
