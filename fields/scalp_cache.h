// A scalp loaded once for many frames. While a ScalpCacheScope lives (the frame loop of
// cli/frame_options.h), load_scalp keeps the last field it built from a file, keyed by the file's
// bytes and the build parameters: a rigidly moving head (one file for every frame) is converted
// once, and a frame pattern of meshes (head.####.obj) is rebuilt only on the frames whose mesh
// differs from the one before, so a head that holds still between deformations costs nothing.
#pragma once

#include "fields/scalp_field.h"

#include <functional>
#include <memory>
#include <string>

namespace groom {

class ScalpCacheScope {
public:
    ScalpCacheScope();
    ~ScalpCacheScope();
    ScalpCacheScope(const ScalpCacheScope&) = delete;
    ScalpCacheScope& operator=(const ScalpCacheScope&) = delete;

    /// Fields built (or read) from files since this scope began: the frames that were not reused.
    static long builds();
};

/// With a ScalpCacheScope alive: the cached field when `path` holds the same bytes and `params`
/// equal those of the last load, else `load()`'s result, kept. Without one: `load()`.
std::shared_ptr<const ScalpField> cached_scalp(const std::string& path, const ScalpBuildParams& params,
                                               const std::function<std::shared_ptr<const ScalpField>()>& load);

}  // namespace groom
