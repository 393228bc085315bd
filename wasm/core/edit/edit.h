// Edits a user makes to a finished result — split, merge, impose a type, lock, add a seed —
// as plain data, and their JSON form (docs/EDITS.md).
#pragma once

#include "fitting/model_selection.h"

#include <nlohmann/json.hpp>

#include <vector>

namespace vqsa {

enum class EditKind { split, merge, set_type, lock, unlock, add_seed };
const char* edit_kind_name(EditKind kind);

// Regions are numbered as in the result the edit applies to: a merge removes the second
// region (those after it move down by one), a split or a new seed appends one. Faces are
// in the input's order (the report's `labels`).
struct Edit {
    EditKind kind = EditKind::split;
    int region = -1;  // split, set_type, lock, unlock; merge: the region kept
    int other = -1;   // merge: the region merged into `region`
    // split: the face that seeds the new region (-1: the region's face farthest from its
    // surface); add_seed: the face the new region grows from.
    int face = -1;
    ImposedType type = ImposedType::none;  // set_type (none: the data choose again)

    static Edit split(int region, int face = -1) { return {EditKind::split, region, -1, face}; }
    static Edit merge(int a, int b) { return {EditKind::merge, a, b}; }
    static Edit set_type(int region, ImposedType type) { return {EditKind::set_type, region, -1, -1, type}; }
    static Edit lock(int region) { return {EditKind::lock, region}; }
    static Edit unlock(int region) { return {EditKind::unlock, region}; }
    static Edit add_seed(int face) { return {EditKind::add_seed, -1, -1, face}; }
    bool operator==(const Edit& o) const {
        return kind == o.kind && region == o.region && other == o.other && face == o.face && type == o.type;
    }
};

// {"op": "split", "region": 3, "face": 120} · {"op": "merge", "regions": [2, 5]} ·
// {"op": "set_type", "region": 1, "type": "cone"} · {"op": "lock", "region": 4} ·
// {"op": "unlock", "region": 4} · {"op": "add_seed", "face": 812}
nlohmann::json edit_to_json(const Edit& edit);
// Throws std::invalid_argument saying what is wrong with the object.
Edit edit_from_json(const nlohmann::json& object);
// A list of edits: an array of them, or an object holding one under "edits" (a report).
std::vector<Edit> edits_from_json(const nlohmann::json& value);

}  // namespace vqsa
