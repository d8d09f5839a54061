// Length units by name, as curves carry them (detail string `units`) and USD gives them
// (`metersPerUnit`): `groom transform` converts between them, the .usda reader and writer map them.
#pragma once

#include <charconv>
#include <cmath>
#include <string>
#include <string_view>

namespace groom {

/// Metres per unit for "mm" "cm" "m" "in", or for a number, which is metres per unit itself (what a
/// USD layer's metersPerUnit that none of the names fits reads as: "0.3048", feet; it had been
/// dropped, and the file written without it read as centimetres, 30 times off: a trial); 0 for
/// anything else.
inline double meters_per_unit(std::string_view unit)
{
    if (unit == "mm") return 0.001;
    if (unit == "cm") return 0.01;
    if (unit == "m") return 1.0;
    if (unit == "in") return 0.0254;
    double v = 0.0;
    const auto [end, ec] = std::from_chars(unit.data(), unit.data() + unit.size(), v);
    return ec == std::errc() && end == unit.data() + unit.size() && v > 0.0 && std::isfinite(v) ? v : 0.0;
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

/// The `units` text for `meters` per unit: its name, else the number itself (shortest round trip).
inline std::string unit_text(double meters)
{
    if (const std::string_view name = unit_named(meters); !name.empty()) return std::string(name);
    char buf[32];
    const auto [end, ec] = std::to_chars(buf, buf + sizeof buf, meters);
    return ec == std::errc() ? std::string(buf, end) : std::string();
}

}  // namespace groom
