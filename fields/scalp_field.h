// ScalpField: the scalp as an OpenVDB signed-distance level set plus the repaired mesh it came from.
// Built from any mesh a user has (see fields/mesh_repair.h), or loaded from a .vdb written by
// `groom scalp`. OpenVDB stays behind a pimpl so ops/ and cli/ compile without its headers.
#pragma once

#include "fields/surface.h"
#include "kernel/io/mesh_io.h"
#include "kernel/progress.h"

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace groom {

struct ScalpBuildParams {
    float voxel_size = 0.0f;      ///< scene units; 0 = automatic from the mesh size
    float band_voxels = 3.0f;     ///< narrow-band half width in voxels; >= 1
    bool flip = false;            ///< treat the mesh as inside out
    uint64_t memory_budget = 4ull << 30;  ///< bytes; larger grids are refused with a suggested voxel size
    void validate() const;        ///< throws InvalidParam
};

/// One sampled root on the scalp.
struct SurfaceSample {
    float3 position;
    float3 normal;
    int32_t face = -1;
};

class ScalpField final : public Surface {
public:
    ScalpField();
    ~ScalpField() override;
    ScalpField(ScalpField&&) noexcept;
    ScalpField& operator=(ScalpField&&) noexcept;

    float distance(const float3& p) const override;
    float3 normal(const float3& p) const override;
    float3 closest_point(const float3& p) const override;
    bool first_intersection(const float3& a, const float3& b, float3& hit, float tolerance = 0.0f) const override;

    float voxel_size() const;

    /// `count` points area-uniformly distributed over the scalp faces whose points lie within
    /// `radius` of `center` (radius <= 0: the whole surface), deterministic for a given seed.
    std::vector<SurfaceSample> sample_ball(const float3& center, float radius, int64_t count, uint64_t seed) const;

    struct Impl;
    Impl& impl() { return *impl_; }
    const Impl& impl() const { return *impl_; }

private:
    std::unique_ptr<Impl> impl_;
    friend ScalpField build_scalp(const PolygonSoup&, const ScalpBuildParams&, struct RepairReport*, Progress*);
    friend ScalpField read_scalp_vdb(const std::string&);
};

}  // namespace groom

namespace groom {

/// Loads the scalp for any command's --scalp: a .vdb written by `groom scalp` (grid "scalp"), or a
/// mesh converted on the fly with `params`. Throws ParseError/IoError/InvalidParam.
std::unique_ptr<ScalpField> load_scalp(const std::string& path, const ScalpBuildParams& params = {}, Progress* progress = nullptr);

}  // namespace groom
