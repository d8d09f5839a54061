// CurveSet: the one geometry container of groom. Curves are an offsets array (curve c owns points
// [offsets[c], offsets[c+1])) plus named attribute columns on the point, curve and detail domains.
// Point attribute "P" holds positions; curves run root to tip; curve attribute "id" is the stable
// identity that seeds randomness (see kernel/rng.h).
#pragma once

#include "kernel/attribute.h"

#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

namespace groom {

/// Half-open range of point indices [begin, end).
struct IndexRange {
    int64_t begin = 0, end = 0;
    int64_t size() const { return end - begin; }
    bool empty() const { return end <= begin; }
};

/// Well-known attribute names (Houdini's where one exists).
namespace attr {
inline constexpr std::string_view P = "P";          ///< point float3, position
inline constexpr std::string_view width = "width";  ///< point float, fibre diameter in scene units
inline constexpr std::string_view id = "id";        ///< curve int64, stable identity
/// detail int32, 1: every curve is a closed loop, its first point repeated at its end (as readers
/// give a USD `wrap = "periodic"` curve, an OBJ record back to its first vertex, a loop of edges);
/// writers that can say so write the loop closed again (.usda periodic, .obj back to its first vertex)
inline constexpr std::string_view closed = "closed";
}  // namespace attr

class CurveSet {
public:
    CurveSet();

    /// A set with `counts.size()` curves, curve c having counts[c] points; every existing point
    /// and curve attribute is resized, P is zero. Throws InvalidGeometry for a negative count.
    static CurveSet from_counts(std::span<const int64_t> counts);
    static CurveSet from_counts(std::span<const int32_t> counts);

    size_t num_curves() const { return offsets_.size() - 1; }
    size_t num_points() const { return static_cast<size_t>(offsets_.back()); }
    std::span<const int64_t> offsets() const { return offsets_; }
    IndexRange points_of(size_t curve) const { return {offsets_[curve], offsets_[curve + 1]}; }
    int64_t points_in(size_t curve) const { return offsets_[curve + 1] - offsets_[curve]; }

    /// Replaces the topology; point and curve columns are resized (values kept up to the new size).
    void set_counts(std::span<const int64_t> counts);
    /// Replaces the offsets array directly (validated: starts at 0, non-decreasing).
    void set_offsets(std::vector<int64_t> offsets);

    AttributeSet& attributes(Domain d) { return domains_[static_cast<int>(d)]; }
    const AttributeSet& attributes(Domain d) const { return domains_[static_cast<int>(d)]; }

    /// Size a column on this domain must have.
    size_t domain_size(Domain d) const;

    /// Adds (or returns) a column sized for its domain and returns its values.
    template <class T> std::span<T> add(Domain d, std::string_view name)
    {
        return attributes(d).add(name, d, attr_type_of<T>(), domain_size(d)).template values<T>();
    }
    /// Returns the values of a column of type T, or an empty span when absent or of another type.
    template <class T> std::span<const T> find(Domain d, std::string_view name) const
    {
        const Attribute* a = attributes(d).find(name);
        if (!a || a->type() != attr_type_of<T>()) return {};
        return a->values<T>();
    }
    /// The same column for writing; named apart so that a reader cannot write by accident.
    template <class T> std::span<T> find_for_write(Domain d, std::string_view name)
    {
        Attribute* a = attributes(d).find(name);
        if (!a || a->type() != attr_type_of<T>()) return {};
        return a->values<T>();
    }

    /// Point positions ("P"), read only; positions_for_write() for the writable view (Blender's
    /// naming: a call that can change the geometry says so).
    std::span<const float3> positions() const { return attributes(Domain::Point).find(attr::P)->values<float3>(); }
    std::span<float3> positions_for_write() { return attributes(Domain::Point).find(attr::P)->values<float3>(); }

    /// Curve ids: the "id" curve attribute when present (int64 or int32), else the curve index.
    std::vector<int64_t> curve_ids() const;
    /// The same for curves [begin, end) only (an op working a block of curves at a time).
    std::vector<int64_t> curve_ids(size_t begin, size_t end) const;

    /// Detail string attribute, or `fallback` when absent.
    std::string detail_string(std::string_view name, std::string_view fallback = {}) const;
    void set_detail_string(std::string_view name, std::string_view value);

    /// Checks every invariant: offsets start at 0 and never decrease, every column has its domain's
    /// size, P exists as float3 and is finite, a float `width` (point or curve) is finite and >= 0,
    /// detail columns have one value. Throws InvalidGeometry naming the curve/point and what was
    /// found. `what` prefixes messages (e.g. the file name).
    void validate(std::string_view what = {}) const;

    Bounds3 bounds() const;

private:
    std::vector<int64_t> offsets_;
    AttributeSet domains_[3];
};

/// Whether `curves` are closed loops: the detail int `closed` (attr::closed) is 1.
bool is_closed(const CurveSet& curves);
/// Sets (1) or removes the detail int `closed`.
void set_closed(CurveSet& curves, bool closed);

/// Copies every curve and detail attribute of `src` onto `dst`, where dst curve c comes from src curve
/// src_curve[c]. Columns dst already has are left alone, and so is the detail `closed` (curves made
/// from loops are not loops; an op that keeps every curve's ends sets it again). Point attributes are not touched: ops that
/// rebuild points decide how those carry.
void carry_curve_attributes(const CurveSet& src, CurveSet& dst, std::span<const int64_t> src_curve);

/// Copies every point attribute of `src` except those named in `skip`, where dst point p takes the
/// value of src point src_point[p] (a gather). Columns dst already has are left alone.
void carry_point_attributes(const CurveSet& src, CurveSet& dst, std::span<const int64_t> src_point,
                            std::initializer_list<std::string_view> skip = {});

}  // namespace groom
