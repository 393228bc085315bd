#include "export/gltf_export.h"

#include "export/palette.h"
#include "export/report.h"

#include <tiny_gltf.h>

#include <algorithm>
#include <cstring>
#include <map>
#include <sstream>

namespace vqsa {

namespace {

tinygltf::Value to_value(const nlohmann::json& j) {
    switch (j.type()) {
        case nlohmann::json::value_t::object: {
            tinygltf::Value::Object o;
            for (auto it = j.begin(); it != j.end(); ++it) o[it.key()] = to_value(it.value());
            return tinygltf::Value(std::move(o));
        }
        case nlohmann::json::value_t::array: {
            tinygltf::Value::Array a;
            for (const auto& v : j) a.push_back(to_value(v));
            return tinygltf::Value(std::move(a));
        }
        case nlohmann::json::value_t::string: return tinygltf::Value(j.get<std::string>());
        case nlohmann::json::value_t::boolean: return tinygltf::Value(j.get<bool>());
        case nlohmann::json::value_t::number_integer:
        case nlohmann::json::value_t::number_unsigned: return tinygltf::Value(j.get<int>());
        case nlohmann::json::value_t::number_float: return tinygltf::Value(j.get<double>());
        default: return tinygltf::Value();
    }
}

// Appends typed data to the one buffer, 8-byte aligned (property tables need it), as a
// new bufferView; returns its index.
class BufferWriter {
public:
    explicit BufferWriter(tinygltf::Model& model) : model_(model) { model_.buffers.emplace_back(); }

    template <typename T>
    int view(const std::vector<T>& data, int target = 0) {
        std::vector<unsigned char>& bytes = model_.buffers[0].data;
        while (bytes.size() % 8) bytes.push_back(0);
        tinygltf::BufferView v;
        v.buffer = 0;
        v.byteOffset = bytes.size();
        v.byteLength = data.size() * sizeof(T);
        v.target = target;
        const auto* raw = reinterpret_cast<const unsigned char*>(data.data());
        bytes.insert(bytes.end(), raw, raw + v.byteLength);
        model_.bufferViews.push_back(v);
        return static_cast<int>(model_.bufferViews.size()) - 1;
    }

    int accessor(int view, int component, int type, std::size_t count, const std::vector<double>& min = {},
                 const std::vector<double>& max = {}) {
        tinygltf::Accessor a;
        a.bufferView = view;
        a.componentType = component;
        a.type = type;
        a.count = count;
        a.minValues = min;
        a.maxValues = max;
        model_.accessors.push_back(a);
        return static_cast<int>(model_.accessors.size()) - 1;
    }

private:
    tinygltf::Model& model_;
};

// Vertices split by region: one glTF vertex per (mesh vertex, region) pair in use.
struct SplitVertices {
    std::vector<int> source;  // mesh vertex of each glTF vertex
    std::vector<int> region;  // its region
    std::vector<std::uint32_t> indices;
};

SplitVertices split_by_region(const std::vector<Triangle>& triangles, const std::vector<int>& labels) {
    SplitVertices out;
    std::map<std::pair<int, int>, std::uint32_t> index;
    for (std::size_t f = 0; f < triangles.size(); ++f)
        for (int v : triangles[f]) {
            const auto [it, inserted] = index.try_emplace({v, labels[f]}, static_cast<std::uint32_t>(out.source.size()));
            if (inserted) {
                out.source.push_back(v);
                out.region.push_back(labels[f]);
            }
            out.indices.push_back(it->second);
        }
    return out;
}

struct Attributes {
    int position, normal;
};

// Positions and area-weighted normals (per region, since vertices are split) of one surface.
Attributes write_surface(BufferWriter& writer, const std::vector<Vec3>& points, const std::vector<Triangle>& triangles,
                         const SplitVertices& split) {
    std::vector<Vec3> normals(split.source.size(), Vec3::Zero());
    for (std::size_t f = 0; f < triangles.size(); ++f) {
        const Vec3 &a = points[triangles[f][0]], &b = points[triangles[f][1]], &c = points[triangles[f][2]];
        const Vec3 n = (b - a).cross(c - a);  // twice the area, along the normal
        for (int k = 0; k < 3; ++k) normals[split.indices[3 * f + k]] += n;
    }
    std::vector<float> position, normal;
    std::vector<double> lo(3, std::numeric_limits<double>::infinity()), hi(3, -std::numeric_limits<double>::infinity());
    for (std::size_t i = 0; i < split.source.size(); ++i) {
        const Vec3& p = points[split.source[i]];
        Vec3 n = normals[i];
        n = n.norm() > 0 ? Vec3(n.normalized()) : Vec3(0, 0, 1);
        for (int k = 0; k < 3; ++k) {
            const float v = static_cast<float>(p[k]);
            position.push_back(v);
            normal.push_back(static_cast<float>(n[k]));
            lo[k] = std::min(lo[k], double(v));
            hi[k] = std::max(hi[k], double(v));
        }
    }
    const std::size_t count = split.source.size();
    return {writer.accessor(writer.view(position, TINYGLTF_TARGET_ARRAY_BUFFER), TINYGLTF_COMPONENT_TYPE_FLOAT,
                            TINYGLTF_TYPE_VEC3, count, lo, hi),
            writer.accessor(writer.view(normal, TINYGLTF_TARGET_ARRAY_BUFFER), TINYGLTF_COMPONENT_TYPE_FLOAT,
                            TINYGLTF_TYPE_VEC3, count)};
}

// The EXT_structural_metadata schema and property table: one row per region.
nlohmann::json metadata(BufferWriter& writer, const std::vector<nlohmann::json>& regions,
                        const std::vector<Classification>& shapes) {
    auto f64 = [](const char* type) { return nlohmann::json{{"type", type}, {"componentType", "FLOAT64"}}; };
    nlohmann::json properties = {
        {"type", {{"type", "STRING"}, {"description", "quadric type"}}},
        {"coefficients", {{"type", "SCALAR"}, {"componentType", "FLOAT64"}, {"array", true}, {"count", 10},
                          {"description", "C0..C9 of C0 + C1 x + C2 y + C3 z + C4 x2 + C5 xy + C6 xz + C7 y2 + C8 yz + C9 z2"}}},
        {"center", f64("VEC3")},     {"axis", f64("VEC3")},      {"rotation", f64("MAT3")},
        {"semi_axes", f64("VEC3")},  {"radius", f64("SCALAR")},  {"half_angle", f64("SCALAR")},
        {"area", f64("SCALAR")},     {"rms_error", f64("SCALAR")},
        {"faces", {{"type", "SCALAR"}, {"componentType", "UINT32"}}},
        {"type_rms", {{"type", "SCALAR"}, {"componentType", "FLOAT64"}, {"description", "RMS distance of the region's vertices to its surface"}}},
        {"runner_up", {{"type", "STRING"}, {"description", "the best other type (empty when types were not selected)"}}},
        {"runner_up_rms", {{"type", "SCALAR"}, {"componentType", "FLOAT64"}, {"description", "its RMS distance (0 when none)"}}}};

    std::vector<std::string> types, runners_up;
    std::vector<std::uint32_t> faces;
    std::vector<double> coefficients, center, axis, rotation, semi_axes, radius, half_angle, area, rms, type_rms, runner_up_rms;
    for (std::size_t i = 0; i < regions.size(); ++i) {
        const nlohmann::json& r = regions[i];
        const Classification& c = shapes[i];
        types.push_back(r["type"].get<std::string>());
        type_rms.push_back(r["type_rms"]);
        const bool runner = r["runner_up"].is_object();
        runners_up.push_back(runner ? r["runner_up"]["type"].get<std::string>() : "");
        runner_up_rms.push_back(runner ? r["runner_up"]["rms"].get<double>() : 0.0);
        for (double v : r["coefficients"]) coefficients.push_back(v);
        for (int k = 0; k < 3; ++k) {
            center.push_back(c.center[k]);
            axis.push_back(c.axis()[k]);
            semi_axes.push_back(c.semi_axes[k]);
        }
        for (int col = 0; col < 3; ++col)
            for (int row = 0; row < 3; ++row) rotation.push_back(c.rotation(row, col));  // column-major
        radius.push_back(c.radius);
        half_angle.push_back(c.half_angle);
        area.push_back(r["area"]);
        rms.push_back(r["rms_error"]);
        faces.push_back(r["faces"]);
    }
    auto strings = [&](const std::vector<std::string>& values) {
        std::string bytes;
        std::vector<std::uint32_t> offsets{0};
        for (const std::string& v : values) bytes += v, offsets.push_back(static_cast<std::uint32_t>(bytes.size()));
        return nlohmann::json{{"values", writer.view(std::vector<char>(bytes.begin(), bytes.end()))},
                              {"stringOffsets", writer.view(offsets)},
                              {"stringOffsetType", "UINT32"}};
    };
    nlohmann::json columns = {
        {"type", strings(types)},
        {"type_rms", {{"values", writer.view(type_rms)}}},
        {"coefficients", {{"values", writer.view(coefficients)}}},
        {"center", {{"values", writer.view(center)}}},
        {"axis", {{"values", writer.view(axis)}}},
        {"rotation", {{"values", writer.view(rotation)}}},
        {"semi_axes", {{"values", writer.view(semi_axes)}}},
        {"radius", {{"values", writer.view(radius)}}},
        {"half_angle", {{"values", writer.view(half_angle)}}},
        {"area", {{"values", writer.view(area)}}},
        {"rms_error", {{"values", writer.view(rms)}}},
        {"faces", {{"values", writer.view(faces)}}}};
    // With no runner-up anywhere (types not selected, or regions too small for a second
    // candidate) the columns are left out: glTF allows no empty buffer view, and a
    // property the table does not list has no data.
    if (std::any_of(runners_up.begin(), runners_up.end(), [](const std::string& t) { return !t.empty(); })) {
        columns["runner_up"] = strings(runners_up);
        columns["runner_up_rms"] = {{"values", writer.view(runner_up_rms)}};
    }
    return {{"schema", {{"id", "vqsa"}, {"classes", {{"region", {{"name", "Region"}, {"properties", properties}}}}}}},
            {"propertyTables", {{{"name", "regions"}, {"class", "region"}, {"count", regions.size()}, {"properties", columns}}}}};
}

}  // namespace

GlbColours glb_colours_from(const std::string& name) {
    if (name == "region") return GlbColours::region;
    if (name == "type") return GlbColours::type;
    throw std::invalid_argument("GLB colours must be 'region' or 'type', not '" + name + "'");
}

std::string export_glb(const Mesh& mesh, const Result& result, GlbColours colours) {
    const std::vector<int>& labels = result.face_labels;
    const int regions = static_cast<int>(result.proxies.size());

    tinygltf::Model gltf;
    gltf.asset.version = "2.0";
    gltf.asset.generator = std::string("vqsa ") + VQSA_VERSION;
    gltf.extensionsUsed = {"EXT_mesh_features", "EXT_structural_metadata"};
    BufferWriter writer(gltf);

    std::vector<nlohmann::json> region_data;
    std::vector<Classification> shapes;
    std::vector<Vec3> colors;
    for (int i = 0; i < regions; ++i) {
        nlohmann::json r = proxy_report(result, i);
        shapes.push_back(result.proxies[i].shape);
        colors.push_back(colours == GlbColours::type ? type_color(result.proxies[i].type) : region_color(i));
        r["feature_id"] = i;
        r["color"] = {colors.back().x(), colors.back().y(), colors.back().z()};
        region_data.push_back(r);
    }

    const SplitVertices split = split_by_region(mesh.triangles, labels);
    const std::size_t count = split.source.size();
    std::vector<float> color;
    for (int r : split.region)
        for (int k = 0; k < 3; ++k) color.push_back(static_cast<float>(colors[r][k]));
    const int color_accessor = writer.accessor(writer.view(color, TINYGLTF_TARGET_ARRAY_BUFFER),
                                               TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, count);
    int feature_accessor;
    if (regions <= 65536) {
        // Vertex attributes start on 4-byte boundaries: one id and two bytes of padding each.
        std::vector<std::uint16_t> ids;
        for (int r : split.region) ids.push_back(static_cast<std::uint16_t>(r)), ids.push_back(0);
        const int view = writer.view(ids, TINYGLTF_TARGET_ARRAY_BUFFER);
        gltf.bufferViews[view].byteStride = 4;
        feature_accessor =
            writer.accessor(view, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, TINYGLTF_TYPE_SCALAR, count);
    } else {
        std::vector<float> ids(split.region.begin(), split.region.end());
        feature_accessor = writer.accessor(writer.view(ids, TINYGLTF_TARGET_ARRAY_BUFFER), TINYGLTF_COMPONENT_TYPE_FLOAT,
                                           TINYGLTF_TYPE_SCALAR, count);
    }
    int index_accessor;
    if (count <= 65535) {
        std::vector<std::uint16_t> small(split.indices.begin(), split.indices.end());
        index_accessor = writer.accessor(writer.view(small, TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER),
                                         TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, TINYGLTF_TYPE_SCALAR, small.size());
    } else {
        index_accessor = writer.accessor(writer.view(split.indices, TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER),
                                         TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, TINYGLTF_TYPE_SCALAR, split.indices.size());
    }

    tinygltf::Material material;
    material.name = "regions";
    material.pbrMetallicRoughness.metallicFactor = 0.0;
    material.pbrMetallicRoughness.roughnessFactor = 0.8;
    material.doubleSided = true;
    gltf.materials.push_back(material);

    const nlohmann::json features = {
        {"featureIds", {{{"featureCount", regions}, {"attribute", 0}, {"propertyTable", 0}, {"label", "region"}}}}};
    auto add_mesh = [&](const std::string& name, const std::vector<Vec3>& points, nlohmann::json extras) {
        const Attributes a = write_surface(writer, points, mesh.triangles, split);
        tinygltf::Primitive primitive;
        primitive.attributes = {{"POSITION", a.position},
                                {"NORMAL", a.normal},
                                {"COLOR_0", color_accessor},
                                {"_FEATURE_ID_0", feature_accessor}};
        primitive.indices = index_accessor;
        primitive.material = 0;
        primitive.mode = TINYGLTF_MODE_TRIANGLES;
        primitive.extensions["EXT_mesh_features"] = to_value(features);
        tinygltf::Mesh m;
        m.name = name;
        m.primitives.push_back(primitive);
        m.extras = to_value(extras);
        gltf.meshes.push_back(m);
        tinygltf::Node node;
        node.name = name;
        node.mesh = static_cast<int>(gltf.meshes.size()) - 1;
        gltf.nodes.push_back(node);
    };

    add_mesh("input", mesh.vertices, {{"regions", region_data}});
    if (!result.projected.empty()) add_mesh("projected", result.projected, {{"regions_of", "input"}});

    gltf.extensions["EXT_structural_metadata"] = to_value(metadata(writer, region_data, shapes));
    gltf.buffers[0].data.resize((gltf.buffers[0].data.size() + 3) / 4 * 4, 0);

    nlohmann::json run = run_report(result);
    run["legend"] = palette_json()["types"];
    std::vector<int> dropped;
    for (std::size_t k = 0, f = 0; f < static_cast<std::size_t>(mesh.input_face_count); ++f) {
        if (k < mesh.source_face.size() && mesh.source_face[k] == static_cast<int>(f)) ++k;
        else dropped.push_back(static_cast<int>(f));
    }
    run["dropped_faces"] = dropped;
    // The projected mesh lies where the input does: in a scene of its own, so that a
    // viewer showing the default scene shows one surface, not two fighting for depth.
    tinygltf::Scene scene;
    scene.name = "vqsa";
    scene.nodes = {0};
    scene.extras = to_value(run);
    gltf.scenes.push_back(scene);
    if (gltf.nodes.size() > 1) {
        tinygltf::Scene projected;
        projected.name = "projection";
        projected.nodes = {1};
        gltf.scenes.push_back(projected);
    }
    gltf.defaultScene = 0;

    std::ostringstream out;
    tinygltf::TinyGLTF writer_gltf;
    if (!writer_gltf.WriteGltfSceneToStream(&gltf, out, false, true))
        throw std::runtime_error("glTF export: tinygltf could not write the file");
    return out.str();
}

}  // namespace vqsa
