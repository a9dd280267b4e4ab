#pragma once
// Model no more than a scene needs: near-duplicate archetypes are merged until at most
// maxArchetypes remain (agglomerative, complete linkage on a shape distance), and each merge is
// recorded in the library so a user can see what was folded into what.
#include "meadow/modeling/archetype_library.h"

namespace meadow::modeling {

// Distance between two blade shapes (m): the mean over kShapeSamples equal arc-length fractions
// of the spine-point distance plus the width difference, both in the blade-local frame.
float shapeDistance_m(const Archetype& a, const Archetype& b);

// Merges until library.archetypes.size() <= maxArchetypes; the medoid of each group stays.
// maxArchetypes < 1 throws std::invalid_argument.
void mergeNearDuplicates(ArchetypeLibrary& library, int maxArchetypes);

}  // namespace meadow::modeling
