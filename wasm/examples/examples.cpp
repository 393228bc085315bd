#include "examples.h"

#include "cad_parts.h"
#include "shapes.h"

#include <cmath>
#include <cstdlib>
#include <stdexcept>

namespace vqsa {

namespace {

// `s` scales the resolution in both directions (faces grow as s²).
int steps(int base, double s) { return std::max(1, static_cast<int>(std::lround(base * s))); }

// A lathe-turned part: base disk, cylinder, chamfer cone, shoulder, neck, spherical cap.
Mesh turned_part(double s) {
    std::vector<ProfilePoint> p{{0, 0, 0}};
    add_segment(p, 1.0, 0, steps(10, s), 0);         // base: plane
    add_segment(p, 1.0, 0.6, steps(12, s), 1);       // cylinder
    add_segment(p, 0.7, 0.9, steps(8, s), 2);        // chamfer: cone
    add_segment(p, 0.45, 0.9, steps(6, s), 3);       // shoulder: plane
    add_segment(p, 0.45, 1.5, steps(12, s), 4);      // neck: cylinder
    add_arc(p, 0, 1.5, 0.45, 0, M_PI / 2, steps(14, s), 5);  // cap: sphere
    return revolve(p, steps(96, s)).mesh;
}

// An axle: two spheres joined by a cone and a cylinder (a freer mix of quadrics).
Mesh axle(double s) {
    std::vector<ProfilePoint> p{{0, -1.6, 0}};
    add_arc(p, 0, -1.0, 0.6, -M_PI / 2, 0, steps(14, s), 0);
    add_segment(p, 0.6, -0.2, steps(10, s), 1);
    add_segment(p, 0.3, 0.6, steps(10, s), 2);
    add_segment(p, 0.3, 1.2, steps(8, s), 3);
    add_arc(p, 0, 1.2, 0.3, 0, M_PI / 2, steps(10, s), 4);
    return revolve(p, steps(80, s)).mesh;
}

Mesh make(const std::string& name, double s) {
    if (name == "turned_part") return turned_part(s);
    if (name == "capsule") return make_capsule(0.5, 1.5, steps(96, s), steps(24, s)).mesh;
    if (name == "closed_cylinder") return make_closed_cylinder(0.5, 1.5, steps(96, s), steps(16, s)).mesh;
    if (name == "axle") return axle(s);
    for (const std::string& part : part_names()) {
        PartOptions options;
        options.detail = s;
        if (name == part) return make_part(name, options).mesh;
    }
    throw std::invalid_argument("unknown example '" + name + "'");
}

}  // namespace

std::vector<std::string> example_names() {
    std::vector<std::string> names{"turned_part", "capsule", "closed_cylinder", "axle"};
    for (const std::string& part : part_names()) names.push_back(part);
    return names;
}

Mesh example_mesh(const std::string& spec) {
    const std::size_t colon = spec.find(':');
    const std::string name = spec.substr(0, colon);
    if (colon == std::string::npos) return make(name, 1.0);
    const std::string size = spec.substr(colon + 1);
    char* end = nullptr;
    const double faces = std::strtod(size.c_str(), &end);
    if (size.empty() || *end != '\0' || !(faces >= 100 && faces <= 2e7))
        throw std::invalid_argument("example size '" + size + "' must be a face count between 100 and 20000000");
    // Faces grow as the square of the resolution: scale from the default's count.
    const double base = static_cast<double>(make(name, 1.0).triangles.size());
    return make(name, std::sqrt(faces / base));
}

}  // namespace vqsa
