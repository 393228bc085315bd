// The planar VSA peer (Cohen-Steiner et al. 2004, CGAL's implementation, L21 metric,
// hierarchical seeding, 20 iterations) at a given proxy count, its output mesh measured
// with vqsa's own metric. Built only by the benchmark script (Debian libcgal-dev).
// Usage: planar_vsa MESH PROXIES [RUNS] → one JSON line.
#include "io/mesh_io.h"
#include "post/metrics.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Variational_shape_approximation.h>

#include <algorithm>
#include <chrono>
#include <cstdio>

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using SurfaceMesh = CGAL::Surface_mesh<Kernel::Point_3>;
using VertexPointMap = SurfaceMesh::Property_map<SurfaceMesh::Vertex_index, Kernel::Point_3>;
using Approximation = CGAL::Variational_shape_approximation<SurfaceMesh, VertexPointMap>;
namespace VSA = CGAL::Surface_mesh_approximation;

int main(int argc, char** argv) {
    if (argc < 3) {
        std::fprintf(stderr, "usage: planar_vsa MESH PROXIES [RUNS]\n");
        return 2;
    }
    const vqsa::Mesh mesh = vqsa::read_mesh_file(argv[1]);
    const std::size_t proxies = std::stoul(argv[2]);
    const int runs = argc > 3 ? std::max(1, std::atoi(argv[3])) : 1;

    SurfaceMesh sm;
    std::vector<SurfaceMesh::Vertex_index> vertex;
    for (const vqsa::Vec3& p : mesh.vertices) vertex.push_back(sm.add_vertex(Kernel::Point_3(p.x(), p.y(), p.z())));
    int rejected = 0;
    for (const vqsa::Triangle& t : mesh.triangles)
        if (sm.add_face(vertex[t[0]], vertex[t[1]], vertex[t[2]]) == SurfaceMesh::null_face()) ++rejected;
    sm.collect_garbage();

    std::vector<double> seconds, meshing;
    std::vector<vqsa::Vec3> anchors;
    std::vector<vqsa::Triangle> triangles;
    std::size_t found = 0;
    for (int r = 0; r < runs; ++r) {
        const auto t0 = std::chrono::steady_clock::now();
        Approximation::Error_metric metric(sm, get(CGAL::vertex_point, sm));
        Approximation approx(sm, get(CGAL::vertex_point, sm), metric);
        approx.initialize_seeds(CGAL::parameters::seeding_method(VSA::HIERARCHICAL).max_number_of_proxies(proxies));
        approx.run(20);
        const auto t1 = std::chrono::steady_clock::now();
        approx.extract_mesh(CGAL::parameters::subdivision_ratio(5.0));
        const auto t2 = std::chrono::steady_clock::now();
        seconds.push_back(std::chrono::duration<double>(t1 - t0).count());
        meshing.push_back(std::chrono::duration<double>(t2 - t1).count());
        found = approx.number_of_proxies();
        if (r == 0) {
            std::vector<Kernel::Point_3> points;
            std::vector<std::array<std::size_t, 3>> faces;
            approx.anchor_points(std::back_inserter(points));
            approx.indexed_triangles(std::back_inserter(faces));
            for (const auto& p : points) anchors.emplace_back(p.x(), p.y(), p.z());
            for (const auto& f : faces) triangles.push_back({int(f[0]), int(f[1]), int(f[2])});
        }
    }
    std::sort(seconds.begin(), seconds.end());
    std::sort(meshing.begin(), meshing.end());
    const vqsa::SurfaceDistance d = triangles.empty()
                                        ? vqsa::SurfaceDistance{-1, -1}
                                        : vqsa::compare_surfaces(mesh.vertices, mesh.triangles, anchors, triangles);
    std::printf("{\"mesh\": \"%s\", \"faces\": %zu, \"proxies\": %zu, \"vsa_s\": %.4f, \"meshing_s\": %.4f, "
                "\"rms\": %.4e, \"hausdorff\": %.4e, \"output_triangles\": %zu, \"rejected_faces\": %d}\n",
                argv[1], mesh.triangles.size(), found, seconds[seconds.size() / 2], meshing[meshing.size() / 2], d.rms,
                d.hausdorff, triangles.size(), rejected);
    return 0;
}
