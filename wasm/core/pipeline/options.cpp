#include "pipeline/options.h"

#include <cmath>
#include <cstdlib>
#include <stdexcept>

namespace vqsa {

namespace {

using nlohmann::json;

// The largest integer a JavaScript number holds exactly: seeds travel through JS.
constexpr double kMaxSafeInteger = 9007199254740991.0;

std::vector<OptionSpec> make_schema() {
    std::vector<OptionSpec> s;
    s.push_back({"proxies", OptionKind::count, 1, 1e6, {},
                 "stop at this many proxies; 'auto' grows until more proxies no longer pay",
                 [](Options& o, const json& v) { o.lloyd.proxies = v.is_string() ? 0 : v.get<int>(); },
                 [](const Options& o) { return o.lloyd.proxies > 0 ? json(o.lloyd.proxies) : json("auto"); }});
    s.push_back({"tolerance", OptionKind::number, 0, 1, {},
                 "stop once the RMS distance, relative to the longest bounding-box side, is below this (0: off)",
                 [](Options& o, const json& v) { o.lloyd.tolerance = v.get<double>(); },
                 [](const Options& o) { return json(o.lloyd.tolerance); }, 0.002});
    s.push_back({"max-iterations", OptionKind::integer, 1, 1e8, {}, "cap on Lloyd iterations in all",
                 [](Options& o, const json& v) { o.lloyd.max_iterations = v.get<int>(); },
                 [](const Options& o) { return json(o.lloyd.max_iterations); }});
    s.push_back({"seed", OptionKind::integer, 0, kMaxSafeInteger, {},
                 "drives the random choices (the seed faces within charts; with init 'paper' none matter); the same seed gives the same result",
                 [](Options& o, const json& v) { o.lloyd.seed = static_cast<std::uint64_t>(v.get<double>()); },
                 [](const Options& o) { return json(o.lloyd.seed); }});
    s.push_back({"init", OptionKind::choice, 0, 0, {"features", "paper"},
                 "seeding: 'features' (charts between sharp creases first) or 'paper' (one seed per component, farthest-point insertion)",
                 [](Options& o, const json& v) {
                     o.lloyd.init = v == "paper" ? Initialization::paper : Initialization::features;
                 },
                 [](const Options& o) { return json(o.lloyd.init == Initialization::paper ? "paper" : "features"); }});
    s.push_back({"crease-angle", OptionKind::number, 0, 180, {},
                 "dihedral angle, in degrees, above which an edge is a sharp crease (180: none)",
                 [](Options& o, const json& v) { o.lloyd.features.crease_angle = v.get<double>(); },
                 [](const Options& o) { return json(o.lloyd.features.crease_angle); }});
    s.push_back({"smooth", OptionKind::boolean, 0, 0, {}, "smooth the region boundaries by graph cut",
                 [](Options& o, const json& v) { o.smooth = v.get<bool>(); },
                 [](const Options& o) { return json(o.smooth); }});
    s.push_back({"rings", OptionKind::integer, 1, 100, {}, "width of the smoothing band, in face rings each side",
                 [](Options& o, const json& v) { o.smoothing.rings = v.get<int>(); },
                 [](const Options& o) { return json(o.smoothing.rings); }});
    s.push_back({"lambda", OptionKind::number, 0, 1e6, {}, "weight of boundary length against distance in the smoothing",
                 [](Options& o, const json& v) { o.smoothing.lambda = v.get<double>(); },
                 [](const Options& o) { return json(o.smoothing.lambda); }});
    s.push_back({"refit", OptionKind::boolean, 0, 0, {},
                 "choose each region's type (plane, sphere, cylinder, cone, paraboloid or general quadric) by model selection (a region whose quadric is a plane pair, or has two parts it lies on, always is)",
                 [](Options& o, const json& v) { o.refit = v.get<bool>(); },
                 [](const Options& o) { return json(o.refit); }});
    s.push_back({"project", OptionKind::boolean, 0, 0, {}, "project the mesh onto the proxies",
                 [](Options& o, const json& v) { o.project = v.get<bool>(); },
                 [](const Options& o) { return json(o.project); }});
    s.push_back({"measure", OptionKind::boolean, 0, 0, {},
                 "measure the distance between the input and the projected mesh",
                 [](Options& o, const json& v) { o.measure = v.get<bool>(); },
                 [](const Options& o) { return json(o.measure); }});
    return s;
}

std::string describe(const OptionSpec& spec) {
    auto number = [](double v) {
        const json j = v == std::floor(v) && std::abs(v) <= kMaxSafeInteger ? json(static_cast<long long>(v)) : json(v);
        return j.dump();
    };
    switch (spec.kind) {
        case OptionKind::count: return "an integer between " + number(spec.min) + " and " + number(spec.max) + " or 'auto'";
        case OptionKind::integer: return "an integer between " + number(spec.min) + " and " + number(spec.max);
        case OptionKind::number: return "a number between " + number(spec.min) + " and " + number(spec.max);
        case OptionKind::boolean: return "true or false";
        case OptionKind::choice: {
            std::string out = "one of";
            for (const std::string& c : spec.choices) out += " '" + c + "'";
            return out;
        }
    }
    return "";
}

// The words a boolean option reads (from the CLI's JSON, an element's attribute).
const std::pair<const char*, bool> boolean_words[] = {{"true", true},  {"1", true},  {"yes", true}, {"on", true},
                                                      {"false", false}, {"0", false}, {"no", false}, {"off", false}};

// The value checked against the spec and normalised: a number, a bool, or (count) "auto".
json normalised(const OptionSpec& spec, const json& value) {
    auto fail = [&]() -> json {
        throw std::invalid_argument(spec.name + " must be " + describe(spec) + ", not " + value.dump());
    };
    if (spec.kind == OptionKind::boolean) {
        if (value.is_boolean()) return value;
        if (value.is_number() && (value == 0 || value == 1)) return json(value == 1);
        if (value.is_string())
            for (const auto& [word, meaning] : boolean_words)
                if (value.get<std::string>() == word) return json(meaning);
        return fail();
    }
    if (spec.kind == OptionKind::choice) {
        if (value.is_string())
            for (const std::string& c : spec.choices)
                if (value.get<std::string>() == c) return value;
        return fail();
    }
    if (spec.kind == OptionKind::count && value == "auto") return value;
    double v;
    if (value.is_number()) {
        v = value.get<double>();
    } else if (value.is_string()) {
        const std::string t = value.get<std::string>();
        char* end = nullptr;
        v = std::strtod(t.c_str(), &end);
        if (t.empty() || *end != '\0') return fail();
    } else {
        return fail();
    }
    const bool integral = spec.kind != OptionKind::number;
    if (!std::isfinite(v) || v < spec.min || v > spec.max || (integral && v != std::floor(v))) return fail();
    return integral && spec.max < 2147483648.0 ? json(static_cast<int>(v)) : json(v);
}

const OptionSpec* find(std::string_view name) {
    for (const OptionSpec& spec : option_schema())
        if (name == spec.name || name == camel_case(spec.name)) return &spec;
    return nullptr;
}

const char* kind_name(OptionKind kind) {
    switch (kind) {
        case OptionKind::count: return "count";
        case OptionKind::integer: return "integer";
        case OptionKind::number: return "number";
        case OptionKind::boolean: return "boolean";
        case OptionKind::choice: return "choice";
    }
    return "";
}

}  // namespace

const std::vector<OptionSpec>& option_schema() {
    static const std::vector<OptionSpec> schema = make_schema();
    return schema;
}

std::string camel_case(std::string_view name) {
    std::string out;
    bool upper = false;
    for (char c : name) {
        if (c == '-') {
            upper = true;
            continue;
        }
        out += upper ? static_cast<char>(std::toupper(static_cast<unsigned char>(c))) : c;
        upper = false;
    }
    return out;
}

void set_option(Options& options, std::string_view name, const json& value) {
    const OptionSpec* spec = find(name);
    if (!spec) throw std::invalid_argument("unknown option '" + std::string(name) + "'");
    spec->set(options, normalised(*spec, value));
}

Options options_from_json(const json& object, Options options) {
    if (!object.is_object()) throw std::invalid_argument("options must be an object");
    for (auto it = object.begin(); it != object.end(); ++it)
        if (!it.value().is_null()) set_option(options, it.key(), it.value());
    return options;
}

json options_to_json(const Options& options) {
    json out = json::object();
    for (const OptionSpec& spec : option_schema()) out[spec.name] = spec.get(options);
    return out;
}

json schema_to_json() {
    const Options defaults;
    json out = json::array();
    for (const OptionSpec& spec : option_schema()) {
        json entry = {{"name", spec.name},
                      {"js", camel_case(spec.name)},
                      {"kind", kind_name(spec.kind)},
                      {"default", spec.get(defaults)},
                      {"help", spec.help}};
        if (spec.kind == OptionKind::count || spec.kind == OptionKind::integer || spec.kind == OptionKind::number) {
            entry["min"] = spec.min;
            entry["max"] = spec.max;
        }
        if (spec.kind == OptionKind::choice) entry["choices"] = spec.choices;
        if (spec.kind == OptionKind::boolean)
            for (const auto& [word, meaning] : boolean_words) entry["words"][word] = meaning;
        if (spec.typical_when_on != 0) entry["typicalWhenOn"] = spec.typical_when_on;
        out.push_back(entry);
    }
    return out;
}

void validate(const Options& options) {
    // Values set on the struct directly pass the same checks as those set by name.
    for (const OptionSpec& spec : option_schema()) normalised(spec, spec.get(options));
    validate(options.lloyd);
    if (!(options.max_projection_distance > 0)) throw std::invalid_argument("the projection distance guard must be positive");
}

}  // namespace vqsa
