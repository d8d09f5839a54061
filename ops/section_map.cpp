#include "ops/section_map.h"

#include "kernel/error.h"
#include "kernel/math/polyline.h"
#include "kernel/parallel.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <string>

namespace groom {

namespace {

constexpr double kPi = 3.14159265358979323846;
/// Finest angle between image samples, radians: a section a few degrees wide gets dozens of samples.
constexpr double kImageStep = 0.5 * kPi / 180.0;
/// Rays hitting the scalp this obliquely or worse count as this oblique (a fold's area is bounded).
constexpr double kMinCos = 0.2;

int round_count(double x) { return int(std::lround(std::max(1.0, x))); }

/// The bands `size` makes across `across` (rounded to an odd count for rows), refused past the most
/// the count options allow: `--size 1e-20` had overflowed the count (a crash), and 1e-3 asked for
/// 23 GB before anything said no (a trial).
int bands_from_size(double across, float size, int most, bool odd, const char* what)
{
    const double n = across / double(size);
    // The count as it is rounded (odd for rows: 256 rounds up to 257), checked after rounding; the
    // least size named gives at most `most` (most - 1 when odd).
    const double fits = odd ? double(most - 1) : double(most);
    if (!(n <= fits + 0.49)) {
        throw InvalidParam("sections: `size` " + format_number(size) + " makes " + format_number(float(n)) + " " + what + " across this scalp (" +
                           format_number(float(across)) + " scene units; at most " + std::to_string(most) + "): give a size of at least " +
                           format_number(float(across / fits)) + ", or the count itself");
    }
    return odd ? 2 * int(std::lround(std::max(0.0, (n - 1.0) / 2.0))) + 1 : round_count(n);
}

}  // namespace

SectionMap::SectionMap(const Surface& scalp, const CurveSet& hairline, const HairRegion& region, const SectionsParams& params,
                       Progress* progress)
    : scalp_(scalp), region_(region), layout_(params.layout)
{
    if (!region.has_hairline() || hairline.num_curves() != 1) throw InvalidGeometry("sections: a hairline (one closed curve) is needed");
    c_ = region.centroid();
    up_ = normalize(params.up);
    fwd_ = normalize(params.forward - up_ * dot(params.forward, up_));
    side_ = cross(up_, fwd_);
    back_ = -fwd_;
    const auto hl = check_hairline(hairline, "sections: the hairline");  // without a closing repeat of the first point
    hairline_.assign(hl.begin(), hl.end());
    hairline_index_ = std::make_shared<PointIndex>(hairline_);
    float far = 0.0f;
    for (const float3& p : hl) far = std::max(far, distance(p, c_));
    reach_ = 3.0f * far + 1e-3f;

    // --- The chart's extent.
    if (layout_ == SectionLayout::Radial) {
        pole_ = params.has_crown ? normalize(params.crown - c_, up_) : up_;
        e1_ = normalize(fwd_ - pole_ * dot(fwd_, pole_), any_perpendicular(pole_));
        e2_ = cross(pole_, e1_);
        if (!region.inside_hairline(c_ + pole_)) {
            throw InvalidGeometry("sections: the crown is outside the hairline (give --crown inside it)");
        }
        // The hairline as a polar angle per azimuth around the crown: it must go once around.
        const size_t n = hl.size();
        std::vector<double> phi(n), theta(n);
        for (size_t i = 0; i < n; ++i) {
            const float3 d = normalize(hl[i] - c_);
            theta[i] = std::acos(std::clamp(double(dot(d, pole_)), -1.0, 1.0));
            phi[i] = std::atan2(double(dot(d, e2_)), double(dot(d, e1_)));
        }
        double turn = 0.0;
        int sign = 0;
        for (size_t i = 0; i < n; ++i) {
            double d = phi[(i + 1) % n] - phi[i];
            if (d > kPi) d -= 2 * kPi;
            if (d < -kPi) d += 2 * kPi;
            const int sg = d > 0 ? 1 : d < 0 ? -1 : 0;
            if (sg == 0 || (sign != 0 && sg != sign)) {
                throw InvalidGeometry("sections: the hairline must go once around the crown without turning back; point " + std::to_string(i) +
                                      " turns back (move --crown toward the middle of the haired part)");
            }
            sign = sg;
            turn += d;
        }
        if (std::fabs(std::fabs(turn) - 2 * kPi) > 0.1) {
            throw InvalidGeometry("sections: the hairline must go once around the crown; it turns " + format_number(turn * 180 / kPi) + " degrees");
        }
        std::vector<size_t> order(n);
        std::iota(order.begin(), order.end(), size_t(0));
        std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return phi[a] < phi[b]; });
        for (size_t i : order) {
            phi_.push_back(phi[i]);
            theta_.push_back(theta[i]);
        }
        s0_ = 0.0;
    }
    else {
        // Latitude about the ear-to-ear axis: the hairline's widest reaches bound it, unless the
        // region covers an end of the axis (a hairline below the ears), where bands reach the pole.
        double smax = 0.0;
        for (const float3& p : hl) smax = std::max(smax, std::fabs(std::asin(std::clamp(double(dot(normalize(p - c_), side_)), -1.0, 1.0))));
        if (region.inside_hairline(c_ + side_) || region.inside_hairline(c_ - side_)) smax = 0.5 * kPi - 1e-6;
        s0_ = -smax;
    }
    const double s_range = layout_ == SectionLayout::Radial ? 1.0 : -2.0 * s0_;
    mean_r_ = 0.0f;
    for (const float3& p : hl) mean_r_ += distance(p, c_) / float(hl.size());
    mean_r_ = 0.5f * (mean_r_ + distance(hit(layout_ == SectionLayout::Radial ? pole_ : up_), c_));

    // --- The ruler across the bands: scene length along s, averaged over lines of constant t (grid,
    // rows: five lines from over the forehead to the back of the head; radial: 16 azimuths, crown to
    // hairline). Grid and rows bands are cut equally wide on it, so the narrower sides of a head get
    // bands as wide as those over the top; rings follow the hairline, equal in s.
    const int nruler = 128;
    std::vector<double> ruler(nruler + 1, 0.0);
    {
        const bool radial = layout_ == SectionLayout::Radial;
        const int lines = radial ? 16 : 5;
        for (int a = 0; a < lines; ++a) {
            const double t = radial ? -kPi + 2 * kPi * (a + 0.5) / lines : (-30.0 + 30.0 * a) * kPi / 180.0;
            float3 prev = hit(to_dir(s0_, t));
            for (int i = 1; i <= nruler; ++i) {
                const float3 q = hit(to_dir(s0_ + s_range * i / nruler, t));
                ruler[i] += distance(prev, q) / lines;
                prev = q;
            }
        }
        for (int i = 1; i <= nruler; ++i) ruler[i] += ruler[i - 1];
    }
    const double across = ruler.back();

    // --- How many bands: given, from the size, or the layout's default.
    switch (layout_) {
    case SectionLayout::Grid: bands_ = params.cols > 0 ? params.cols : params.size > 0 ? bands_from_size(across, params.size, 256, false, "bands") : 8; break;
    case SectionLayout::Rows:
        if (params.rows > 0) bands_ = params.rows;
        else if (params.size > 0) bands_ = bands_from_size(across, params.size, 256, true, "rows");
        else bands_ = 7;
        break;
    case SectionLayout::Radial:
        bands_ = params.rings > 0 ? params.rings : params.size > 0 ? bands_from_size(across, params.size, 64, false, "rings") : 1;
        break;
    }
    edges_.assign(size_t(bands_) + 1, 0.0);
    for (int b = 0; b <= bands_; ++b) {
        if (layout_ == SectionLayout::Radial) {
            edges_[b] = double(b) / bands_;
            continue;
        }
        const double want = across * b / bands_;
        const int i = std::clamp(int(std::upper_bound(ruler.begin(), ruler.end(), want) - ruler.begin()) - 1, 0, nruler - 1);
        const double f = ruler[i + 1] > ruler[i] ? (want - ruler[i]) / (ruler[i + 1] - ruler[i]) : 0.0;
        edges_[b] = s0_ + s_range * (i + std::clamp(f, 0.0, 1.0)) / nruler;
    }
    edges_.front() = s0_;
    edges_.back() = s0_ + s_range;

    // --- The image: k rows across each band (odd, so one row is the band's middle), nt columns along t.
    double widest = 0.0;
    for (int b = 0; b < bands_; ++b) widest = std::max(widest, edges_[b + 1] - edges_[b]);
    if (layout_ == SectionLayout::Radial) widest *= *std::max_element(theta_.begin(), theta_.end());
    int k = std::max(9, int(std::ceil(widest / kImageStep)));
    k |= 1;
    const int ns = bands_ * k;
    const int nt = int(std::ceil(2 * kPi / kImageStep));
    const double dt = 2 * kPi / nt;
    auto ds_at = [&](int i) { return (edges_[i / k + 1] - edges_[i / k]) / k; };
    auto s_at = [&](int i) { return edges_[i / k] + (i % k + 0.5) * ds_at(i); };
    auto t_at = [&](int j) { return -kPi + (j + 0.5) * dt; };
    const size_t nimg = size_t(ns) * size_t(nt);
    std::vector<float3> X(nimg);
    std::vector<double> area(nimg, 0.0);
    std::vector<uint8_t> in(nimg, 0);
    std::vector<int64_t> row_rays(size_t(ns), 0);
    {
        ProgressStep step(progress, "sections: chart", ns);
        parallel_for(ns, 1, [&](int64_t b, int64_t e) {
            for (int64_t i = b; i < e; ++i) {
                float r_prev = 0.0f;
                for (int j = 0; j < nt; ++j) {
                    const size_t at = size_t(i) * nt + j;
                    const double s = s_at(int(i)), t = t_at(j);
                    const float3 d = to_dir(s, t);
                    if (!region_.inside_hairline(c_ + d)) {
                        r_prev = 0.0f;
                        continue;
                    }
                    // Start just outside the neighbour's hit: inside the field's narrow band, where
                    // queries are cheap; a start found inside the scalp falls back to the far start.
                    float3 x;
                    bool ok = false;
                    if (r_prev > 0.0f) {
                        const float3 a = c_ + d * (r_prev * 1.03f);
                        if (scalp_.distance(a) > 0.0f) ok = scalp_.first_intersection(a, c_, x, 1e-5f * reach_);
                    }
                    if (!ok) x = hit(d);
                    ++row_rays[size_t(i)];
                    const float r = distance(x, c_);
                    r_prev = r;
                    const double cos_a = std::max(kMinCos, double(dot(scalp_.normal(x), d)));
                    X[at] = x;
                    area[at] = double(r) * r / cos_a * jacobian(s, t) * ds_at(int(i)) * dt;
                    in[at] = 1;
                }
            }
            step.advance(e - b);
        });
    }
    rays_ = std::accumulate(row_rays.begin(), row_rays.end(), int64_t(0));

    // --- Band areas (per column of the image) and the length of each band's middle line.
    std::vector<int> row0(size_t(bands_) + 1);  // band b owns image rows [row0[b], row0[b+1])
    for (int b = 0; b <= bands_; ++b) row0[b] = b * k;
    std::vector<std::vector<double>> hist(size_t(bands_), std::vector<double>(size_t(nt), 0.0));
    for (int i = 0; i < ns; ++i)
        for (int j = 0; j < nt; ++j) hist[size_t(i / k)][size_t(j)] += area[size_t(i) * nt + j];
    const bool periodic = layout_ == SectionLayout::Radial;
    auto band_area = [&](int b) { return std::accumulate(hist[b].begin(), hist[b].end(), 0.0); };
    auto band_length = [&](int b) {
        const int im = (row0[b] + row0[b + 1]) / 2;  // the band's middle row (or the first past it)
        double len = 0.0;
        for (int j = 0; j < nt; ++j) {
            const int j1 = j + 1 < nt ? j + 1 : periodic ? 0 : -1;
            if (j1 < 0) continue;
            const size_t a0 = size_t(im) * nt + j, a1 = size_t(im) * nt + j1;
            if (in[a0] && in[a1]) len += distance(X[a0], X[a1]);
        }
        return len;
    };
    // The band holding the chart's middle (s = 0; radial: the outermost ring): grid --rows counts its cells.
    int middle = periodic ? bands_ - 1 : int(std::upper_bound(edges_.begin(), edges_.end(), 0.0) - edges_.begin()) - 1;
    middle = std::clamp(middle, 0, bands_ - 1);
    if (!periodic && bands_ % 2 == 0 && middle > 0 && band_area(middle - 1) > band_area(middle)) --middle;

    // --- The area every grid cell aims at: square in the middle band (its width squared), or the
    // middle band cut into --rows. A band at either side too small for half a cell (the hairline
    // leaves a sliver over the ear) joins its neighbour: a cell that small would be no braid's.
    if (layout_ == SectionLayout::Grid) {
        const double a_mid = band_area(middle), l_mid = band_length(middle);
        const double target = params.rows > 0 ? a_mid / params.rows : l_mid > 0.0 ? std::pow(a_mid / l_mid, 2.0) : a_mid;
        auto merge = [&](int b) {  // band b joins band b + 1
            for (int j = 0; j < nt; ++j) hist[b][j] += hist[b + 1][j];
            hist.erase(hist.begin() + b + 1);
            edges_.erase(edges_.begin() + b + 1);
            row0.erase(row0.begin() + b + 1);
            --bands_;
        };
        while (bands_ > 2 && band_area(0) < 0.5 * target) merge(0);
        while (bands_ > 2 && band_area(bands_ - 1) < 0.5 * target) merge(bands_ - 2);
        grid_target_ = target;
    }

    // --- Cells along each band: equal areas.
    cuts_.assign(size_t(bands_), {});
    first_.assign(size_t(bands_), -1);
    std::vector<int> cells(size_t(bands_), 0);
    for (int b = 0; b < bands_; ++b) {
        const double ab = band_area(b);
        if (ab <= 0.0) continue;
        switch (layout_) {
        case SectionLayout::Grid: cells[b] = round_count(std::min(ab / grid_target_, 256.0)); break;  // --rows' most
        case SectionLayout::Rows: cells[b] = 1; break;
        case SectionLayout::Radial:
            if (params.wedges > 0 || params.size <= 0) {
                const int outer = params.wedges > 0 ? params.wedges : 12;
                cells[b] = round_count(outer * ab / band_area(bands_ - 1));
            }
            else {
                // Square cells: as long around as the ring is wide (area / length of its middle line).
                const double l = band_length(b);
                cells[b] = round_count(std::min(l > 0.0 ? l * l / ab : 1.0, 256.0));  // --wedges' most
            }
            break;
        }
    }
    int count = 0;
    for (int b = 0; b < bands_; ++b) {
        if (cells[b] == 0) continue;
        first_[b] = count;
        const double ab = band_area(b);
        // Cut where the cumulative area along t reaches m / n of the band's (linear within a sample).
        double cum = 0.0;
        int m = 1;
        for (int j = 0; j < nt && m < cells[b]; ++j) {
            const double next = cum + hist[b][j];
            while (m < cells[b] && next >= ab * m / cells[b]) {
                const double f = hist[b][j] > 0.0 ? (ab * m / cells[b] - cum) / hist[b][j] : 0.0;
                cuts_[b].push_back(-kPi + (j + f) * dt);
                ++m;
            }
            cum = next;
        }
        for (int c = 0; c < cells[b]; ++c) {
            SectionInfo info;
            info.band = b;
            info.cell = c;
            sections_.push_back(info);
        }
        count += cells[b];
    }
    if (sections_.empty()) throw InvalidGeometry("sections: the hairline encloses no scalp");
    std::vector<int> band_of_row(static_cast<size_t>(ns));
    for (int b = 0; b < bands_; ++b)
        for (int i = row0[b]; i < row0[b + 1]; ++i) band_of_row[size_t(i)] = b;

    // --- Each section's area, centroid and margin-maximising image sample.
    std::vector<int32_t> sec(nimg, -1);
    std::vector<float> marg(nimg, -std::numeric_limits<float>::infinity());
    parallel_for(ns, 4, [&](int64_t b, int64_t e) {
        for (int64_t i = b; i < e; ++i) {
            const int band = band_of_row[size_t(i)];
            if (first_[band] < 0) continue;
            for (int j = 0; j < nt; ++j) {
                const size_t at = size_t(i) * nt + j;
                if (!in[at]) continue;
                sec[at] = first_[band] + cell_of(band, t_at(j));
                marg[at] = margin(X[at], sec[at]);
            }
        }
    });
    std::vector<double> sx(sections_.size(), 0.0), sy(sections_.size(), 0.0), sz(sections_.size(), 0.0);
    std::vector<size_t> best(sections_.size(), nimg);
    for (size_t at = 0; at < nimg; ++at) {
        const int s = sec[at];
        if (s < 0) continue;
        sections_[s].area += area[at];
        sx[s] += area[at] * X[at].x;
        sy[s] += area[at] * X[at].y;
        sz[s] += area[at] * X[at].z;
        if (best[s] == nimg || marg[at] > marg[best[s]]) best[s] = at;
    }
    const float need = params.parting_gap;
    parallel_for(int64_t(sections_.size()), 1, [&](int64_t b, int64_t e) {
        for (int64_t s = b; s < e; ++s) {
            SectionInfo& info = sections_[s];
            if (info.area <= 0.0) {
                info.root = info.centroid = hit(to_dir(0.5 * (edges_[info.band] + edges_[info.band + 1]), 0.0));
                continue;
            }
            info.centroid = float3(float(sx[s] / info.area), float(sy[s] / info.area), float(sz[s] / info.area));
            // The centroid carried onto the scalp along its ray, unless that leaves it near the
            // section's border (a crescent's centroid lies outside it): then the image sample
            // deepest inside.
            const float3 x = hit(normalize(info.centroid - c_, up_));
            info.root = section_of(x) == int(s) && margin(x, int(s)) >= need ? x : X[best[s]];
        }
    });
}

// --- The chart ---------------------------------------------------------------------------------------

SectionMap::Param SectionMap::to_param(const float3& d) const
{
    Param q;
    if (layout_ == SectionLayout::Radial) {
        const double theta = std::acos(std::clamp(double(dot(d, pole_)), -1.0, 1.0));
        q.t = std::atan2(double(dot(d, e2_)), double(dot(d, e1_)));
        q.s = theta / hairline_theta(q.t);
    }
    else {
        q.s = std::asin(std::clamp(double(dot(d, side_)), -1.0, 1.0));
        q.t = std::atan2(double(dot(d, back_)), double(dot(d, up_)));
    }
    return q;
}

float3 SectionMap::to_dir(double s, double t) const
{
    if (layout_ == SectionLayout::Radial) {
        const double theta = s * hairline_theta(t);
        const double st = std::sin(theta);
        return normalize(pole_ * float(std::cos(theta)) + e1_ * float(st * std::cos(t)) + e2_ * float(st * std::sin(t)));
    }
    const double cs = std::cos(s);
    return normalize(side_ * float(std::sin(s)) + up_ * float(cs * std::cos(t)) + back_ * float(cs * std::sin(t)));
}

double SectionMap::jacobian(double s, double t) const
{
    if (layout_ == SectionLayout::Radial) {
        // (rho, phi) -> (theta = rho theta_h(phi), phi): d theta d phi = theta_h d rho d phi.
        const double th = hairline_theta(t);
        return std::sin(s * th) * th;
    }
    return std::cos(s);
}

double SectionMap::s_scale(double s, double t, double r) const
{
    (void)s;
    return layout_ == SectionLayout::Radial ? r * hairline_theta(t) : r;
}

double SectionMap::t_scale(double s, double t, double r) const
{
    return layout_ == SectionLayout::Radial ? r * std::sin(s * hairline_theta(t)) : r * std::cos(s);
}

double SectionMap::hairline_theta(double phi) const
{
    // Linear in azimuth between the two hairline points around phi (periodic), as HairRegion reads it.
    phi = std::remainder(phi, 2 * kPi);
    const size_t n = phi_.size();
    const size_t hi = std::upper_bound(phi_.begin(), phi_.end(), phi) - phi_.begin();
    const size_t i1 = hi % n, i0 = (hi + n - 1) % n;
    double a0 = phi_[i0], a1 = phi_[i1];
    if (hi == 0) a0 -= 2 * kPi;
    if (hi == n) a1 += 2 * kPi;
    const double f = a1 > a0 ? (phi - a0) / (a1 - a0) : 0.0;
    return theta_[i0] + (theta_[i1] - theta_[i0]) * f;
}

int SectionMap::band_of(double s) const
{
    return std::clamp(int(std::upper_bound(edges_.begin() + 1, edges_.end() - 1, s) - edges_.begin()) - 1, 0, bands_ - 1);
}

int SectionMap::cell_of(int band, double t) const
{
    const auto& c = cuts_[size_t(band)];
    return int(std::upper_bound(c.begin(), c.end(), t) - c.begin());
}

bool SectionMap::inside(double s, double t) const { return region_.inside_hairline(c_ + to_dir(s, t)); }

float3 SectionMap::hit(const float3& dir) const
{
    float3 x;
    if (!scalp_.first_intersection(c_ + dir * reach_, c_, x, 1e-5f * reach_)) {
        // Begins "sections: the hairline" so the command names the file (a trial's hairline was
        // made on another head, and the message did not say which file or why).
        throw InvalidGeometry("sections: the hairline's centroid " + format_xyz(c_) + " is not inside the head: no scalp along the ray toward " +
                              format_xyz(dir) + " (was the hairline made on another head, or in other units?)");
    }
    return x;
}

// --- Queries ------------------------------------------------------------------------------------------

float SectionMap::hairline_distance(const float3& p) const
{
    // The nearest hairline points and the segments either side of them (the points are as close as
    // the hairline's own spacing, so the nearest segment touches one of the two nearest points).
    std::vector<PointIndex::Neighbour> nb;
    hairline_index_->nearest(p, 2, nb);
    const size_t n = hairline_.size();
    double best = std::numeric_limits<double>::infinity();
    for (const auto& q : nb) {
        const size_t i = q.index;
        for (size_t j : {(i + 1) % n, (i + n - 1) % n}) best = std::min(best, segment_distance_sq(p, p, hairline_[i], hairline_[j]));
    }
    const float d = float(std::sqrt(best));
    return region_.inside_hairline(p) ? d : -d;
}

int SectionMap::section_of(const float3& p) const
{
    if (!region_.inside_hairline(p)) return -1;
    const Param q = to_param(normalize(p - c_, up_));
    const int b = band_of(q.s);
    return first_[size_t(b)] < 0 ? -1 : first_[size_t(b)] + cell_of(b, q.t);
}

float SectionMap::margin(const float3& p, int section) const
{
    const SectionInfo& info = sections_[size_t(section)];
    const float r = distance(p, c_);
    const Param q = to_param(normalize(p - c_, up_));
    double m = hairline_distance(p);
    // Borders between bands are partings; the chart's own ends are not (the hairline is there).
    const double lo = edges_[info.band], hi = edges_[info.band + 1];
    const double ss = s_scale(q.s, q.t, r), ts = t_scale(q.s, q.t, r);
    if (info.band > 0) m = std::min(m, (q.s - lo) * ss);
    if (info.band < bands_ - 1) m = std::min(m, (hi - q.s) * ss);
    const auto& cuts = cuts_[size_t(info.band)];
    const int n = int(cuts.size()) + 1;
    if (layout_ == SectionLayout::Radial && n > 1) {
        // Wedges: both sides are partings (the first and last wedge meet at the back, t = +-pi).
        const double a = info.cell > 0 ? cuts[info.cell - 1] : -kPi, b = info.cell < n - 1 ? cuts[info.cell] : kPi;
        m = std::min(m, std::min(q.t - a, b - q.t) * ts);
    }
    else {
        if (info.cell > 0) m = std::min(m, (q.t - cuts[info.cell - 1]) * ts);
        if (info.cell < n - 1) m = std::min(m, (cuts[info.cell] - q.t) * ts);
    }
    return float(m);
}

// --- Border lines -------------------------------------------------------------------------------------

template <class At>
void SectionMap::trace(At at, double lo, double hi, double unit_length, bool closed, float spacing, float overshoot, int kind, int band,
                       std::vector<Border>& out) const
{
    // Sampled at a quarter of the spacing to find where the line crosses the hairline, then each
    // crossing refined by bisection.
    const int n = std::max(8, int(std::ceil((hi - lo) * unit_length / (0.25 * spacing))));
    std::vector<double> lam(static_cast<size_t>(n));
    std::vector<uint8_t> ins(static_cast<size_t>(n));
    for (int i = 0; i < n; ++i) {
        lam[i] = closed ? lo + (hi - lo) * i / n : lo + (hi - lo) * i / (n - 1);
        const Param q = at(lam[i]);
        ins[i] = inside(q.s, q.t);
    }
    auto crossing = [&](double l_out, double l_in) {
        for (int it = 0; it < 40; ++it) {
            const double mid = 0.5 * (l_out + l_in);
            const Param q = at(mid);
            (inside(q.s, q.t) ? l_in : l_out) = mid;
        }
        return l_in;
    };
    auto emit = [&](double a, double b, bool loop) {
        Border border;
        border.kind = kind;
        border.band = band;
        const int m = std::max(1, int(std::ceil(std::fabs(b - a) * unit_length / spacing)));
        for (int i = 0; i <= m; ++i) {
            if (loop && i == m) {
                border.points.push_back(border.points.front());
                break;
            }
            const Param q = at(a + (b - a) * i / m);
            border.points.push_back(hit(to_dir(q.s, q.t)));
        }
        out.push_back(std::move(border));
    };
    const double over = overshoot / unit_length;
    if (closed) {
        // A loop wholly inside is one closed parting; otherwise start it at an outside sample and
        // close it with that sample again, so every run inside has an outside sample either side.
        const auto first_out = std::find(ins.begin(), ins.end(), uint8_t(0));
        if (first_out == ins.end()) {
            emit(lo, hi, true);
            return;
        }
        const size_t start = size_t(first_out - ins.begin());
        std::vector<double> lam2;
        std::vector<uint8_t> ins2;
        for (size_t i = 0; i <= size_t(n); ++i) {
            const size_t j = (start + i) % size_t(n);
            lam2.push_back(lam[j] + (start + i >= size_t(n) ? hi - lo : 0.0));
            ins2.push_back(ins[j]);
        }
        lam.swap(lam2);
        ins.swap(ins2);
    }
    const int m = int(lam.size());
    for (int i = 0; i < m;) {
        if (!ins[size_t(i)]) {
            ++i;
            continue;
        }
        int j = i;
        while (j + 1 < m && ins[size_t(j + 1)]) ++j;
        // Ends inside the hairline stay where the line ends (on another parting); crossings of the
        // hairline run on past it by the overshoot.
        const double a = i > 0 ? crossing(lam[size_t(i - 1)], lam[size_t(i)]) - over : lam[size_t(i)];
        const double b = j < m - 1 ? crossing(lam[size_t(j + 1)], lam[size_t(j)]) + over : lam[size_t(j)];
        emit(a, b, false);
        i = j + 1;
    }
}

std::vector<SectionMap::Border> SectionMap::borders(float spacing, float overshoot) const
{
    std::vector<Border> out;
    const double r = mean_r_;
    if (layout_ == SectionLayout::Radial) {
        for (int b = 1; b < bands_; ++b) {
            const double rho = edges_[b];
            const double th = rho * std::accumulate(theta_.begin(), theta_.end(), 0.0) / double(theta_.size());
            trace([rho](double l) { return Param{rho, l}; }, -kPi, kPi, r * std::sin(th), true, spacing, overshoot, 0, b, out);
        }
        for (int b = 0; b < bands_; ++b) {
            if (cuts_[b].empty()) continue;
            std::vector<double> lines{-kPi};
            lines.insert(lines.end(), cuts_[b].begin(), cuts_[b].end());
            const double lo = edges_[b];
            // The outermost ring's wedges run out past the hairline (rho = 1), so their crossing is found.
            const double hi = b + 1 < bands_ ? edges_[b + 1] : 1.25;
            for (double t : lines) {
                trace([t](double l) { return Param{l, t}; }, lo, hi, r * hairline_theta(t), false, spacing, overshoot, 1, b, out);
            }
        }
        return out;
    }
    for (int b = 1; b < bands_; ++b) {
        const double s = edges_[b];
        trace([s](double l) { return Param{s, l}; }, -kPi, kPi, r * std::cos(s), false, spacing, overshoot, 0, b, out);
    }
    for (int b = 0; b < bands_; ++b) {
        const double lo = edges_[b], hi = edges_[b + 1];
        for (double t : cuts_[b]) trace([t](double l) { return Param{l, t}; }, lo, hi, r, false, spacing, overshoot, 1, b, out);
    }
    return out;
}

std::vector<float3> SectionMap::midline(int section, float inset, float spacing) const
{
    std::vector<float3> out;
    if (layout_ == SectionLayout::Radial) return out;
    const SectionInfo& info = sections_[size_t(section)];
    const auto& cuts = cuts_[size_t(info.band)];
    const double s = 0.5 * (edges_[info.band] + edges_[info.band + 1]);
    const double lo = info.cell > 0 ? cuts[info.cell - 1] : -kPi;
    const double hi = info.cell < int(cuts.size()) ? cuts[info.cell] : kPi;
    const double unit = double(mean_r_) * std::cos(s);
    const int n = std::max(8, int(std::ceil((hi - lo) * unit / (0.25 * spacing))));
    // The longest run of samples at least `inset` inside the section.
    int best_a = -1, best_len = 0;
    for (int i = 0; i < n;) {
        auto ok = [&](int j) {
            const float3 x = c_ + to_dir(s, lo + (hi - lo) * (j + 0.5) / n) * mean_r_;
            return region_.inside_hairline(x) && margin(x, section) >= inset;
        };
        if (!ok(i)) {
            ++i;
            continue;
        }
        int len = 0;
        while (i + len < n && ok(i + len)) ++len;
        if (len > best_len) best_a = i, best_len = len;
        i += len;
    }
    if (best_a < 0 || best_len < 2) return out;
    const double a = lo + (hi - lo) * (best_a + 0.5) / n, b = lo + (hi - lo) * (best_a + best_len - 0.5) / n;
    const int m = std::max(1, int(std::ceil((b - a) * unit / spacing)));
    for (int i = 0; i <= m; ++i) out.push_back(hit(to_dir(s, a + (b - a) * i / m)));
    return out;
}

}  // namespace groom
