// Mesh readers: OFF, OBJ, PLY (ASCII, binary), STL (ASCII, binary), glTF/GLB.
#pragma once

#include "io/mesh.h"

#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>

namespace vqsa {

// Every reading problem, with the file's name and what is wrong with it.
class MeshReadError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// Reads and cleans a mesh (see build_mesh). The format is chosen by the name's
// extension; `name` also prefixes every error message.
Mesh read_mesh(std::string_view name, const std::uint8_t* data, std::size_t size);
Mesh read_mesh_file(const std::string& path);

// Format readers: raw polygons as stored. They throw std::invalid_argument saying
// what is wrong; read_mesh adds the file name.
PolygonSoup read_off(std::string_view text);
PolygonSoup read_obj(std::string_view text);
PolygonSoup read_ply(std::string_view bytes);
PolygonSoup read_stl(std::string_view bytes);
// `base_dir` resolves external buffers of a .gltf; empty means only embedded data.
PolygonSoup read_gltf(std::string_view bytes, bool binary, const std::string& base_dir);

}  // namespace vqsa
