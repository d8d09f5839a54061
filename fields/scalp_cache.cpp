#include "fields/scalp_cache.h"

#include "kernel/io/io_util.h"

#include <fstream>
#include <iterator>
#include <mutex>

namespace groom {

namespace {

struct Cache {
    std::mutex mutex;
    int scopes = 0;
    long builds = 0;
    std::string bytes;  // the whole file: compared, not hashed, so a reuse is never a collision
    ScalpBuildParams params;
    std::shared_ptr<const ScalpField> field;
};

Cache& cache()
{
    static Cache c;
    return c;
}

bool same(const ScalpBuildParams& a, const ScalpBuildParams& b)
{
    return a.voxel_size == b.voxel_size && a.band_voxels == b.band_voxels && a.flip == b.flip && a.memory_budget == b.memory_budget &&
           a.remove_enclosed_shells == b.remove_enclosed_shells && a.fill_holes == b.fill_holes && a.group == b.group && a.grid == b.grid;
}

}  // namespace

ScalpCacheScope::ScalpCacheScope()
{
    const std::lock_guard lock(cache().mutex);
    if (cache().scopes++ == 0) cache().builds = 0;
}

ScalpCacheScope::~ScalpCacheScope()
{
    Cache& c = cache();
    const std::lock_guard lock(c.mutex);
    if (--c.scopes == 0) {
        c.field.reset();
        c.bytes.clear();
        c.bytes.shrink_to_fit();
    }
}

long ScalpCacheScope::builds()
{
    const std::lock_guard lock(cache().mutex);
    return cache().builds;
}

std::shared_ptr<const ScalpField> cached_scalp(const std::string& path, const ScalpBuildParams& params,
                                               const std::function<std::shared_ptr<const ScalpField>()>& load)
{
    Cache& c = cache();
    {
        const std::lock_guard lock(c.mutex);
        if (c.scopes == 0) return load();
    }
    std::ifstream in(path, std::ios::binary);
    if (!in) return load();  // load() names the file and the reason
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    {
        const std::lock_guard lock(c.mutex);
        if (c.field && same(c.params, params) && c.bytes == bytes) return c.field;
    }
    std::shared_ptr<const ScalpField> field = load();
    const std::lock_guard lock(c.mutex);
    c.bytes = std::move(bytes);
    c.params = params;
    c.field = field;
    ++c.builds;
    return field;
}

}  // namespace groom
