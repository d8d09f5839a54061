// Test helper for the curve-format tests: a CurveSet with awkward values and an attribute of every
// type and domain, bit-exact comparisons of points and attributes, and a check for parse errors.
#pragma once

#include "kernel/curve_set.h"
#include "kernel/error.h"
#include "kernel/io/curve_io.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <type_traits>
#include <variant>
#include <vector>

namespace groom::test {

/// Awkward floats on purpose: values with no short decimal form, tiny and huge magnitudes, -0.
inline CurveSet sample_curves(bool with_attributes = true)
{
    const std::vector<int64_t> counts{3, 5, 2, 4};
    CurveSet cs = CurveSet::from_counts(counts);
    auto P = cs.positions_for_write();
    for (size_t i = 0; i < P.size(); ++i) {
        const float t = static_cast<float>(i);
        P[i] = {std::nextafter(0.1f * t, 1.0f), std::sin(t) * 1e-7f + 1.0f / 3.0f, -1234.5678f * t - 1e-30f};
    }
    P[0].z = -0.0f;
    if (!with_attributes) return cs;
    auto w = cs.add<float>(Domain::Point, attr::width);
    for (size_t i = 0; i < w.size(); ++i) w[i] = 0.01f / (1.0f + static_cast<float>(i));
    auto cd = cs.add<float3>(Domain::Point, "Cd");
    for (size_t i = 0; i < cd.size(); ++i) cd[i] = {0.1f * i, 0.7f, 1.0f / (i + 3.0f)};
    auto seg = cs.add<int32_t>(Domain::Point, "segment");
    for (size_t i = 0; i < seg.size(); ++i) seg[i] = static_cast<int32_t>(i) - 5;
    auto id = cs.add<int64_t>(Domain::Curve, attr::id);
    for (size_t c = 0; c < id.size(); ++c) id[c] = (int64_t(1) << 40) + static_cast<int64_t>(c) * 7;
    auto len = cs.add<float>(Domain::Curve, "clump");
    for (size_t c = 0; c < len.size(); ++c) len[c] = 1.0f / (c + 7.0f);
    cs.add<float3>(Domain::Curve, "root_uv")[2] = {0.25f, 0.5f, 0.0f};
    cs.set_detail_string("source", "groom test \"quoted\"\nsecond line \\ backslash");
    cs.add<float>(Domain::Detail, "scale")[0] = 0.017f;
    cs.add<int32_t>(Domain::Detail, "seed")[0] = -42;
    cs.add<float3>(Domain::Detail, "up")[0] = {0.0f, 1.0f, 0.0f};
    return cs;
}

inline bool same_bits(float a, float b) { return std::memcmp(&a, &b, sizeof a) == 0; }

inline void expect_points_bit_exact(const CurveSet& a, const CurveSet& b)
{
    ASSERT_EQ(a.num_curves(), b.num_curves());
    ASSERT_EQ(a.num_points(), b.num_points());
    for (size_t c = 0; c <= a.num_curves(); ++c) EXPECT_EQ(a.offsets()[c], b.offsets()[c]);
    auto pa = a.positions(), pb = b.positions();
    for (size_t i = 0; i < pa.size(); ++i) {
        EXPECT_TRUE(same_bits(pa[i].x, pb[i].x) && same_bits(pa[i].y, pb[i].y) && same_bits(pa[i].z, pb[i].z))
            << "point " << i << ": " << pa[i].x << "," << pa[i].y << "," << pa[i].z << " vs " << pb[i].x << "," << pb[i].y << "," << pb[i].z;
    }
}

/// Every column of `a` exists in `b` with the same domain, type and bit-identical values.
inline void expect_attributes_equal(const CurveSet& a, const CurveSet& b)
{
    for (Domain d : {Domain::Point, Domain::Curve, Domain::Detail}) {
        for (const Attribute& col : a.attributes(d).all()) {
            const Attribute* other = b.attributes(d).find(col.name);
            ASSERT_NE(other, nullptr) << domain_name(d) << " attribute " << col.name << " lost";
            ASSERT_EQ(other->type(), col.type()) << col.name;
            ASSERT_EQ(other->size(), col.size()) << col.name;
            std::visit(
                [&](const auto& va) {
                    using V = std::decay_t<decltype(va)>;
                    const V& vb = std::get<V>(other->data);
                    if constexpr (std::is_same_v<V, std::vector<std::string>>) {
                        EXPECT_EQ(va, vb) << col.name;
                    }
                    else {
                        EXPECT_EQ(std::memcmp(va.data(), vb.data(), va.size() * sizeof(va[0])), 0) << col.name;
                    }
                },
                col.data);
        }
        EXPECT_EQ(a.attributes(d).count(), b.attributes(d).count()) << "extra attributes on " << domain_name(d);
    }
}

inline void expect_parse_error(const std::string& path, const std::string& text, const std::string& needle)
{
    write_text(path, text);
    try {
        read_curves(path);
        ADD_FAILURE() << "no error reading " << path;
    }
    catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << "message: " << e.what() << "\nexpected to contain: " << needle;
        EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << "message does not name the file: " << e.what();
    }
}

}  // namespace groom::test
