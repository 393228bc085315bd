// Procedural meshes: examples the app offers and ground truth for the tests. Every
// face knows the analytic patch it was cut from.
#pragma once

#include "io/mesh.h"

#include <functional>
#include <vector>

namespace vqsa {

struct Shape {
    Mesh mesh;
    std::vector<int> patch;  // per kept face
};

// A profile for surfaces of revolution about z: points (r, z) with the patch id of the
// segment that ends at each point (the first point's id is unused).
struct ProfilePoint {
    double r, z;
    int patch;
};

// Revolves the profile with `around` segments. Points with r = 0 close the surface.
Shape revolve(const std::vector<ProfilePoint>& profile, int around);

// Appends a straight segment (r0,z0) → (r1,z1) cut into `steps` pieces (the start is
// assumed already in the profile) and a circular arc around (rc, zc) from angle a0 to
// a1 (radians, measured from +r towards +z).
void add_segment(std::vector<ProfilePoint>& profile, double r1, double z1, int steps, int patch);
void add_arc(std::vector<ProfilePoint>& profile, double rc, double zc, double radius, double a0, double a1, int steps,
             int patch);

// Cylinder of radius r (patch 0) between z = ±length/2, closed by two hemispheres
// (patch 1 on top, 2 below).
Shape make_capsule(double radius, double length, int around, int rings);
// Cylinder (patch 0) closed by two disks (patch 1 on top, 2 below).
Shape make_closed_cylinder(double radius, double height, int around, int rings);

// A grid over [u0,u1]×[v0,v1] mapped through `surface`, all patch 0.
Shape make_grid(const std::function<Vec3(double, double)>& surface, double u0, double u1, double v0, double v1,
                int nu, int nv);

// Adds the mesh's triangles to the soup, moved by `offset` (to build scenes of parts).
void append(PolygonSoup& soup, const Mesh& mesh, const Vec3& offset = Vec3::Zero());

// Applies p → R p + t to every vertex.
void transform(Mesh& mesh, const Eigen::Matrix3d& rotation, const Vec3& translation);

}  // namespace vqsa
