// What an edit does to a finished run's state before Lloyd re-runs on the regions it touched.
#pragma once

#include "edit/edit.h"
#include "geometry/model.h"
#include "pipeline/pipeline.h"

#include <vector>

namespace vqsa {

// Applies `edit` (its face in the model's order) to `state`: relabels, adds or removes the
// region, records the lock or the imposed type. Returns, per region of the new state, the
// regions Lloyd re-runs on: the merged region; the split one and the new one (split,
// add_seed); the retyped one and its unlocked neighbours (set_type); none for lock and
// unlock. Throws std::invalid_argument when the edit does not apply (no such region, a
// locked one, regions not adjacent, a type that does not fit), before changing anything
// but the length of the per-region flags (`locked`, `imposed`: sized to the regions).
std::vector<char> apply_edit(const Model& model, const LloydOptions& options, const Edit& edit, Pipeline::State& state);

}  // namespace vqsa
