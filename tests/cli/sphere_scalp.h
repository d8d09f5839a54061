// Test helper for the CLI suites: the sphere scalp their closed forms are about, as a mesh file.
#pragma once

#include "kernel/io/mesh_io.h"
#include "support/sphere_mesh.h"
#include "test_support.h"

#include <string>

namespace groom::test {

constexpr float kSphereScalpRadius = 10.0f;

/// An icosphere of radius 10 at the origin (5120 triangles: chordal error about 0.024), written to
/// `dir`/head.obj; returns that path.
inline std::string sphere_scalp(const TempDir& dir)
{
    const std::string path = dir.file("head.obj");
    write_mesh(icosphere(float3(0, 0, 0), kSphereScalpRadius, 4), path);
    return path;
}

}  // namespace groom::test
