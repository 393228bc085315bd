#include "edit/edit.h"

#include <algorithm>
#include <iterator>
#include <limits>
#include <stdexcept>
#include <string>

namespace vqsa {

namespace {

constexpr EditKind kKinds[] = {EditKind::split,  EditKind::merge,  EditKind::set_type,
                               EditKind::lock,   EditKind::unlock, EditKind::add_seed};

int index_field(const nlohmann::json& object, const char* key, const std::string& op) {
    if (!object.contains(key)) throw std::invalid_argument(op + " needs \"" + key + "\"");
    const nlohmann::json& v = object.at(key);
    if (!v.is_number_integer() || v.get<long long>() < 0 || v.get<long long>() > std::numeric_limits<int>::max())
        throw std::invalid_argument(op + ": \"" + key + "\" must be a non-negative integer");
    return v.get<int>();
}

}  // namespace

const char* edit_kind_name(EditKind kind) {
    switch (kind) {
        case EditKind::split: return "split";
        case EditKind::merge: return "merge";
        case EditKind::set_type: return "set_type";
        case EditKind::lock: return "lock";
        case EditKind::unlock: return "unlock";
        case EditKind::add_seed: return "add_seed";
    }
    return "unknown";
}

nlohmann::json edit_to_json(const Edit& e) {
    nlohmann::json j = {{"op", edit_kind_name(e.kind)}};
    switch (e.kind) {
        case EditKind::merge: j["regions"] = {e.region, e.other}; break;
        case EditKind::add_seed: j["face"] = e.face; break;
        case EditKind::split:
            j["region"] = e.region;
            if (e.face >= 0) j["face"] = e.face;
            break;
        case EditKind::set_type:
            j["region"] = e.region;
            j["type"] = imposed_type_name(e.type);
            break;
        default: j["region"] = e.region;
    }
    return j;
}

Edit edit_from_json(const nlohmann::json& o) {
    if (!o.is_object() || !o.contains("op") || !o.at("op").is_string())
        throw std::invalid_argument("an edit must be an object with an \"op\"");
    const std::string op = o.at("op").get<std::string>();
    const auto kind = std::find_if(std::begin(kKinds), std::end(kKinds), [&](EditKind k) { return op == edit_kind_name(k); });
    if (kind == std::end(kKinds)) {
        std::string names;
        for (EditKind k : kKinds) names += std::string(names.empty() ? "" : ", ") + edit_kind_name(k);
        throw std::invalid_argument("unknown edit '" + op + "' (one of " + names + ")");
    }
    Edit e;
    e.kind = *kind;
    switch (e.kind) {
        case EditKind::merge: {
            const nlohmann::json* r = o.contains("regions") ? &o.at("regions") : nullptr;
            if (!r || !r->is_array() || r->size() != 2) throw std::invalid_argument("merge needs \"regions\": [a, b]");
            const nlohmann::json pair = {{"a", (*r)[0]}, {"b", (*r)[1]}};
            e.region = index_field(pair, "a", op);
            e.other = index_field(pair, "b", op);
            break;
        }
        case EditKind::add_seed: e.face = index_field(o, "face", op); break;
        case EditKind::split:
            e.region = index_field(o, "region", op);
            if (o.contains("face")) e.face = index_field(o, "face", op);
            break;
        case EditKind::set_type:
            e.region = index_field(o, "region", op);
            if (!o.contains("type") || !o.at("type").is_string())
                throw std::invalid_argument("set_type needs \"type\" (plane, sphere, cylinder, cone, quadric or none)");
            e.type = imposed_type_from(o.at("type").get<std::string>());
            break;
        default: e.region = index_field(o, "region", op);
    }
    return e;
}

std::vector<Edit> edits_from_json(const nlohmann::json& value) {
    const nlohmann::json& list = value.is_object() && value.contains("edits") ? value.at("edits") : value;
    if (!list.is_array()) throw std::invalid_argument("edits must be an array (or an object with \"edits\")");
    std::vector<Edit> out;
    for (std::size_t i = 0; i < list.size(); ++i) {
        try {
            out.push_back(edit_from_json(list[i]));
        } catch (const std::invalid_argument& e) {
            throw std::invalid_argument("edit " + std::to_string(i) + ": " + e.what());
        }
    }
    return out;
}

}  // namespace vqsa
