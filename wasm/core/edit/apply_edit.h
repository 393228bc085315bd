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

// For a split or a seed whose new region `added` (still its seed face alone) came out of
// Lloyd a strip (its old region's fit won the race everywhere: the region lies on one
// surface): gives it the faces of its old region nearer its seed than the old region's
// face farthest from it, in steps across edges (ties stay), so that both start from a fit
// to a real part of the region.
void halve_for_new_region(const Model& model, std::vector<int>& labels, int added);

}  // namespace vqsa
