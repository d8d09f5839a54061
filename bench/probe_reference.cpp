// The reference for `groom probe` (issue 17): what a user with CGAL would write to get the same
// table. Reads an OBJ mesh with CGAL's reader (polygons fanned into triangles), builds CGAL's AABB
// tree with accelerate_distance_queries(), reads `x y z` text points with iostream, and writes
// x,y,z,distance,nx,ny,nz,cx,cy,cz with printf's %.9g, as `groom probe` does.
//
// The distance is signed by the closest triangle's face normal (negative where dot(p - c, n_face)
// < 0), the normal is (p - c) / distance (the face normal where p lies on the surface): the plain
// answer, not groom's (which signs by pseudo-normals and the winding number at open rims, and
// interpolates its level set in the narrow band). Same columns, same kind of work.
//
// Usage: probe_reference MESH.obj POINTS.txt OUT.csv [THREADS]
//   THREADS (default 1): the queries run on that many threads (TBB); reading and writing stay serial,
//   as a straightforward program's would.
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/IO/OBJ.h>
#include <CGAL/Simple_cartesian.h>

#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

using K = CGAL::Simple_cartesian<double>;
using Point = K::Point_3;
using Triangle = K::Triangle_3;
using Primitive = CGAL::AABB_triangle_primitive<K, std::vector<Triangle>::const_iterator>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<K, Primitive>>;

int main(int argc, char** argv)
{
    if (argc < 4) {
        std::fprintf(stderr, "usage: %s MESH.obj POINTS.txt OUT.csv [THREADS]\n", argv[0]);
        return 2;
    }
    const int threads = argc > 4 ? std::stoi(argv[4]) : 1;
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, std::max(threads, 1));

    std::vector<Point> vertices;
    std::vector<std::vector<std::size_t>> polygons;
    if (!CGAL::IO::read_OBJ(std::string(argv[1]), vertices, polygons)) {
        std::fprintf(stderr, "%s: cannot read the mesh\n", argv[1]);
        return 1;
    }
    std::vector<Triangle> triangles;
    for (const auto& poly : polygons)
        for (std::size_t k = 1; k + 1 < poly.size(); ++k)
            triangles.emplace_back(vertices[poly[0]], vertices[poly[k]], vertices[poly[k + 1]]);
    Tree tree(triangles.cbegin(), triangles.cend());
    tree.build();
    tree.accelerate_distance_queries();

    std::ifstream in(argv[2]);
    if (!in) {
        std::fprintf(stderr, "%s: cannot open\n", argv[2]);
        return 1;
    }
    std::vector<Point> points;
    double x, y, z;
    while (in >> x >> y >> z) points.emplace_back(x, y, z);

    const std::size_t n = points.size();
    std::vector<double> dist(n);
    std::vector<Point> closest(n);
    std::vector<K::Vector_3> normal(n);
    tbb::parallel_for(std::size_t(0), n, [&](std::size_t i) {
        const auto hit = tree.closest_point_and_primitive(points[i]);
        const Triangle& t = *hit.second;
        const K::Vector_3 face = CGAL::cross_product(t[1] - t[0], t[2] - t[0]);
        const K::Vector_3 delta = points[i] - hit.first;
        const double len = std::sqrt(delta.squared_length());
        const double sign = delta * face < 0.0 ? -1.0 : 1.0;
        closest[i] = hit.first;
        dist[i] = sign * len;
        normal[i] = len > 0.0 ? delta / dist[i] : face / std::sqrt(face.squared_length());
    });

    std::FILE* out = std::fopen(argv[3], "w");
    if (!out) {
        std::fprintf(stderr, "%s: cannot write\n", argv[3]);
        return 1;
    }
    std::fprintf(out, "x,y,z,distance,nx,ny,nz,cx,cy,cz\n");
    for (std::size_t i = 0; i < n; ++i) {
        const Point &p = points[i], &c = closest[i];
        const K::Vector_3& m = normal[i];
        std::fprintf(out, "%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g\n", p.x(), p.y(), p.z(), dist[i], m.x(), m.y(), m.z(),
                     c.x(), c.y(), c.z());
    }
    return std::fclose(out) == 0 ? 0 : 1;
}
