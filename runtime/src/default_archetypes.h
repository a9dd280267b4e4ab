#pragma once
// A small built-in set of blade archetypes for scenes that name no archetype library.
#include <vector>

#include "meadow/modeling/archetype.h"

namespace meadow::runtime {

std::vector<modeling::Archetype> defaultArchetypes();

}  // namespace meadow::runtime
