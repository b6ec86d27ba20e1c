#pragma once
// The built-in texture: seven horizontal stripes, red and white, with a blue
// canton at the hoist (upper left): strong edges in both directions, so a fold
// or a wrinkle shows in the texture as well as in the shading.
#include "flagsim/render/image.hpp"

namespace flagsim::render {

/// 192 x 128 pixels; row 0 is the top edge of the flag, column 0 the pole edge.
Image flag_pattern();

}  // namespace flagsim::render
