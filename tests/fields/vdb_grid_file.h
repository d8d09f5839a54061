// Test helper: a .vdb's "scalp" grid read and written with OpenVDB directly, for tests that change
// groom's grid metadata (take it away, damage it) and read the file back through groom.
#pragma once

#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>

#include <string>

namespace groom::test {

inline openvdb::FloatGrid::Ptr read_scalp_grid(const std::string& path)
{
    openvdb::initialize();
    openvdb::io::File in(path);
    in.open();
    openvdb::FloatGrid::Ptr g = openvdb::gridPtrCast<openvdb::FloatGrid>(in.readGrid("scalp"));
    in.close();
    return g;
}

inline void write_grid(const openvdb::FloatGrid::Ptr& g, const std::string& path)
{
    openvdb::io::File out(path);
    out.write(openvdb::GridCPtrVec{g});
    out.close();
}

/// `g` with its metadata `name` replaced by `meta`, written to `path`; returns path.
inline std::string write_grid_with(const openvdb::FloatGrid::Ptr& g, const std::string& name, const openvdb::Metadata& meta,
                                   const std::string& path)
{
    g->removeMeta(name);
    g->insertMeta(name, meta);
    write_grid(g, path);
    return path;
}

}  // namespace groom::test
