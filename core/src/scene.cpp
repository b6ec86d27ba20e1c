#include "flagsim/core/scene.hpp"

#include <cmath>

namespace flagsim {

int Scene::simulated_frames() const {
  // t = 0 is frame 0; the last frame is the one at (or just before) duration.
  return int(std::floor(duration_s * fps + 1e-9)) + 1;
}

Lattice Scene::fine_lattice() const {
  return Lattice::rectangle(flag.fine_rows, flag.fine_cols, flag.width_m, flag.height_m,
                            flag.origin_m);
}

const char* to_string(Mode mode) {
  switch (mode) {
    case Mode::kHybrid:
      return "hybrid";
    case Mode::kMassSpring:
      return "mass-spring";
    case Mode::kBullet:
      return "bullet";
    case Mode::kInfill:
      return "infill";
  }
  return "?";
}

const char* to_string(PinSet pin) {
  switch (pin) {
    case PinSet::kLeft:
      return "left";
    case PinSet::kRight:
      return "right";
    case PinSet::kTop:
      return "top";
    case PinSet::kCorners:
      return "corners";
    case PinSet::kNone:
      return "none";
  }
  return "?";
}

}  // namespace flagsim
