#pragma once
// A headless OpenGL context: the one thing the renderer needs from a platform.
// Today's provider is OSMesa (Mesa's software rasterizer, no display, no GPU);
// newer Mesa releases drop OSMesa, and an EGL provider (EGL_MESA_platform_surfaceless
// or a pbuffer) can implement the same two calls.
#include <memory>

#include "flagsim/render/image.hpp"

namespace flagsim::render {

class OffscreenContext {
 public:
  virtual ~OffscreenContext() = default;
  /// The drawn buffer's size, pixels (the image's times the samples per side).
  virtual int width() const = 0;
  virtual int height() const = 0;
  /// Drawn pixels per image pixel along each side (supersampling), 1 for none.
  virtual int samples() const { return 1; }
  /// Makes the context current on this thread; GL 1.x calls draw into it.
  virtual void make_current() = 0;
  /// Finishes drawing and returns the colour buffer, row 0 at the top.
  virtual Image read_rgb() = 0;
};

/// An OSMesa context whose images are `width` x `height` pixels, with a depth
/// buffer; it draws `samples` x `samples` pixels for each and read_rgb()
/// averages them (supersampling; width() and height() are the drawn sizes).
/// Throws UserError when OSMesa cannot create one.
std::unique_ptr<OffscreenContext> make_osmesa_context(int width, int height, int samples = 1);

/// The GL implementation an OSMesa context gets ("4.5 (Compatibility Profile)
/// Mesa 22.3.6": GL_VERSION of a 16 x 16 one), for --version; "unavailable"
/// when none can be made.
std::string osmesa_gl_version();

}  // namespace flagsim::render
