// USD xform ops to a matrix (usda_syntax.h local_xform): UsdGeomXformable's rules. xformOpOrder lists the
// ops outermost first, so with column vectors the local matrix is the product of the ops in that order
// (the last op touches points first); rotateXYZ turns about X first, then Y, then Z; angles are in
// degrees; `orient` is a quaternion written (real, i, j, k); `transform` is written for row vectors
// (translation in the last row), so it is transposed here.
#include "kernel/io/usda_syntax.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>

namespace groom::io::usda {

namespace {

using M4 = Eigen::Matrix4d;

Matrix4 to_array(const M4& m)
{
    Matrix4 out;
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) out[r * 4 + c] = m(r, c);
    return out;
}

M4 rotation(int axis, double degrees)
{
    const Eigen::Vector3d axes[3] = {Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY(), Eigen::Vector3d::UnitZ()};
    M4 m = M4::Identity();
    m.topLeftCorner<3, 3>() = Eigen::AngleAxisd(degrees * M_PI / 180.0, axes[axis]).toRotationMatrix();
    return m;
}

}  // namespace

Matrix4 multiply(const Matrix4& a, const Matrix4& b)
{
    Matrix4 out{};
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) {
            double s = 0;
            for (int k = 0; k < 4; ++k) s += a[r * 4 + k] * b[k * 4 + c];
            out[r * 4 + c] = s;
        }
    return out;
}

LocalXform local_xform(const PropertyView& props, const std::string& file_name, const std::string& prim_path)
{
    LocalXform out;
    const auto order_it = props.find("xformOpOrder");
    if (order_it == props.end() || order_it->second->blocked) return out;
    const Property& order = *order_it->second;
    const auto* names = order.column ? std::get_if<std::vector<std::string>>(&*order.column) : nullptr;
    if (!names) fail_at_line(file_name, order.line, "xformOpOrder of <" + prim_path + "> must be a token[] of op names, found " + order.type);
    M4 local = M4::Identity();
    for (const std::string& entry : *names) {
        if (entry == "!resetXformStack!") {
            // Only meaningful first; ops written before it would be discarded by the reset anyway.
            out.resets = true;
            local = M4::Identity();
            continue;
        }
        const bool invert = entry.rfind("!invert!", 0) == 0;
        const std::string name = invert ? entry.substr(8) : entry;
        const auto it = props.find(name);
        if (it == props.end()) {
            fail_at_line(file_name, order.line, "xformOpOrder of <" + prim_path + "> names '" + name + "', which the prim does not have");
        }
        const Property& op = *it->second;
        auto bad = [&](const std::string& why) { fail_at_line(file_name, op.line, "xform op '" + name + "' of <" + prim_path + ">: " + why); };
        if (op.blocked) bad("its value is None");
        const size_t colon = name.find(':', 8);
        const std::string kind = name.substr(8, colon == std::string::npos ? std::string::npos : colon - 8);
        const std::vector<double>& v = op.numbers;
        auto need = [&](size_t n, const char* what) {
            if (v.size() != n) bad("expected " + std::string(what) + " (" + std::to_string(n) + " numbers), found " + std::to_string(v.size()) + " numbers");
            for (double x : v)
                if (!std::isfinite(x)) bad("a value is not finite");
        };
        M4 m = M4::Identity();
        if (kind == "translate") {
            need(3, "a 3-vector");
            m.topRightCorner<3, 1>() = Eigen::Vector3d(v[0], v[1], v[2]);
        }
        else if (kind == "scale") {
            need(3, "a 3-vector");
            m.diagonal().head<3>() = Eigen::Vector3d(v[0], v[1], v[2]);
        }
        else if (kind == "rotateX" || kind == "rotateY" || kind == "rotateZ") {
            need(1, "one angle in degrees");
            m = rotation(kind[6] - 'X', v[0]);
        }
        else if (kind.size() == 9 && kind.rfind("rotate", 0) == 0) {
            // rotateXYZ ... rotateZYX: the first letter's axis turns first.
            const std::string axes = kind.substr(6);
            std::string sorted = axes;
            std::sort(sorted.begin(), sorted.end());
            if (sorted != "XYZ") bad("unknown rotation order '" + kind + "' (expected rotateXYZ, rotateXZY, rotateYXZ, rotateYZX, rotateZXY or rotateZYX)");
            need(3, "three angles in degrees");
            for (int i = 0; i < 3; ++i) {
                const int axis = axes[i] - 'X';
                m = rotation(axis, v[axis]) * m;
            }
        }
        else if (kind == "orient") {
            need(4, "a quaternion (real, i, j, k)");
            Eigen::Quaterniond q(v[0], v[1], v[2], v[3]);
            if (q.norm() == 0) bad("the quaternion is zero");
            m.topLeftCorner<3, 3>() = q.normalized().toRotationMatrix();
        }
        else if (kind == "transform") {
            need(16, "a matrix4d");
            for (int r = 0; r < 4; ++r)
                for (int c = 0; c < 4; ++c) m(c, r) = v[r * 4 + c];
        }
        else {
            bad("unknown op type '" + kind + "' (expected translate, scale, rotateX/Y/Z, rotateXYZ and the other orders, orient or transform)");
        }
        if (invert) {
            const double det = m.determinant();
            if (!(std::abs(det) > 1e-300)) bad("'!invert!' of a singular op");
            m = m.inverse().eval();
        }
        local = local * m;
    }
    out.matrix = to_array(local);
    return out;
}

}  // namespace groom::io::usda
