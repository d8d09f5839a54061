// Hair-type presets for the curl op (talk, Sec. 3.1: "We first define the hair type, which determines
// the average frequency : amplitude ratio of the curls" and the secondary tier of shapes). Types are
// those of Andre Walker's typing system, 2a..4c. Where each number comes from is documented in the
// README ("Curls: groom curl", "Where the hair-type numbers come from") and beside the table in
// hair_types.cpp; numbers that are our own choice are marked so there.
#pragma once

#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace groom {

struct HairTypePreset {
    const char* name;             ///< "2a" .. "4c"
    float shrinkage;              ///< 1 - (curled extent / straight length) the type is modelled on; [0, 1)
    float ratio;                  ///< frequency x amplitude (dimensionless: curl radius / curl pitch)
                                  ///< of a circular helix with that shrinkage, = sqrt(i^2 - 1) / (2 pi),
                                  ///< i = 1 / (1 - shrinkage) the curl index
    float radius_cm;              ///< default curl radius (amplitude), centimetres
    int dominant;                 ///< default dominant shape (tier A), a curl_shapes.h index
    std::vector<int> secondary;   ///< tier B shapes (curl_shapes.h indices)
};

/// The preset table, 2a..4c in order of rising curliness (and rising ratio).
std::span<const HairTypePreset> hair_type_presets();

/// The preset named `name` ("2a".."4c", case-insensitive), or nullptr.
const HairTypePreset* find_hair_type(std::string_view name);

/// "2a|2b|...|4c" for messages.
std::string hair_type_list();

}  // namespace groom
