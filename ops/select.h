// select: keep the curves that match (or, inverted, those that do not) by id range, guide, attribute
// comparison or USD prim path, so a TD can cut a groom apart without another tool.
#pragma once

#include "kernel/curve_set.h"

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace groom {

/// Inclusive range of curve ids [lo, hi].
struct IdRange {
    int64_t lo = 0, hi = 0;
};

enum class CompareOp { Less, LessEqual, Greater, GreaterEqual, Equal, NotEqual };

/// `NAME OP NUMBER`, e.g. `width>0.01`, `kind==2`, `Cd.x<=0.5`: a curve attribute is compared per
/// curve, a point attribute at the curve's root point, a detail attribute once for every curve.
/// A float3 attribute needs a component (`.x`, `.y`, `.z`). `id` on curves without an id column is
/// the curve index, as everywhere else.
struct AttributeTest {
    std::string name;       ///< attribute name, without the component suffix
    int component = -1;     ///< 0..2 for float3 attributes, else -1
    CompareOp op = CompareOp::Equal;
    double value = 0.0;
};

/// Parses `NAME OP NUMBER` (OP one of < <= > >= == !=; `=` is taken as ==). Throws InvalidParam
/// naming `option` and what was expected when the text is not of that form.
AttributeTest parse_attribute_test(std::string_view text, std::string_view option = "where");

/// Parses `A-B,C,D-E` (inclusive ranges of integer ids, a single id is a range of one; negative ids
/// written as `-5` or `-9--5`). Throws InvalidParam naming `option`.
std::vector<IdRange> parse_id_ranges(std::string_view text, std::string_view option = "ids");

struct SelectParams {
    std::vector<IdRange> ids;           ///< curve id (attribute `id`, else the index) in any range; empty = no test
    std::vector<int64_t> guides;        ///< curve attribute `guide` equal to one of these; empty = no test
    std::vector<AttributeTest> where;   ///< every comparison must hold; empty = no test
    /// USD prim paths: the curve's prim (curve int attribute `prim`, an index into the detail
    /// string `prim_paths`, one path a line) is one of these or lies under one; empty = no test.
    std::vector<std::string> prims;
    bool invert = false;                ///< keep the curves that do NOT match instead
    void validate() const;              ///< throws InvalidParam: no criterion, a range with lo > hi
};

struct SelectStats {
    int64_t matched = 0;  ///< curves matching every criterion (before invert)
    int64_t kept = 0;     ///< curves in the output
};

/// @brief The curves matching every given criterion (each list matches when any entry does), or with
/// `invert` the others. Reads curve id, guide, prim and whatever `where` names. Every attribute is
/// carried, curve order kept. Throws InvalidParam naming the option when a named attribute is absent
/// (listing the ones there are), has strings, or needs a component it lacks; and when --guide or
/// --prim is given for curves without `guide` or prim paths.
CurveSet select(const CurveSet& src, const SelectParams& params, SelectStats* stats = nullptr);

}  // namespace groom
