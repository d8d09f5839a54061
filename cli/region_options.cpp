#include "cli/region_options.h"

#include "cli/command.h"
#include "kernel/error.h"
#include "kernel/io/curve_io.h"

#include <algorithm>
#include <cmath>

namespace groom::cli {

void add_region_options(CLI::App* app, RegionOptions& o)
{
    app->add_option("--hairline", o.hairline, "Hairline: one closed curve around the head (`groom hairline`); roots only inside it");
    app->add_option("--parting", o.parting, "Partings: curves on the scalp (`groom parting`); bare lines no hair crosses");
    app->add_option("--parting-gap", o.params.parting_gap, "Bare width along each parting, scene units, >= 0")->capture_default_str();
    app->add_option("--up", o.up, "X,Y,Z: the head's up direction (reading the hairline)")->capture_default_str();
}

CurveSet read_hairline(const std::string& path, const CommonOptions* common)
{
    CurveReadOptions ro;
    ro.closed_loops = true;
    if (common) ro.warn = [common](const std::string& w) { warn(*common, "warning: " + w); };
    CurveSet hairline = read_curves(path, ro);
    // An empty file had been taken for "no hairline", with --fit-cranium too (a hostile trial).
    if (hairline.num_curves() == 0) {
        throw InvalidGeometry(path + ": holds no curve; a hairline is one closed curve around the head (`groom hairline` writes one)");
    }
    return hairline;
}

void check_hairline_on_scalp(const std::string& file, const CurveSet& hairline, const Surface& scalp)
{
    // What is wrong with its shape first (two curves, too few points), named as every command names it.
    std::span<const float3> P;
    try {
        P = check_hairline(hairline, "hairline");
    }
    catch (const InvalidGeometry& e) {
        throw InvalidGeometry(file + ": " + e.what());
    }
    if (P.empty()) return;
    float3 mid{};
    for (const float3& p : P) mid = mid + p;
    mid = mid * (1.0f / float(P.size()));
    float reach = 0.0f;
    std::vector<float> off;
    off.reserve(P.size());
    for (const float3& p : P) {
        reach = std::max(reach, distance(p, mid));
        off.push_back(std::fabs(scalp.distance(p)));
    }
    std::nth_element(off.begin(), off.begin() + std::ptrdiff_t(off.size() / 2), off.end());
    const float median = off[off.size() / 2];
    if (median > 0.15f * reach) {
        throw InvalidGeometry(file + ": the hairline lies a median " + format_number(median) + " off the scalp, for a hairline " +
                              format_number(2.0f * reach) + " across (expected on it, within 0.15 of its half width): a hairline of another "
                              "head, or in other units? (`groom hairline --scalp` makes this head's)");
    }
}

CurveSet reported_hairline(const std::string& command, const Surface& scalp, const Bounds3& bounds, const HairlineParams& params,
                           const CommonOptions& common)
{
    HairlineReport report;
    CurveSet hairline = make_hairline(scalp, bounds, params, &report);
    for (const auto& [is_warning, m] : report.messages(command, params.forward)) is_warning ? warn(common, m) : note(common, m);
    return hairline;
}

void warn_if_hairline_faces_away(const std::string& command, const std::string& file, const CurveSet& hairline, const float3& up,
                                 const float3& forward, const CommonOptions& common)
{
    const auto P = hairline.positions();
    if (P.size() < 8) return;  // the region refuses it, naming what is wrong
    const float3 U = normalize(up);
    const float3 F = normalize(forward - U * dot(forward, U));
    if (!(length(F) > 0.0f)) return;
    float3 mid{};
    for (const float3& p : P) mid = mid + p;
    mid = mid * (1.0f / float(P.size()));
    float reach = 0.0f;
    for (const float3& p : P) reach = std::max(reach, std::fabs(dot(p - mid, F)));
    // Mean heights of the points in the front and back halves of the hairline's reach along F.
    double front = 0.0, back = 0.0;
    int nf = 0, nb = 0;
    for (const float3& p : P) {
        const float a = dot(p - mid, F);
        if (a > 0.5f * reach) front += dot(p - mid, U), ++nf;
        if (a < -0.5f * reach) back += dot(p - mid, U), ++nb;
    }
    if (nf == 0 || nb == 0) return;
    front /= nf;
    back /= nb;
    // A tenth of the reach: every head tried has its forehead well above its nape (Lee Perry-Smith's
    // hairline 2.4 higher at the front, for a reach of 1.9).
    if (back > front + 0.1 * double(reach)) {
        warn(common, command + ": warning: " + file + " lies higher behind the head than in front of it along --forward " + format_xyz(forward) +
                         " (" + format_number(float(back)) + " against " + format_number(float(front)) +
                         " above its centroid; a hairline runs higher over the forehead than at the nape), so the face may look the other way: "
                         "pass --forward " + format_xyz(float3(0.0f, 0.0f, 0.0f) - F));
    }
}

std::unique_ptr<HairRegion> make_region(const RegionOptions& o, const Surface& scalp, const CurveSet* hairline_at_hand)
{
    HairRegionParams params = o.params;
    params.up = parse_float3("--up", o.up);
    params.validate();
    if (!o.given() && !hairline_at_hand) return nullptr;
    // Readers name the file in their own errors.
    const CurveSet hairline = hairline_at_hand ? *hairline_at_hand : !o.hairline.empty() ? read_hairline(o.hairline) : CurveSet();
    const CurveSet partings = o.parting.empty() ? CurveSet() : read_curves(o.parting);
    try {
        return std::make_unique<HairRegion>(scalp, hairline, partings, params);
    }
    catch (const InvalidGeometry& e) {
        // The region names `hairline` or `parting`; the user typed a file.
        const std::string what = e.what();
        const std::string file = what.rfind("hairline", 0) == 0 ? (o.hairline.empty() ? std::string("the default hairline") : o.hairline) : o.parting;
        throw InvalidGeometry(file + ": " + what);
    }
}

}  // namespace groom::cli
