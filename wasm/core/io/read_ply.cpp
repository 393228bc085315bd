#include "io/mesh_io.h"
#include "io/text_tokenizer.h"

#include <cstdio>
#include <cstring>
#include <vector>

namespace vqsa {

namespace {

enum class Encoding { ascii, little_endian, big_endian };

struct ScalarType {
    int size = 0;
    bool is_float = false;
    bool is_signed = false;
};

ScalarType scalar_type(std::string_view name) {
    if (name == "char" || name == "int8") return {1, false, true};
    if (name == "uchar" || name == "uint8") return {1, false, false};
    if (name == "short" || name == "int16") return {2, false, true};
    if (name == "ushort" || name == "uint16") return {2, false, false};
    if (name == "int" || name == "int32") return {4, false, true};
    if (name == "uint" || name == "uint32") return {4, false, false};
    if (name == "float" || name == "float32") return {4, true, true};
    if (name == "double" || name == "float64") return {8, true, true};
    throw std::invalid_argument("unknown PLY property type '" + std::string(name) + "'");
}

struct Property {
    std::string name;
    ScalarType type;
    bool is_list = false;
    ScalarType count_type;
};

struct Element {
    std::string name;
    std::int64_t count = 0;
    std::vector<Property> properties;
};

// Reads the body's values one at a time, whatever the encoding.
class BodyReader {
public:
    BodyReader(std::string_view body, Encoding encoding) : body_(body), encoding_(encoding), text_(body) {}

    double read(const ScalarType& type) {
        if (encoding_ == Encoding::ascii) return text_.number("a PLY value");
        if (pos_ + type.size > body_.size()) throw std::invalid_argument("the binary body is truncated");
        unsigned char raw[8];
        std::memcpy(raw, body_.data() + pos_, type.size);
        pos_ += type.size;
        if (encoding_ == Encoding::big_endian)
            for (int i = 0; i < type.size / 2; ++i) std::swap(raw[i], raw[type.size - 1 - i]);
        switch (type.size) {
            case 1: return type.is_signed ? double(std::int8_t(raw[0])) : double(raw[0]);
            case 2: {
                std::uint16_t v; std::memcpy(&v, raw, 2);
                return type.is_signed ? double(std::int16_t(v)) : double(v);
            }
            case 4: {
                if (type.is_float) { float v; std::memcpy(&v, raw, 4); return v; }
                std::uint32_t v; std::memcpy(&v, raw, 4);
                return type.is_signed ? double(std::int32_t(v)) : double(v);
            }
            default: { double v; std::memcpy(&v, raw, 8); return v; }
        }
    }

    std::size_t remaining() const { return encoding_ == Encoding::ascii ? body_.size() : body_.size() - pos_; }

private:
    std::string_view body_;
    Encoding encoding_;
    std::size_t pos_ = 0;
    TextTokenizer text_;
};

}  // namespace

PolygonSoup read_ply(std::string_view bytes) {
    const std::size_t header_end = bytes.find("end_header");
    if (bytes.substr(0, 3) != "ply") throw std::invalid_argument("not a PLY file: it does not start with 'ply'");
    if (header_end == std::string_view::npos) throw std::invalid_argument("the PLY header has no 'end_header'");
    std::size_t body_start = bytes.find('\n', header_end);
    body_start = body_start == std::string_view::npos ? bytes.size() : body_start + 1;

    TextTokenizer header(bytes.substr(0, header_end), '\0');
    header.token("ply");
    Encoding encoding = Encoding::ascii;
    bool has_format = false;
    std::vector<Element> elements;
    while (!header.at_end()) {
        const std::string_view keyword = header.token("a header keyword");
        if (keyword == "format") {
            const std::string_view f = header.token("the format");
            if (f == "ascii") encoding = Encoding::ascii;
            else if (f == "binary_little_endian") encoding = Encoding::little_endian;
            else if (f == "binary_big_endian") encoding = Encoding::big_endian;
            else header.fail("unknown PLY format '" + std::string(f) + "'");
            has_format = true;
            header.skip_line();
        } else if (keyword == "element") {
            Element e;
            e.name = std::string(header.token("an element name"));
            e.count = header.integer("an element count");
            if (e.count < 0) header.fail("negative element count");
            elements.push_back(std::move(e));
        } else if (keyword == "property") {
            if (elements.empty()) header.fail("a property before any element");
            Property p;
            std::string_view type = header.token("a property type");
            if (type == "list") {
                p.is_list = true;
                p.count_type = scalar_type(header.token("a list count type"));
                if (p.count_type.is_float) header.fail("a list count must be an integer type");
                type = header.token("a list item type");
            }
            p.type = scalar_type(type);
            p.name = std::string(header.token("a property name"));
            elements.back().properties.push_back(std::move(p));
        } else {
            header.skip_line();  // comment, obj_info
        }
    }
    if (!has_format) throw std::invalid_argument("the PLY header has no 'format' line");

    const std::size_t body_size = bytes.size() - body_start;
    BodyReader body(bytes.substr(body_start), encoding);
    PolygonSoup soup;
    bool has_vertices = false, has_faces = false;
    std::vector<int> polygon;
    for (const Element& e : elements) {
        // Every record takes at least one byte (two characters in ASCII): larger counts are lies.
        if (static_cast<std::uint64_t>(e.count) > body_size)
            throw std::invalid_argument("the header announces " + std::to_string(e.count) + " " + e.name +
                                        " elements, more than the file can hold (truncated or corrupt)");
        int xyz[3] = {-1, -1, -1};
        int face_list = -1;
        for (std::size_t i = 0; i < e.properties.size(); ++i) {
            const Property& p = e.properties[i];
            if (!p.is_list && p.name.size() == 1 && p.name[0] >= 'x' && p.name[0] <= 'z') xyz[p.name[0] - 'x'] = int(i);
            if (p.is_list && face_list < 0 && (p.name == "vertex_indices" || p.name == "vertex_index")) face_list = int(i);
        }
        const bool is_vertex = e.name == "vertex", is_face = e.name == "face";
        if (is_vertex) {
            if (xyz[0] < 0 || xyz[1] < 0 || xyz[2] < 0) throw std::invalid_argument("the vertex element lacks x, y or z");
            has_vertices = true;
            soup.positions.reserve(static_cast<std::size_t>(e.count));
        }
        if (is_face) {
            if (face_list < 0) throw std::invalid_argument("the face element has no vertex_indices list");
            has_faces = true;
        }
        for (std::int64_t r = 0; r < e.count; ++r) {
            Vec3 position = Vec3::Zero();
            for (std::size_t i = 0; i < e.properties.size(); ++i) {
                const Property& p = e.properties[i];
                if (!p.is_list) {
                    const double v = body.read(p.type);
                    for (int k = 0; k < 3; ++k)
                        if (int(i) == xyz[k]) position[k] = v;
                    continue;
                }
                const double n = body.read(p.count_type);
                if (!(n >= 0 && n <= static_cast<double>(body.remaining()))) {
                    char count[32];
                    std::snprintf(count, sizeof count, "%.0f", n);  // n may be far beyond any integer type
                    throw std::invalid_argument("a " + e.name + " list of " + count + " items, more than the file holds");
                }
                if (int(i) == face_list && is_face) polygon.clear();
                for (int k = 0; k < static_cast<int>(n); ++k) {
                    const double v = body.read(p.type);
                    if (int(i) == face_list && is_face) {
                        if (v < 0 || v > INT32_MAX || v != static_cast<double>(static_cast<std::int64_t>(v)))
                            throw std::invalid_argument("face " + std::to_string(r) + " has a bad vertex index " +
                                                        std::to_string(v));
                        polygon.push_back(static_cast<int>(v));
                    }
                }
                if (int(i) == face_list && is_face) soup.add_polygon(polygon.data(), polygon.size());
            }
            if (is_vertex) soup.positions.push_back(position);
        }
    }
    if (!has_vertices || !has_faces) throw std::invalid_argument("the PLY file has no vertex or no face element");
    return soup;
}

}  // namespace vqsa
