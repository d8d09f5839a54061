// The curl op's command-line options, shared by `groom curl` and any command that curls what it
// generates (e.g. `groom puff`), so every curl option is spelled, documented and checked once.
#pragma once

#include "cli/width_options.h"
#include "ops/curl.h"

#include <CLI/CLI.hpp>

#include <string>
#include <string_view>

namespace groom::cli {

/// Option text as typed (lists and ranges are parsed after CLI11 has run) plus the params that
/// CLI11 fills directly.
struct CurlOptions {
    std::string type, dominant, shapes, amplitude, frequency, phase, offset;
    bool keep_extent = false;
    WidthOptions widths;
    CurlParams params;
};

/// Adds --type --dominant --uniformity --shapes --amplitude --frequency --phase --offset
/// --units-per-cm --root-ease --root-ramp --samples --blend --keep-extent --lame-exponent
/// --polygon-sides --ellipse-aspect --rose-petals --root-width --tip-width and (with_seed) --seed to `app`, writing into `o`.
/// A command with a --seed of its own passes with_seed = false and sets o.params.seed itself.
void add_curl_options(CLI::App* app, CurlOptions& o, bool with_seed = true);

/// The validated CurlParams the options describe. Throws InvalidParam naming the option, with
/// `command` ("puff", "gather") as the messages' prefix.
CurlParams curl_params_from(const CurlOptions& o, const std::string& command = "curl");

/// Index of a shape given by name (case-sensitive, as curl_shape_name spells it) or by its number
/// ("0".."4"); -1 when unknown.
int curl_shape_from_string(std::string_view text);

}  // namespace groom::cli
