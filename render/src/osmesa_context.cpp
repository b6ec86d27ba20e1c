#include <GL/gl.h>
#include <GL/osmesa.h>
#include <fmt/format.h>

#include <cstdlib>
#include <exception>
#include <vector>

#include "flagsim/core/errors.hpp"
#include "flagsim/render/offscreen_context.hpp"

namespace flagsim::render {
namespace {

// Drawing a W x H image takes about 24 bytes a pixel at its peak: our RGBA
// buffer and Mesa's colour and depth buffers (12), the RGB image read back and
// the one encoded (9), and room for the encoder. Asked for (and given back)
// before Mesa is: a size this process cannot hold is one error line, not an
// out-of-memory error inside the GL library.
void check_room(int width, int height) {
  const std::size_t bytes = std::size_t(width) * std::size_t(height) * 24;
  void* trial = std::malloc(bytes);
  if (!trial)
    throw UserError(
        fmt::format("--size {}x{}: drawing it needs about {} MiB, more than this process can have; "
                    "choose a smaller size",
                    width, height, bytes >> 20));
  std::free(trial);
}

class OsMesaContext final : public OffscreenContext {
 public:
  /// Draws `samples` x `samples` pixels for each of the image's `width` x `height`.
  OsMesaContext(int width, int height, int samples = 1)
      : out_width_(width),
        out_height_(height),
        samples_(samples),
        width_(width * samples),
        height_(height * samples) {
    check_room(width_, height_);
    buffer_.resize(std::size_t(width_) * std::size_t(height_) * 4);
    context_ = OSMesaCreateContextExt(OSMESA_RGBA, 24, 0, 0, nullptr);
    if (!context_) throw UserError("OSMesa could not create a rendering context");
  }
  // Mesa cannot always destroy a context that ran out of memory (a SIGSEGV in
  // OSMesaDestroyContext while an out-of-memory error unwinds): then it is
  // left to the process's end, which that error is on its way to.
  ~OsMesaContext() override {
    if (std::uncaught_exceptions() == 0) OSMesaDestroyContext(context_);
  }
  OsMesaContext(const OsMesaContext&) = delete;
  OsMesaContext& operator=(const OsMesaContext&) = delete;

  int width() const override { return width_; }
  int height() const override { return height_; }
  int samples() const override { return samples_; }
  void make_current() override {
    if (!OSMesaMakeCurrent(context_, buffer_.data(), GL_UNSIGNED_BYTE, width_, height_))
      throw UserError(fmt::format("OSMesa could not draw a {} x {} image", width_, height_));
    OSMesaPixelStore(OSMESA_Y_UP, 0);  // row 0 of the buffer is the top of the image
  }
  Image read_rgb() override {
    glFinish();
    // Each image pixel the mean of its samples x samples drawn ones (a box
    // filter: supersampling, the edges anti-aliased), rounded to nearest.
    Image image(out_width_, out_height_);
    const int count = samples_ * samples_;
    for (int y = 0; y < out_height_; ++y)
      for (int x = 0; x < out_width_; ++x)
        for (int c = 0; c < 3; ++c) {
          int sum = 0;
          for (int sy = 0; sy < samples_; ++sy)
            for (int sx = 0; sx < samples_; ++sx)
              sum += buffer_[(std::size_t(y * samples_ + sy) * std::size_t(width_) +
                              std::size_t(x * samples_ + sx)) *
                                 4 +
                             std::size_t(c)];
          image.rgb[(std::size_t(y) * std::size_t(out_width_) + std::size_t(x)) * 3 +
                    std::size_t(c)] = static_cast<unsigned char>((sum + count / 2) / count);
        }
    return image;
  }

 private:
  int out_width_, out_height_, samples_;
  int width_, height_;
  std::vector<unsigned char> buffer_;
  OSMesaContext context_ = nullptr;
};

}  // namespace

std::unique_ptr<OffscreenContext> make_osmesa_context(int width, int height, int samples) {
  return std::make_unique<OsMesaContext>(width, height, samples);
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
