// Length units by name, as curves carry them (detail string `units`) and USD gives them
// (`metersPerUnit`): `groom transform` converts between them, the .usda reader and writer map them.
#pragma once

#include <string_view>

namespace groom {

/// Metres per unit for "mm" "cm" "m" "in"; 0 for anything else.
inline double meters_per_unit(std::string_view unit)
{
    if (unit == "mm") return 0.001;
    if (unit == "cm") return 0.01;
    if (unit == "m") return 1.0;
    if (unit == "in") return 0.0254;
    return 0.0;
}

/// The unit's name for `meters` per unit (within 1e-6 of it, relative), or "" for none of them.
inline std::string_view unit_named(double meters)
{
    for (const std::string_view name : {"mm", "cm", "m", "in"}) {
        const double m = meters_per_unit(name);
        if (meters / m - 1.0 < 1e-6 && meters / m - 1.0 > -1e-6) return name;
    }
    return {};
}

}  // namespace groom
