#include "io/mesh_write.h"

#include <cstdint>
#include <cctype>
#include <iomanip>
#include <sstream>
#include <stdexcept>

namespace vqsa {

std::string write_mesh(std::string_view name, const std::vector<Vec3>& vertices, const std::vector<Triangle>& triangles) {
    const std::size_t dot = name.find_last_of('.');
    std::string ext(dot == std::string_view::npos ? "" : name.substr(dot + 1));
    for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    std::ostringstream out;
    out << std::setprecision(17);
    if (ext == "obj") {
        out << "# vqsa projected mesh\n";
        for (const Vec3& p : vertices) out << "v " << p.x() << ' ' << p.y() << ' ' << p.z() << '\n';
        for (const Triangle& t : triangles) out << "f " << t[0] + 1 << ' ' << t[1] + 1 << ' ' << t[2] + 1 << '\n';
    } else if (ext == "off") {
        out << "OFF\n" << vertices.size() << ' ' << triangles.size() << " 0\n";
        for (const Vec3& p : vertices) out << p.x() << ' ' << p.y() << ' ' << p.z() << '\n';
        for (const Triangle& t : triangles) out << "3 " << t[0] << ' ' << t[1] << ' ' << t[2] << '\n';
    } else if (ext == "ply") {
        out << "ply\nformat binary_little_endian 1.0\ncomment vqsa projected mesh\nelement vertex " << vertices.size()
            << "\nproperty double x\nproperty double y\nproperty double z\nelement face " << triangles.size()
            << "\nproperty list uchar int vertex_indices\nend_header\n";
        std::string body;
        body.reserve(vertices.size() * 24 + triangles.size() * 13);
        auto put = [&](const void* data, std::size_t size) { body.append(static_cast<const char*>(data), size); };
        for (const Vec3& p : vertices) put(p.data(), 24);  // little-endian hosts only, as our targets are
        for (const Triangle& t : triangles) {
            const std::uint8_t three = 3;
            const std::int32_t v[3] = {t[0], t[1], t[2]};
            put(&three, 1);
            put(v, 12);
        }
        out << body;
    } else {
        throw std::invalid_argument("cannot write '." + ext + "' meshes; use .obj, .ply or .off");
    }
    return out.str();
}

}  // namespace vqsa
