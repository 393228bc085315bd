// libFuzzer target for the whole pipeline on small meshes: load → approximate → smooth →
// classify and refit → project → measure → report → GLB. The first byte picks the proxy
// count, the second the format.
#include "lloyd/engine.h"
#include "export/gltf_export.h"
#include "io/mesh_io.h"
#include "export/report.h"

#include <algorithm>
#include <cstddef>
#include <cstdint>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    if (size < 3) return 0;
    static const char* const names[] = {"f.off", "f.obj", "f.ply", "f.stl", "f.glb"};
    try {
        const vqsa::Mesh mesh = vqsa::read_mesh(names[data[1] % 5], data + 2, size - 2);
        if (mesh.triangles.size() > 4000) return 0;  // small meshes: many executions
        vqsa::EngineOptions options;
        options.proxies = std::min<int>(1 + data[0] % 8, static_cast<int>(mesh.triangles.size()));
        options.max_iterations = 300;
        options.metrics.samples = 2000;
        vqsa::Engine engine(mesh, options);
        engine.run();
        vqsa::make_report(mesh, engine, {}).dump();
        vqsa::export_glb(mesh, engine);
    } catch (const vqsa::MeshReadError&) {
    }
    return 0;
}
