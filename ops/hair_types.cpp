#include "ops/hair_types.h"

#include "ops/curl_shapes.h"

#include <cctype>
#include <cmath>
#include <numbers>

namespace groom {

namespace {

/// Frequency x amplitude of a circular helix whose hair shrinks by `shrinkage` when it curls:
/// per cycle the hair runs sqrt((2 pi r)^2 + p^2) along an axis advance p, so the curl index
/// i = 1 / (1 - shrinkage) = sqrt(1 + (2 pi r / p)^2) and r / p = sqrt(i^2 - 1) / (2 pi).
float helix_ratio(float shrinkage)
{
    const double i = 1.0 / (1.0 - double(shrinkage));
    return float(std::sqrt(i * i - 1.0) / (2.0 * std::numbers::pi));
}

std::vector<HairTypePreset> build_table()
{
    // Shrinkage: a web summary of natural-hair shrinkage (askvity.info, "how many people in the world
    // have naturally curly hair") gives wavy hair "up to 5%", curly "up to 30%", coily "up to 75%";
    // we take those bounds for 2c, 3c and 4c and space a and b evenly below them (our choice).
    // radius_cm: our choice (no measurement we could read gives one per Walker subtype), except 4c,
    // whose 1.5 mm radius matches the 2-4 mm coil diameters measured on shed type-4 hair in the
    // pureestrogen.com article on natural curl diameters. Shapes: our reading of Walker's
    // descriptions (type 2 flattened S-waves; 3 round spirals and ringlets; 4b Z-pattern with sharp
    // angles; 4c tightest, zig-zag, pattern hard to see).
    struct Row {
        const char* name;
        float shrinkage, radius_cm;
        int dominant;
        std::vector<int> secondary;
    };
    const Row rows[] = {
        {"2a", 0.05f / 3.0f, 0.25f, kEllipse, {kLame}},
        {"2b", 0.10f / 3.0f, 0.35f, kEllipse, {kLame}},
        {"2c", 0.05f, 0.45f, kEllipse, {kCircle, kLame}},
        {"3a", 0.05f + 0.25f / 3.0f, 1.00f, kCircle, {kEllipse}},
        {"3b", 0.05f + 0.50f / 3.0f, 0.70f, kCircle, {kEllipse, kLame}},
        {"3c", 0.30f, 0.40f, kCircle, {kLame, kEllipse}},
        {"4a", 0.30f + 0.45f / 3.0f, 0.25f, kCircle, {kEllipse, kLame}},
        {"4b", 0.30f + 0.90f / 3.0f, 0.20f, kLame, {kPolygon, kEllipse}},
        {"4c", 0.75f, 0.15f, kPolygon, {kRose, kLame}},
    };
    std::vector<HairTypePreset> table;
    for (const Row& r : rows) table.push_back({r.name, r.shrinkage, helix_ratio(r.shrinkage), r.radius_cm, r.dominant, r.secondary});
    return table;
}

}  // namespace

std::span<const HairTypePreset> hair_type_presets()
{
    static const std::vector<HairTypePreset> table = build_table();
    return table;
}

const HairTypePreset* find_hair_type(std::string_view name)
{
    for (const HairTypePreset& p : hair_type_presets()) {
        if (name.size() == 2 && name[0] == p.name[0] && std::tolower(static_cast<unsigned char>(name[1])) == p.name[1]) return &p;
    }
    return nullptr;
}

std::string hair_type_list()
{
    std::string out;
    for (const HairTypePreset& p : hair_type_presets()) {
        if (!out.empty()) out += "|";
        out += p.name;
    }
    return out;
}

}  // namespace groom
