#include "examples.h"

#include "shapes.h"

#include <cmath>
#include <stdexcept>

namespace vqsa {

namespace {

// A lathe-turned part: base disk, cylinder, chamfer cone, shoulder, neck, spherical cap.
Mesh turned_part() {
    std::vector<ProfilePoint> p{{0, 0, 0}};
    add_segment(p, 1.0, 0, 10, 0);         // base: plane
    add_segment(p, 1.0, 0.6, 12, 1);       // cylinder
    add_segment(p, 0.7, 0.9, 8, 2);        // chamfer: cone
    add_segment(p, 0.45, 0.9, 6, 3);       // shoulder: plane
    add_segment(p, 0.45, 1.5, 12, 4);      // neck: cylinder
    add_arc(p, 0, 1.5, 0.45, 0, M_PI / 2, 14, 5);  // cap: sphere
    return revolve(p, 96).mesh;
}

// An axle: two spheres joined by a cone and a cylinder (a freer mix of quadrics).
Mesh axle() {
    std::vector<ProfilePoint> p{{0, -1.6, 0}};
    add_arc(p, 0, -1.0, 0.6, -M_PI / 2, 0, 14, 0);
    add_segment(p, 0.6, -0.2, 10, 1);
    add_segment(p, 0.3, 0.6, 10, 2);
    add_segment(p, 0.3, 1.2, 8, 3);
    add_arc(p, 0, 1.2, 0.3, 0, M_PI / 2, 10, 4);
    return revolve(p, 80).mesh;
}

}  // namespace

std::vector<const char*> example_names() { return {"turned_part", "capsule", "closed_cylinder", "axle"}; }

Mesh example_mesh(const std::string& name) {
    if (name == "turned_part") return turned_part();
    if (name == "capsule") return make_capsule(0.5, 1.5, 96, 24).mesh;
    if (name == "closed_cylinder") return make_closed_cylinder(0.5, 1.5, 96, 16).mesh;
    if (name == "axle") return axle();
    throw std::invalid_argument("unknown example '" + name + "'");
}

}  // namespace vqsa
