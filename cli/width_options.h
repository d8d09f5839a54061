// --root-width and --tip-width, shared by every command that makes hairs (ops/hair_widths.h), so the
// options are spelled, documented and checked once.
#pragma once

#include "ops/hair_widths.h"

#include <CLI/CLI.hpp>

#include <string>

namespace groom::cli {

struct WidthOptions {
    float root = 0.0f, tip = 0.0f;
    CLI::Option* root_opt = nullptr;
    CLI::Option* tip_opt = nullptr;
};

/// Adds --root-width and --tip-width to `app`. `unset` says what the command writes when neither is
/// given; empty: the human-hair defaults (the help prints them).
void add_width_options(CLI::App* app, WidthOptions& o, const std::string& unset = {});

/// The widths the options ask for (unset when not given). Throws InvalidParam naming the option.
HairWidths hair_widths_from(const WidthOptions& o, std::string_view command);

}  // namespace groom::cli
