// --view / --views and --color-by names to View and ColorBy (render_options.h); the messages name the
// valid words. Kept out of ops/ so the library only turns enums into names, never names into enums.
#include "cli/render_options.h"

#include "kernel/error.h"

#include <string>

namespace groom::cli {

View parse_view(std::string_view name)
{
    if (name == "front") return View::Front;
    if (name == "back") return View::Back;
    if (name == "left" || name == "side") return View::Left;
    if (name == "right") return View::Right;
    if (name == "top") return View::Top;
    if (name == "three-quarter" || name == "threequarter" || name == "3/4") return View::ThreeQuarter;
    throw InvalidParam("render: unknown view '" + std::string(name) + "' (expected front, back, left, right, top or three-quarter)");
}

ColorBy parse_color_by(std::string_view name)
{
    if (name == "none") return ColorBy::None;
    if (name == "strand") return ColorBy::Strand;
    if (name == "guide") return ColorBy::Guide;
    if (name == "shape") return ColorBy::Shape;
    if (name == "kind") return ColorBy::Kind;
    if (name == "id") return ColorBy::Id;
    if (name == "file") return ColorBy::File;
    throw InvalidParam("render: unknown --color-by '" + std::string(name) + "' (expected none, strand, guide, shape, kind, id or file)");
}

}  // namespace groom::cli
