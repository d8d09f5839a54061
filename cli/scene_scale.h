// Scene units against the defaults: groom's defaults (hair widths, curl radii, baby-hair lengths)
// are centimetres times --units-per-cm, and a scene in metres or millimetres that keeps the default
// 1 gets hair 100 times too thick or curls 100 times too big, silently (a trial on Ratboy, in
// metres: 8 mm hairs, curls of 0.7 m radius that left the hair straight). These checks say so.
#pragma once

#include "cli/command.h"
#include "kernel/curve_set.h"
#include "kernel/math/vec.h"

#include <initializer_list>
#include <string>
#include <utility>

namespace groom::cli {

/// A warning (stderr, unless --quiet) when the scalp's largest extent is outside what a head, a bust
/// or a body measures in centimetres times `units_per_cm` (10 to 300 cm): the scene is probably
/// not in the units the defaults assume. `what` names the defaults in play (e.g. "the default
/// widths").
void warn_scene_scale(const CommonOptions& common, const std::string& command, const Bounds3& scalp, float units_per_cm,
                      const std::string& what);

/// Throws InvalidParam "<command>: --units-per-cm must be a finite number > 0 (got ...)".
void check_units_per_cm(const std::string& command, float units_per_cm);

/// Multiplies each length whose option (`--lift`, ...) was not typed by `units_per_cm`: its default
/// is centimetres, while a length the user typed is taken as scene units (edges, gather).
void scale_default_lengths(const CLI::App& app, float units_per_cm, std::initializer_list<std::pair<const char*, float*>> lengths);

/// The median of the curves' polyline lengths (0 for no curves).
double median_curve_length(const CurveSet& curves);

/// A warning when a default curl radius (`radius`, scene units: the hair type's centimetres times
/// `units_per_cm`) cannot show on these hairs: more than half their median length (a hair shorter
/// than two radii does not finish a turn) or under a thousandth of it (curls finer than a hair is
/// wide). `how` says where the radius came from.
void warn_curl_scale(const CommonOptions& common, const std::string& command, const CurveSet& hair, float radius, const std::string& how);

}  // namespace groom::cli
