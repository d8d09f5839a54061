// What the .usda parser hands the curve builder: each `def BasisCurves` prim's properties as authored (USD
// schema defaults filled in, nothing evaluated). Internal to kernel/io/usda_*.cpp: the one interface between
// parsing (usda_parser.cpp) and building CurveSets (usda_build.cpp).
#pragma once

#include "kernel/attribute.h"
#include "kernel/io/io_util.h"
#include "kernel/math/vec.h"

#include <optional>
#include <string>
#include <vector>

namespace groom::io::usda {

struct Primvar {
    std::string name;             ///< without the "primvars:" prefix, or "widths"
    AttributeData data;
    std::string interpolation;    ///< "" when not authored
    size_t line = 0;
    std::vector<int32_t> indices; ///< indexed primvar (primvars:NAME:indices), empty when not indexed
};

struct CurvesPrim {
    std::string path;
    size_t line = 0;
    std::string type = "cubic", basis = "bezier", wrap = "nonperiodic";  // USD schema defaults
    std::optional<std::vector<int32_t>> counts;
    std::optional<std::vector<float3>> points;
    size_t points_line = 0, counts_line = 0;
    std::vector<Primvar> primvars;  ///< widths first when present
};

/// Every `def BasisCurves` prim of the file, in file order, with the `:indices` arrays of indexed
/// primvars attached. Other prims, metadata and properties are read and skipped. Throws ParseError
/// (with the line) on malformed text, LimitExceeded on prims nested too deep or paths too long.
std::vector<CurvesPrim> parse_curves_prims(const FileBytes& file);

}  // namespace groom::io::usda
