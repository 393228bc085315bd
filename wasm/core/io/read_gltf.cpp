#include "io/mesh_io.h"

#include <Eigen/Geometry>
#include <tiny_gltf.h>

#include <cstring>

namespace vqsa {

namespace {

// Images are irrelevant to geometry: accept them without decoding.
bool ignore_image(tinygltf::Image*, const int, std::string*, std::string*, int, int, const unsigned char*, int,
                  void*) {
    return true;
}

const unsigned char* accessor_data(const tinygltf::Model& model, const tinygltf::Accessor& accessor,
                                   std::size_t element_size, std::size_t& stride) {
    if (accessor.sparse.isSparse) throw std::invalid_argument("sparse accessors are not supported");
    if (accessor.bufferView < 0 || accessor.bufferView >= static_cast<int>(model.bufferViews.size()))
        throw std::invalid_argument("an accessor has no valid bufferView");
    const tinygltf::BufferView& view = model.bufferViews[accessor.bufferView];
    if (view.buffer < 0 || view.buffer >= static_cast<int>(model.buffers.size()))
        throw std::invalid_argument("a bufferView has no valid buffer");
    const std::vector<unsigned char>& buffer = model.buffers[view.buffer].data;
    stride = view.byteStride ? view.byteStride : element_size;
    const std::uint64_t begin = std::uint64_t{view.byteOffset} + accessor.byteOffset;
    const std::uint64_t needed = accessor.count == 0 ? 0 : stride * (accessor.count - 1) + element_size;
    if (begin + needed > view.byteOffset + view.byteLength || view.byteOffset + view.byteLength > buffer.size())
        throw std::invalid_argument("an accessor reaches past the end of its buffer");
    return buffer.data() + begin;
}

double read_component(const unsigned char* p, int component_type, bool normalized) {
    switch (component_type) {
        case TINYGLTF_COMPONENT_TYPE_FLOAT: { float v; std::memcpy(&v, p, 4); return v; }
        case TINYGLTF_COMPONENT_TYPE_BYTE: { const double v = std::int8_t(p[0]); return normalized ? std::max(v / 127.0, -1.0) : v; }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return normalized ? p[0] / 255.0 : p[0];
        case TINYGLTF_COMPONENT_TYPE_SHORT: {
            std::int16_t v; std::memcpy(&v, p, 2);
            return normalized ? std::max(v / 32767.0, -1.0) : v;
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
            std::uint16_t v; std::memcpy(&v, p, 2);
            return normalized ? v / 65535.0 : v;
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: { std::uint32_t v; std::memcpy(&v, p, 4); return v; }
        default: throw std::invalid_argument("unsupported accessor component type");
    }
}

Eigen::Matrix4d node_matrix(const tinygltf::Node& node) {
    Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
    if (node.matrix.size() == 16) {
        for (int i = 0; i < 16; ++i) m(i % 4, i / 4) = node.matrix[i];  // column-major
        return m;
    }
    Eigen::Affine3d t = Eigen::Affine3d::Identity();
    if (node.translation.size() == 3) t.translate(Vec3(node.translation[0], node.translation[1], node.translation[2]));
    if (node.rotation.size() == 4)
        t.rotate(Eigen::Quaterniond(node.rotation[3], node.rotation[0], node.rotation[1], node.rotation[2]).normalized());
    if (node.scale.size() == 3) t.scale(Vec3(node.scale[0], node.scale[1], node.scale[2]));
    return t.matrix();
}

void append_primitive(const tinygltf::Model& model, const tinygltf::Primitive& primitive, const Eigen::Matrix4d& world,
                      PolygonSoup& soup) {
    const int mode = primitive.mode < 0 ? TINYGLTF_MODE_TRIANGLES : primitive.mode;
    if (mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP && mode != TINYGLTF_MODE_TRIANGLE_FAN)
        return;  // points and lines carry no surface
    const auto position = primitive.attributes.find("POSITION");
    if (position == primitive.attributes.end()) return;
    if (position->second < 0 || position->second >= static_cast<int>(model.accessors.size()))
        throw std::invalid_argument("a primitive's POSITION accessor does not exist");
    const tinygltf::Accessor& pa = model.accessors[position->second];
    if (pa.type != TINYGLTF_TYPE_VEC3) throw std::invalid_argument("POSITION is not a VEC3 accessor");
    const std::size_t component = tinygltf::GetComponentSizeInBytes(pa.componentType);
    if (component == std::size_t(-1) || component == 0) throw std::invalid_argument("bad POSITION component type");
    std::size_t stride;
    const unsigned char* data = accessor_data(model, pa, 3 * component, stride);
    const int base = static_cast<int>(soup.positions.size());
    for (std::size_t i = 0; i < pa.count; ++i) {
        const unsigned char* p = data + i * stride;
        const Eigen::Vector4d local(read_component(p, pa.componentType, pa.normalized),
                                    read_component(p + component, pa.componentType, pa.normalized),
                                    read_component(p + 2 * component, pa.componentType, pa.normalized), 1.0);
        soup.positions.push_back((world * local).head<3>());
    }

    std::vector<int> order;
    if (primitive.indices >= 0) {
        if (primitive.indices >= static_cast<int>(model.accessors.size()))
            throw std::invalid_argument("a primitive's index accessor does not exist");
        const tinygltf::Accessor& ia = model.accessors[primitive.indices];
        const std::size_t size = tinygltf::GetComponentSizeInBytes(ia.componentType);
        if (ia.type != TINYGLTF_TYPE_SCALAR || !(size == 1 || size == 2 || size == 4))
            throw std::invalid_argument("indices are not unsigned integer scalars");
        const unsigned char* idx = accessor_data(model, ia, size, stride);
        order.reserve(ia.count);
        for (std::size_t i = 0; i < ia.count; ++i) {
            const double v = read_component(idx + i * stride, ia.componentType, false);
            if (v >= static_cast<double>(pa.count))
                throw std::invalid_argument("index " + std::to_string(static_cast<std::uint64_t>(v)) +
                                            " is out of range (" + std::to_string(pa.count) + " positions)");
            order.push_back(base + static_cast<int>(v));
        }
    } else {
        for (std::size_t i = 0; i < pa.count; ++i) order.push_back(base + static_cast<int>(i));
    }

    const bool flip = world.topLeftCorner<3, 3>().determinant() < 0;
    auto add = [&](int a, int b, int c) {
        const int t[3] = {a, flip ? c : b, flip ? b : c};
        soup.add_polygon(t, 3);
    };
    if (mode == TINYGLTF_MODE_TRIANGLES) {
        for (std::size_t i = 0; i + 2 < order.size(); i += 3) add(order[i], order[i + 1], order[i + 2]);
    } else if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
        for (std::size_t i = 0; i + 2 < order.size(); ++i)
            i % 2 ? add(order[i + 1], order[i], order[i + 2]) : add(order[i], order[i + 1], order[i + 2]);
    } else {
        for (std::size_t i = 1; i + 1 < order.size(); ++i) add(order[0], order[i], order[i + 1]);
    }
}

void append_node(const tinygltf::Model& model, int index, const Eigen::Matrix4d& parent, int depth, PolygonSoup& soup) {
    if (index < 0 || index >= static_cast<int>(model.nodes.size())) throw std::invalid_argument("a node index is out of range");
    if (depth > 256) throw std::invalid_argument("the node hierarchy is too deep (cyclic?)");
    const tinygltf::Node& node = model.nodes[index];
    const Eigen::Matrix4d world = parent * node_matrix(node);
    if (node.mesh >= 0) {
        if (node.mesh >= static_cast<int>(model.meshes.size())) throw std::invalid_argument("a node's mesh does not exist");
        for (const tinygltf::Primitive& primitive : model.meshes[node.mesh].primitives)
            append_primitive(model, primitive, world, soup);
    }
    for (int child : node.children) append_node(model, child, world, depth + 1, soup);
}

}  // namespace

PolygonSoup read_gltf(std::string_view bytes, bool binary, const std::string& base_dir) {
    tinygltf::TinyGLTF loader;
    loader.SetImageLoader(ignore_image, nullptr);
    tinygltf::Model model;
    std::string err, warn;
    const bool ok =
        binary ? loader.LoadBinaryFromMemory(&model, &err, &warn, reinterpret_cast<const unsigned char*>(bytes.data()),
                                             static_cast<unsigned int>(bytes.size()), base_dir)
               : loader.LoadASCIIFromString(&model, &err, &warn, bytes.data(), static_cast<unsigned int>(bytes.size()),
                                            base_dir);
    if (!ok) {
        while (!err.empty() && err.back() == '\n') err.pop_back();
        throw std::invalid_argument(err.empty() ? "not a valid glTF file" : err);
    }

    PolygonSoup soup;
    std::vector<int> roots;
    const int scene = model.defaultScene >= 0 ? model.defaultScene : (model.scenes.empty() ? -1 : 0);
    if (scene >= 0 && scene < static_cast<int>(model.scenes.size())) {
        roots = model.scenes[scene].nodes;
    } else {
        std::vector<bool> is_child(model.nodes.size(), false);
        for (const tinygltf::Node& n : model.nodes)
            for (int c : n.children)
                if (c >= 0 && c < static_cast<int>(is_child.size())) is_child[c] = true;
        for (std::size_t i = 0; i < model.nodes.size(); ++i)
            if (!is_child[i]) roots.push_back(static_cast<int>(i));
    }
    for (int root : roots) append_node(model, root, Eigen::Matrix4d::Identity(), 0, soup);
    if (soup.polygon_count() == 0) throw std::invalid_argument("the glTF scene has no triangles");
    return soup;
}

}  // namespace vqsa
