#include "cli/scalp_xform.h"

#include "ops/scene_length.h"

#include "kernel/error.h"

#include <cmath>
#include <fstream>
#include <sstream>
#include <vector>

namespace groom::cli {

RigidXform RigidXform::from_trs(const double t[3], const double degrees[3])
{
    const double k = M_PI / 180.0;
    const double cx = std::cos(degrees[0] * k), sx = std::sin(degrees[0] * k);
    const double cy = std::cos(degrees[1] * k), sy = std::sin(degrees[1] * k);
    const double cz = std::cos(degrees[2] * k), sz = std::sin(degrees[2] * k);
    // R = Rz * Ry * Rx: X first, as Maya's and Houdini's default rotate order xyz.
    RigidXform x;
    x.r = {{{cz * cy, cz * sy * sx - sz * cx, cz * sy * cx + sz * sx},
            {sz * cy, sz * sy * sx + cz * cx, sz * sy * cx - cz * sx},
            {-sy, cy * sx, cy * cx}}};
    x.t = {t[0], t[1], t[2]};
    return x;
}

std::map<long, RigidXform> read_scalp_xforms(const std::string& path)
{
    std::ifstream in(path);
    if (!in) throw IoError("--scalp-xform " + path + ": cannot open the file");
    std::map<long, RigidXform> out;
    std::string line;
    int line_no = 0;
    while (std::getline(in, line)) {
        ++line_no;
        if (const size_t hash = line.find('#'); hash != std::string::npos) line.erase(hash);
        for (char& c : line)
            if (c == ',') c = ' ';
        std::istringstream words(line);
        std::vector<std::string> tok;
        for (std::string w; words >> w;) tok.push_back(w);
        if (tok.empty()) continue;
        const std::string where = path + ":" + std::to_string(line_no) + ": ";
        long frame = 0;
        try {
            size_t used = 0;
            frame = std::stol(tok[0], &used);
            if (used != tok[0].size()) throw std::invalid_argument("");
        }
        catch (const std::exception&) {
            throw ParseError(where + "expected a frame number first, found '" + tok[0] + "'");
        }
        std::vector<double> v;
        for (size_t i = 1; i < tok.size(); ++i) {
            try {
                size_t used = 0;
                const double d = std::stod(tok[i], &used);
                if (used != tok[i].size() || !std::isfinite(d)) throw std::invalid_argument("");
                v.push_back(d);
            }
            catch (const std::exception&) {
                throw ParseError(where + "expected a finite number, found '" + tok[i] + "'");
            }
        }
        RigidXform x;
        if (v.size() == 6) {
            x = RigidXform::from_trs(&v[0], &v[3]);
        }
        else if (v.size() == 12 || v.size() == 16) {
            for (int i = 0; i < 3; ++i) {
                for (int j = 0; j < 3; ++j) x.r[i][j] = v[size_t(i * 4 + j)];
                x.t[i] = v[size_t(i * 4 + 3)];
            }
            if (v.size() == 16 && (v[12] != 0 || v[13] != 0 || v[14] != 0 || v[15] != 1)) {
                throw ParseError(where + "expected the last row of a 4x4 matrix to be 0 0 0 1 (a rigid transform), found " +
                                 tok[13] + " " + tok[14] + " " + tok[15] + " " + tok[16]);
            }
        }
        else {
            throw ParseError(where + "expected the frame and 6 numbers (tx ty tz rx ry rz), 12 (3x4 matrix) or 16 (4x4 matrix), found " +
                             std::to_string(v.size()) + " numbers after the frame");
        }
        double worst = 0.0;
        for (int i = 0; i < 3; ++i) {
            for (int j = 0; j < 3; ++j) {
                double dot = 0.0;
                for (int k = 0; k < 3; ++k) dot += x.r[k][i] * x.r[k][j];
                worst = std::max(worst, std::abs(dot - (i == j ? 1.0 : 0.0)));
            }
        }
        const auto& r = x.r;
        const double det = r[0][0] * (r[1][1] * r[2][2] - r[1][2] * r[2][1]) - r[0][1] * (r[1][0] * r[2][2] - r[1][2] * r[2][0]) +
                           r[0][2] * (r[1][0] * r[2][1] - r[1][1] * r[2][0]);
        if (worst > 1e-5 || det < 0.0) {
            throw ParseError(where + "expected a rigid transform (a rotation: orthonormal columns to 1e-5, determinant +1); found columns " +
                             "off by " + std::to_string(worst) + ", determinant " + std::to_string(det) +
                             " (a head that changes shape goes in as a frame pattern of meshes, --scalp head.####.obj)");
        }
        // A translation past any scene puts the curves past float's range: named here, not as a
        // non-finite point of the frame's output file (a trial).
        for (int i = 0; i < 3; ++i) {
            if (std::abs(x.t[i]) > double(kMaxSceneLength)) {
                throw ParseError(where + "expected a translation within 1e15 scene units, found " + format_number(x.t[i]));
            }
        }
        if (!out.emplace(frame, x).second) throw ParseError(where + "frame " + std::to_string(frame) + " is given twice");
    }
    if (out.empty()) throw ParseError("--scalp-xform " + path + ": expected one line per frame, found none");
    return out;
}

namespace {

float3 apply(const RigidXform& x, const float3& p, bool inverse, bool point)
{
    const double v[3] = {p.x, p.y, p.z};
    double o[3];
    if (!inverse) {
        for (int i = 0; i < 3; ++i) o[i] = x.r[i][0] * v[0] + x.r[i][1] * v[1] + x.r[i][2] * v[2] + (point ? x.t[i] : 0.0);
    }
    else {
        const double d[3] = {v[0] - (point ? x.t[0] : 0.0), v[1] - (point ? x.t[1] : 0.0), v[2] - (point ? x.t[2] : 0.0)};
        for (int i = 0; i < 3; ++i) o[i] = x.r[0][i] * d[0] + x.r[1][i] * d[1] + x.r[2][i] * d[2];
    }
    return {float(o[0]), float(o[1]), float(o[2])};
}

void move(std::span<float3> values, const RigidXform& x, bool inverse, bool point)
{
    for (float3& p : values) p = apply(x, p, inverse, point);
}

}  // namespace

void transform_curves(CurveSet& curves, const RigidXform& xform, bool inverse)
{
    move(curves.positions_for_write(), xform, inverse, true);
    for (const char* name : {"puff_base", "puff_sphere_center"}) move(curves.find_for_write<float3>(Domain::Detail, name), xform, inverse, true);
    for (Domain d : {Domain::Point, Domain::Curve, Domain::Detail}) move(curves.find_for_write<float3>(d, "N"), xform, inverse, false);
}

}  // namespace groom::cli
