#pragma once
// The legend of `render --color`: a vertical bar of the ramp at the image's
// right edge, its top and bottom values written beside it (a 5 x 7 pixel
// font, no font library: digits, '.', '%', '/', 'm', 's', ' ', '-').
#include <string_view>

#include "flagsim/render/image.hpp"

namespace flagsim::render {

/// Draws the bar (the ramp from 0 at the bottom to 1 at the top) and the two
/// labels into `image`, scaled with its height (sized for 720 rows, at least
/// 1x). Characters outside the font are drawn as blanks.
void draw_color_bar(Image& image, std::string_view top_label, std::string_view bottom_label);

}  // namespace flagsim::render
