// Named, typed attribute columns on the three domains of a CurveSet (point, curve, detail),
// stored as structure of arrays. Mirrors Houdini's attribute owners and Blender's
// CurvesGeometry attribute storage.
#pragma once

#include "kernel/error.h"
#include "kernel/math/vec.h"

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace groom {

/// Where an attribute lives: one value per point, per curve, or one for the whole set.
enum class Domain { Point, Curve, Detail };

/// The value types a column may hold. String is allowed on the detail domain only: per-element
/// strings have no faithful home in the curve formats we write.
enum class AttrType { Float, Int32, Int64, Float3, String };

const char* domain_name(Domain d);   ///< "point", "curve", "detail"
const char* type_name(AttrType t);   ///< "float", "int", "int64", "float3", "string"

using AttributeData = std::variant<std::vector<float>, std::vector<int32_t>, std::vector<int64_t>,
                                   std::vector<float3>, std::vector<std::string>>;

template <class T> constexpr AttrType attr_type_of();
template <> constexpr AttrType attr_type_of<float>() { return AttrType::Float; }
template <> constexpr AttrType attr_type_of<int32_t>() { return AttrType::Int32; }
template <> constexpr AttrType attr_type_of<int64_t>() { return AttrType::Int64; }
template <> constexpr AttrType attr_type_of<float3>() { return AttrType::Float3; }
template <> constexpr AttrType attr_type_of<std::string>() { return AttrType::String; }

/// One named column.
struct Attribute {
    std::string name;
    Domain domain = Domain::Point;
    AttributeData data;

    AttrType type() const { return static_cast<AttrType>(data.index()); }
    size_t size() const;
    void resize(size_t n);

    template <class T> std::span<T> values() { return std::get<std::vector<T>>(data); }
    template <class T> std::span<const T> values() const { return std::get<std::vector<T>>(data); }
};

/// Makes an empty column of the given type.
AttributeData make_attribute_data(AttrType type, size_t size);

/// The columns of one domain, in insertion order (so files are written in a stable order).
class AttributeSet {
public:
    const Attribute* find(std::string_view name) const;
    Attribute* find(std::string_view name);

    /// Adds a column of `size` default values, or returns the existing one if it has the same type.
    /// Throws InvalidGeometry if a column with this name exists with a different type.
    Attribute& add(std::string_view name, Domain domain, AttrType type, size_t size);
    bool remove(std::string_view name);
    void resize(size_t n);

    std::vector<Attribute>& all() { return attrs_; }
    const std::vector<Attribute>& all() const { return attrs_; }
    size_t count() const { return attrs_.size(); }

private:
    std::vector<Attribute> attrs_;
};

}  // namespace groom
