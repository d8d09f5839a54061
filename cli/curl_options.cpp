#include "cli/curl_options.h"

#include "cli/command.h"
#include "kernel/error.h"
#include "ops/hair_types.h"

#include <charconv>

namespace groom::cli {

int curl_shape_from_string(std::string_view text)
{
    for (int i = 0; i < curl_shape_count(); ++i) {
        if (text == curl_shape_name(i)) return i;
    }
    int v = -1;
    const auto res = std::from_chars(text.data(), text.data() + text.size(), v);
    if (!text.empty() && res.ec == std::errc() && res.ptr == text.data() + text.size() && v >= 0 && v < curl_shape_count()) {
        return v;
    }
    return -1;
}

namespace {

int parse_shape(const std::string& option, const std::string& text)
{
    const int s = curl_shape_from_string(text);
    if (s < 0) throw InvalidParam(option + ": unknown shape '" + text + "' (expected a name or number: " + curl_shape_list() + ")");
    return s;
}

}  // namespace

void add_curl_options(CLI::App* app, CurlOptions& o, bool with_seed)
{
    const CurlParams d;
    app->add_option("--type", o.type, "Hair type " + hair_type_list() + ": sets the frequency:amplitude ratio, default radius and shapes (default " + d.hair_type + ")");
    app->add_option("--dominant", o.dominant, "Tier A shape, name or number (" + curl_shape_list() + "); default: the type's");
    app->add_option("--uniformity", o.params.uniformity, "Probability a cycle takes the dominant shape, 0..1")->capture_default_str();
    app->add_option("--shapes", o.shapes, "Allowed shapes, comma list of names or numbers (default all)");
    app->add_option("--amplitude", o.amplitude, "Curl radius range lo,hi, scene units, per cycle (default: the type's radius, +-20%)");
    app->add_option("--frequency", o.frequency, "Cycles per scene unit of guide, lo,hi, per curve (default: type ratio / amplitude)");
    app->add_option("--phase", o.phase, "Rotation of the cross-section, turns, lo,hi, per curve (default 0,1)");
    app->add_option("--offset", o.offset, "Cycle centre offset from the guide, scene units, lo,hi, per cycle (default 0)");
    app->add_option("--units-per-cm", o.params.units_per_cm, "Scene units per centimetre, for the type's default radius and the default widths")->capture_default_str();
    app->add_option("--root-ease", o.params.root_ease, "Straight length at the root, scene units")->capture_default_str();
    app->add_option("--root-ramp", o.params.root_ramp, "Cycles over which the curl grows in after the straight root")->capture_default_str();
    app->add_option("--samples", o.params.samples, "Output points per curl cycle, 4..256")->capture_default_str();
    app->add_option("--blend", o.params.blend, "Half-width of the shape blend at cycle joins, cycles, [0, 0.5)")->capture_default_str();
    app->add_flag("--keep-extent", o.keep_extent, "Curl the whole guide (the hair gets longer) instead of keeping the hair's length");
    app->add_option("--lame-exponent", o.params.shape.lame_exponent, "Lame curve exponent n, > 0")->capture_default_str();
    app->add_option("--polygon-sides", o.params.shape.polygon_sides, "Polygon sides, 3..64")->capture_default_str();
    app->add_option("--ellipse-aspect", o.params.shape.ellipse_aspect, "Ellipse minor/major axis, (0, 1]")->capture_default_str();
    app->add_option("--rose-petals", o.params.shape.rose_petals, "Polar rose k in r = cos(k theta), 1..32")->capture_default_str();
    // Default widths scale with --units-per-cm, as the default radius does.
    add_width_options(app, o.widths, "the input's widths (interpolated), else the defaults x --units-per-cm");
    if (with_seed) app->add_option("--seed", o.params.seed, "Random seed")->capture_default_str();
}

CurlParams curl_params_from(const CurlOptions& o, const std::string& command)
{
    CurlParams p = o.params;
    if (!o.type.empty()) p.hair_type = o.type;
    if (!o.dominant.empty()) p.dominant = parse_shape("--dominant", o.dominant);
    p.shapes.clear();
    if (!o.shapes.empty()) {
        size_t start = 0;
        while (start <= o.shapes.size()) {
            size_t end = o.shapes.find(',', start);
            if (end == std::string::npos) end = o.shapes.size();
            p.shapes.push_back(parse_shape("--shapes", o.shapes.substr(start, end - start)));
            start = end + 1;
        }
    }
    p.amplitude = parse_range("--amplitude", o.amplitude, p.amplitude);
    p.frequency = parse_range("--frequency", o.frequency, p.frequency);
    // The op reads {0, 0} as "the type's default"; a user who typed 0 asked for no curl, or a
    // mistake, and got the default curl without a word (a user trial).
    const auto refuse_zero = [&command](const char* option, const std::string& text, const FloatRange& range) {
        if (!text.empty() && range.lo == 0.0f && range.hi == 0.0f) {
            throw InvalidParam(command + ": " + option + " must be lo,hi with hi > 0 (got '" + text + "'); leave " + option +
                               " out for the hair type's default, or skip curl for straight hair");
        }
    };
    refuse_zero("--amplitude", o.amplitude, p.amplitude);
    refuse_zero("--frequency", o.frequency, p.frequency);
    p.phase = parse_range("--phase", o.phase, p.phase);
    p.offset = parse_range("--offset", o.offset, p.offset);
    p.preserve_length = !o.keep_extent;
    p.widths = hair_widths_from(o.widths, command);
    p.validate_for(command);
    return p;
}

}  // namespace groom::cli
