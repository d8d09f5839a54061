// What the .usda parser hands the rest of the reader: every prim spec of the layer as written (specifier,
// type, composition metadata, variant sets, the properties the reader uses), nothing composed or evaluated.
// Internal to kernel/io/usda_*.cpp: the interface between parsing (usda_parser.cpp), composition
// (usda_compose.cpp) and building CurveSets (usda_build.cpp).
#pragma once

#include "kernel/attribute.h"
#include "kernel/io/io_util.h"
#include "kernel/math/vec.h"

#include <array>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace groom::io::usda {

/// One authored property value the reader uses (curve attributes, primvars, xform ops, NURBS data).
struct Property {
    std::string type;                    ///< the USD value type as written: "point3f", "double3", "matrix4d"...
    std::optional<AttributeData> column; ///< the value as a column, for types a CurveSet can hold
    std::vector<double> numbers;         ///< the value's numbers flattened, for xform ops and NURBS data
    bool blocked = false;                ///< `= None`
    std::string interpolation;           ///< "" when not authored
    int element_size = 1;                ///< `elementSize` metadata
    size_t line = 0;
    int time_samples = 0;                ///< samples in `.timeSamples` (the value read is the earliest)
    double first_time = 0.0;             ///< the earliest sample's time code
};

/// An arc to another prim: `</Path>` or `@@</Path>` (in this file) or `@asset@</Path>` (another file: not read).
struct Arc {
    std::string asset;  ///< empty for an in-file arc
    std::string path;   ///< empty: the target layer's default prim
    size_t line = 0;
};

struct PrimSpec;

struct VariantSet {
    std::string name;
    std::vector<std::pair<std::string, int32_t>> variants;  ///< variant name -> its body (index into Layer::specs)
};

/// One `def` / `over` / `class` block (or one variant's body: specifier "variant").
struct PrimSpec {
    std::string name, specifier, type_name;
    size_t line = 0;
    std::optional<bool> active, instanceable;
    std::vector<Arc> references, inherits, specializes;  ///< payloads are kept with references
    std::vector<std::pair<std::string, std::string>> variant_selection;  ///< `variants = { string set = "name" }`
    std::vector<VariantSet> variant_sets;
    std::map<std::string, Property, std::less<>> props;
    std::vector<int32_t> children;  ///< indices into Layer::specs, in file order
};

struct Layer {
    std::string default_prim;
    /// Layer metadata `upAxis` ("" when not authored) and `metersPerUnit` (0 when not authored).
    std::string up_axis;
    double meters_per_unit = 0.0;
    std::vector<PrimSpec> specs;
    std::vector<int32_t> roots;  ///< the top-level prims, in file order
};

/// Where the reader's warnings go (prims skipped, arcs to other files...).
using Warn = std::function<void(const std::string&)>;

/// An affine 4x4 matrix, row-major, acting on column vectors: p' = M * (p, 1).
using Matrix4 = std::array<double, 16>;
constexpr Matrix4 kIdentity{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
Matrix4 multiply(const Matrix4& a, const Matrix4& b);

/// A prim's properties as composed: the strongest opinion of each name.
using PropertyView = std::map<std::string_view, const Property*, std::less<>>;

/// The transform of a prim's own xform ops (xformOpOrder applied in order, `!invert!` ops inverted);
/// `resets` when the order starts with `!resetXformStack!`. Throws ParseError naming the file, line and
/// op for a malformed one (unknown op, wrong number of values, an order naming an op not authored).
struct LocalXform {
    Matrix4 matrix = kIdentity;
    bool resets = false;
};
LocalXform local_xform(const PropertyView& props, const std::string& file_name, const std::string& prim_path);

/// One curves prim (BasisCurves or NurbsCurves) as composed, with the transform to world space.
struct ComposedCurves {
    std::string path, type_name;
    size_t line = 0;
    PropertyView props;
    Matrix4 world = kIdentity;
};

/// Composes the layer (in-file references, payloads, inherits, specializes, selected variants; `over`
/// and `class` prims are not geometry; inactive prims and their descendants are left out) and lists
/// every curves prim under one of `selected` (prim paths; empty = all) in traversal order. A prim
/// whose xform cannot be read is skipped with its descendants, with a warning; so are arcs to other
/// files. `skipped` gets the message of each prim skipped so. Throws InvalidParam when a selected
/// path names no prim.
std::vector<ComposedCurves> compose_curves(const Layer& layer, const std::string& file_name, const std::vector<std::string>& selected,
                                           const Warn& warn, std::vector<std::string>& skipped);

/// Parses a whole .usda (or text .usd) layer. Throws ParseError (with the line) on malformed text,
/// LimitExceeded on prims nested too deep or paths too long.
Layer parse_layer(const FileBytes& file);

}  // namespace groom::io::usda
