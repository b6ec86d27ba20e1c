#include <GL/gl.h>
#include <GL/osmesa.h>
#include <fmt/format.h>

#include <vector>

#include "flagsim/core/errors.hpp"
#include "flagsim/render/offscreen_context.hpp"

namespace flagsim::render {
namespace {

class OsMesaContext final : public OffscreenContext {
 public:
  OsMesaContext(int width, int height)
      : width_(width), height_(height), buffer_(std::size_t(width) * std::size_t(height) * 4) {
    context_ = OSMesaCreateContextExt(OSMESA_RGBA, 24, 0, 0, nullptr);
    if (!context_) throw UserError("OSMesa could not create a rendering context");
  }
  ~OsMesaContext() override { OSMesaDestroyContext(context_); }
  OsMesaContext(const OsMesaContext&) = delete;
  OsMesaContext& operator=(const OsMesaContext&) = delete;

  int width() const override { return width_; }
  int height() const override { return height_; }
  void make_current() override {
    if (!OSMesaMakeCurrent(context_, buffer_.data(), GL_UNSIGNED_BYTE, width_, height_))
      throw UserError(fmt::format("OSMesa could not draw a {} x {} image", width_, height_));
    OSMesaPixelStore(OSMESA_Y_UP, 0);  // row 0 of the buffer is the top of the image
  }
  Image read_rgb() override {
    glFinish();
    Image image(width_, height_);
    const std::size_t n = std::size_t(width_) * std::size_t(height_);
    for (std::size_t i = 0; i < n; ++i)
      for (int c = 0; c < 3; ++c)
        image.rgb[i * 3 + std::size_t(c)] = buffer_[i * 4 + std::size_t(c)];
    return image;
  }

 private:
  int width_, height_;
  std::vector<unsigned char> buffer_;
  OSMesaContext context_ = nullptr;
};

}  // namespace

std::unique_ptr<OffscreenContext> make_osmesa_context(int width, int height) {
  return std::make_unique<OsMesaContext>(width, height);
}

std::string osmesa_gl_version() {
  try {
    OsMesaContext context(16, 16);
    context.make_current();
    const auto* version = reinterpret_cast<const char*>(glGetString(GL_VERSION));
    return version ? std::string(version) : "unavailable";
  } catch (const UserError&) {
    return "unavailable";
  }
}

}  // namespace flagsim::render
