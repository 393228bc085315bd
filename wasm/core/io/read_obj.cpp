#include "io/mesh_io.h"
#include "io/text_tokenizer.h"

#include <vector>

namespace vqsa {

PolygonSoup read_obj(std::string_view text) {
    TextTokenizer in(text);
    PolygonSoup soup;
    std::vector<int> polygon;
    bool recognised = false;
    while (!in.at_end()) {
        const std::string_view keyword = in.token("a keyword");
        if (keyword == "v") {
            soup.positions.push_back(in.point());
            recognised = true;
        } else if (keyword == "f") {
            polygon.clear();
            for (std::string_view t = in.token_on_line(); !t.empty(); t = in.token_on_line()) {
                // A backslash at the end of a line continues the face on the next (Rhino
                // writes long polygons so).
                if (t == "\\" && in.continue_line()) continue;
                std::int64_t v;
                if (!parse_integer(t.substr(0, t.find('/')), v) || v == 0)
                    in.fail("bad face vertex '" + std::string(t.substr(0, 40)) + "'");
                // Negative indices count back from the latest vertex.
                const std::int64_t index = v > 0 ? v - 1 : static_cast<std::int64_t>(soup.positions.size()) + v;
                if (index < 0 || index > INT32_MAX) in.fail("face vertex " + std::to_string(v) + " is out of range");
                polygon.push_back(static_cast<int>(index));
            }
            if (polygon.size() < 3) in.fail("a face with fewer than three vertices");
            soup.add_polygon(polygon.data(), polygon.size());
            recognised = true;
        }
        in.skip_line();  // normals, texture coordinates, groups, materials: not needed
    }
    if (!recognised) throw std::invalid_argument("no vertices or faces found (not an OBJ file?)");
    return soup;
}

}  // namespace vqsa
