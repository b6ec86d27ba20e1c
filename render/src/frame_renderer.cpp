#include "flagsim/render/frame_renderer.hpp"

#include <GL/gl.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "flagsim/core/lattice.hpp"
#include "flagsim/render/flag_pattern.hpp"

namespace flagsim::render {
namespace {

constexpr float kSky[3] = {0.62f, 0.76f, 0.90f};
constexpr float kGround[3] = {0.42f, 0.50f, 0.38f};
constexpr float kGroundLine[3] = {0.36f, 0.43f, 0.33f};
constexpr float kCloth[3] = {0.80f, 0.12f, 0.10f};
constexpr float kWire[3] = {0.10f, 0.12f, 0.20f};
constexpr float kPole[3] = {0.55f, 0.55f, 0.58f};
constexpr double kMinLineGap = 5.0;  // pixels between drawn wireframe lines

// gluLookAt: the view matrix, column-major.
void look_at(const Camera& camera) {
  const Vec3 f = (camera.target_m - camera.eye_m).normalized();
  const Vec3 s = f.cross(camera.up).normalized();
  const Vec3 u = s.cross(f);
  const double m[16] = {s.x(), u.x(), -f.x(), 0, s.y(), u.y(), -f.y(), 0,
                        s.z(), u.z(), -f.z(), 0, 0,     0,     0,      1};
  glMultMatrixd(m);
  glTranslated(-camera.eye_m.x(), -camera.eye_m.y(), -camera.eye_m.z());
}

void set_material(const float rgb[3]) {
  const float diffuse[4] = {rgb[0], rgb[1], rgb[2], 1.0f};
  const float ambient[4] = {0.35f * rgb[0], 0.35f * rgb[1], 0.35f * rgb[2], 1.0f};
  const float specular[4] = {0.08f, 0.08f, 0.08f, 1.0f};
  glMaterialfv(GL_FRONT_AND_BACK, GL_DIFFUSE, diffuse);
  glMaterialfv(GL_FRONT_AND_BACK, GL_AMBIENT, ambient);
  glMaterialfv(GL_FRONT_AND_BACK, GL_SPECULAR, specular);
  glMaterialf(GL_FRONT_AND_BACK, GL_SHININESS, 20.0f);
}

}  // namespace

std::optional<Style> parse_style(const std::string& name) {
  return value_in(kRenderStyleNames, name);
}

std::array<float, 3> ramp_color(double t) {
  // Five stops of matplotlib's viridis (perceptually uniform, readable in grey
  // and by most colour-blind viewers), linear between them.
  static constexpr float kStops[5][3] = {{0.267f, 0.005f, 0.329f},
                                         {0.231f, 0.322f, 0.546f},
                                         {0.128f, 0.567f, 0.551f},
                                         {0.369f, 0.789f, 0.383f},
                                         {0.993f, 0.906f, 0.144f}};
  const double x = std::clamp(std::isfinite(t) ? t : 0.0, 0.0, 1.0) * 4.0;
  const int i = std::min(int(x), 3);
  const float f = float(x - i);
  return {kStops[i][0] + f * (kStops[i + 1][0] - kStops[i][0]),
          kStops[i][1] + f * (kStops[i + 1][1] - kStops[i][1]),
          kStops[i][2] + f * (kStops[i + 1][2] - kStops[i][2])};
}

FrameRenderer::FrameRenderer(OffscreenContext& context, RenderOptions options)
    : context_(context), options_(std::move(options)) {
  context_.make_current();
  if (options_.style == Style::kTextured) {
    if (options_.texture.rgb.empty()) options_.texture = flag_pattern();
    GLuint id = 0;
    glGenTextures(1, &id);
    texture_id_ = id;
    glBindTexture(GL_TEXTURE_2D, id);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGB, options_.texture.width, options_.texture.height, 0,
                 GL_RGB, GL_UNSIGNED_BYTE, options_.texture.rgb.data());
  }
}

Image FrameRenderer::render(const FrameView& frame) {
  context_.make_current();
  const int w = context_.width(), h = context_.height();
  glViewport(0, 0, w, h);
  // Lines as wide in the image as without supersampling: one image pixel.
  glLineWidth(float(context_.samples()));
  glClearColor(kSky[0], kSky[1], kSky[2], 1.0f);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  glEnable(GL_DEPTH_TEST);

  glMatrixMode(GL_PROJECTION);
  glLoadIdentity();
  const double near = 0.05, far = 500.0;
  const double top =
      near * std::tan(0.5 * options_.camera.vertical_fov_deg * std::numbers::pi / 180);
  const double right = top * double(w) / double(h);
  glFrustum(-right, right, -top, top, near, far);
  glMatrixMode(GL_MODELVIEW);
  glLoadIdentity();
  look_at(options_.camera);

  // A light from over the viewer's left shoulder, fixed to the world.
  const Vec3 to_light =
      (options_.camera.eye_m - options_.camera.target_m).normalized() + Vec3(-0.4, 0.8, 0.0);
  const float light_dir[4] = {float(to_light.x()), float(to_light.y()), float(to_light.z()), 0.0f};
  const float white[4] = {0.85f, 0.85f, 0.85f, 1.0f};
  const float dim[4] = {0.35f, 0.35f, 0.35f, 1.0f};
  glLightfv(GL_LIGHT0, GL_POSITION, light_dir);
  glLightfv(GL_LIGHT0, GL_DIFFUSE, white);
  glLightfv(GL_LIGHT0, GL_SPECULAR, white);
  glLightModelfv(GL_LIGHT_MODEL_AMBIENT, dim);
  glLightModeli(GL_LIGHT_MODEL_TWO_SIDE, GL_TRUE);  // the back of the flag is lit too
  glEnable(GL_LIGHT0);
  glEnable(GL_NORMALIZE);
  glShadeModel(GL_SMOOTH);

  draw_backdrop();
  if (frame.pole_top_m) draw_pole(*frame.pole_top_m, frame.pole_radius_m);
  draw_cloth(frame);
  return context_.read_rgb();
}

void FrameRenderer::draw_backdrop() const {
  // Ground: a large plane at ground height with lines every metre, unlit.
  glDisable(GL_LIGHTING);
  const double y = options_.ground_y_m, extent = 100.0;
  const Vec3 centre = options_.camera.target_m;
  glColor3fv(kGround);
  glBegin(GL_QUADS);
  glVertex3d(centre.x() - extent, y, centre.z() - extent);
  glVertex3d(centre.x() - extent, y, centre.z() + extent);
  glVertex3d(centre.x() + extent, y, centre.z() + extent);
  glVertex3d(centre.x() + extent, y, centre.z() - extent);
  glEnd();
  glEnable(GL_POLYGON_OFFSET_LINE);
  glPolygonOffset(-1.0f, -1.0f);
  glColor3fv(kGroundLine);
  glBegin(GL_LINES);
  const double x0 = std::floor(centre.x()) - 20, z0 = std::floor(centre.z()) - 20;
  for (int i = 0; i <= 40; ++i) {
    glVertex3d(x0 + i, y + 1e-3, z0);
    glVertex3d(x0 + i, y + 1e-3, z0 + 40);
    glVertex3d(x0, y + 1e-3, z0 + i);
    glVertex3d(x0 + 40, y + 1e-3, z0 + i);
  }
  glEnd();
  glDisable(GL_POLYGON_OFFSET_LINE);
}

void FrameRenderer::draw_pole(const Vec3& top, double radius) const {
  const double bottom = options_.ground_y_m;
  glEnable(GL_LIGHTING);
  set_material(kPole);
  glBegin(GL_QUAD_STRIP);
  for (int i = 0; i <= 16; ++i) {
    const double a = 2.0 * std::numbers::pi * i / 16;
    const double c = std::cos(a), s = std::sin(a);
    glNormal3d(c, 0.0, s);
    glVertex3d(top.x() - radius + radius * c, bottom, top.z() + radius * s);
    glVertex3d(top.x() - radius + radius * c, top.y() + 0.05, top.z() + radius * s);
  }
  glEnd();
  // Its top closed: a solid pole, not a tube, seen from above.
  glBegin(GL_TRIANGLE_FAN);
  glNormal3d(0.0, 1.0, 0.0);
  glVertex3d(top.x() - radius, top.y() + 0.05, top.z());
  for (int i = 16; i >= 0; --i) {
    const double a = 2.0 * std::numbers::pi * i / 16;
    glVertex3d(top.x() - radius + radius * std::cos(a), top.y() + 0.05,
               top.z() + radius * std::sin(a));
  }
  glEnd();
}

int FrameRenderer::wire_step(const FrameView& frame) const {
  // Mean on-screen length of a link along the middle row and column, pixels.
  const Camera& camera = options_.camera;
  const Vec3 f = (camera.target_m - camera.eye_m).normalized();
  const Vec3 s = f.cross(camera.up).normalized();
  const Vec3 u = s.cross(f);
  const double focal = 0.5 * context_.height() /
                       context_.samples() /  // image pixels, not drawn ones
                       std::tan(0.5 * camera.vertical_fov_deg * std::numbers::pi / 180);
  auto screen = [&](const Vec3& p) {
    const Vec3 d = p - camera.eye_m;
    const double depth = std::max(d.dot(f), 1e-6);
    return Eigen::Vector2d(focal * d.dot(s) / depth, focal * d.dot(u) / depth);
  };
  const int rows = frame.rows, cols = frame.cols;
  const NodeView x(rows, cols, frame.positions_m);
  const auto at = [&](int j, int k) -> const Vec3& { return x.at(j, k); };
  double length = 0.0;
  int links = 0;
  for (int k = 0; k + 1 < cols; ++k, ++links)
    length += (screen(at(rows / 2, k + 1)) - screen(at(rows / 2, k))).norm();
  for (int j = 0; j + 1 < rows; ++j, ++links)
    length += (screen(at(j + 1, cols / 2)) - screen(at(j, cols / 2))).norm();
  const double per_link = links ? length / links : kMinLineGap;
  return std::max(1, int(std::ceil(kMinLineGap / std::max(per_link, 1e-9))));
}

void FrameRenderer::draw_cloth(const FrameView& frame) {
  const int rows = frame.rows, cols = frame.cols;
  const std::span<const Vec3> x = frame.positions_m;
  const NodeView nodes(rows, cols, x);
  const auto at = [&](int j, int k) -> const Vec3& { return nodes.at(j, k); };
  std::vector<GLuint> indices;
  if (options_.style == Style::kWireframe) {
    glDisable(GL_LIGHTING);
    glColor3fv(kWire);
    // Every lattice line while they are at least kMinLineGap pixels apart on
    // screen; on a lattice finer than that, every n-th line (and the border):
    // a solid blob of lines shows nothing.
    const int step = wire_step(frame);
    auto drawn = [&](int i, int n) { return i % step == 0 || i == n - 1; };
    for (int j = 0; j < rows; ++j)
      for (int k = 0; k < cols; ++k) {
        const GLuint a = GLuint(j * cols + k);
        if (drawn(j, rows) && k + 1 < cols) indices.insert(indices.end(), {a, a + 1});
        if (drawn(k, cols) && j + 1 < rows) indices.insert(indices.end(), {a, a + GLuint(cols)});
      }
    glEnableClientState(GL_VERTEX_ARRAY);
    glVertexPointer(3, GL_DOUBLE, sizeof(Vec3), x.data());
    glDrawElements(GL_LINES, GLsizei(indices.size()), GL_UNSIGNED_INT, indices.data());
    glDisableClientState(GL_VERTEX_ARRAY);
    return;
  }
  // Smooth normals: central differences across the lattice (one-sided at the
  // border). Positions and normals go to GL as float: the rasterizer's own
  // type, so it converts nothing per vertex.
  vertices_.resize(3 * x.size());
  normals_.resize(3 * x.size());
  for (int j = 0; j < rows; ++j)
    for (int k = 0; k < cols; ++k) {
      const Vec3 along = at(j, std::min(k + 1, cols - 1)) - at(j, std::max(k - 1, 0));
      const Vec3 down = at(std::min(j + 1, rows - 1), k) - at(std::max(j - 1, 0), k);
      const Vec3 n = down.cross(along).normalized();
      const std::size_t i = 3 * (std::size_t(j) * cols + std::size_t(k));
      for (int c = 0; c < 3; ++c) {
        vertices_[i + std::size_t(c)] = float(at(j, k)[c]);
        normals_[i + std::size_t(c)] = float(n[c]);
      }
    }
  if (triangle_rows_ != rows || triangle_cols_ != cols) {  // the mesh, once per lattice shape
    triangles_.clear();
    for (int j = 0; j + 1 < rows; ++j)
      for (int k = 0; k + 1 < cols; ++k) {
        const GLuint a = GLuint(j * cols + k), b = a + 1, c = a + GLuint(cols), d = c + 1;
        triangles_.insert(triangles_.end(), {a, c, b, b, c, d});
      }
    triangle_rows_ = rows;
    triangle_cols_ = cols;
  }
  std::vector<float> uv;
  glEnable(GL_LIGHTING);
  if (options_.style == Style::kTextured) {
    const float white[3] = {1.0f, 1.0f, 1.0f};
    set_material(white);
    uv.reserve(x.size() * 2);
    for (int j = 0; j < rows; ++j)
      for (int k = 0; k < cols; ++k) {
        uv.push_back(float(k) / float(cols - 1));
        uv.push_back(float(j) / float(rows - 1));
      }
    glEnable(GL_TEXTURE_2D);
    glBindTexture(GL_TEXTURE_2D, texture_id_);
    glTexEnvi(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, GL_MODULATE);
    glEnableClientState(GL_TEXTURE_COORD_ARRAY);
    glTexCoordPointer(2, GL_FLOAT, 0, uv.data());
  } else {
    set_material(kCloth);
  }
  const bool colored = options_.color && frame.field.size() == x.size();
  if (colored) {
    // The field's colour as the material's ambient and diffuse, lit as the cloth is.
    const ColorScale& scale = *options_.color;
    const double span = scale.high > scale.low ? scale.high - scale.low : 1.0;
    colors_.resize(3 * x.size());
    for (std::size_t i = 0; i < x.size(); ++i) {
      const std::array<float, 3> c = ramp_color((frame.field[i] - scale.low) / span);
      for (int k = 0; k < 3; ++k) colors_[3 * i + std::size_t(k)] = c[std::size_t(k)];
    }
    glColorMaterial(GL_FRONT_AND_BACK, GL_AMBIENT_AND_DIFFUSE);
    glEnable(GL_COLOR_MATERIAL);
    glEnableClientState(GL_COLOR_ARRAY);
    glColorPointer(3, GL_FLOAT, 0, colors_.data());
  }
  glEnableClientState(GL_VERTEX_ARRAY);
  glEnableClientState(GL_NORMAL_ARRAY);
  glVertexPointer(3, GL_FLOAT, 0, vertices_.data());
  glNormalPointer(GL_FLOAT, 0, normals_.data());
  glDrawElements(GL_TRIANGLES, GLsizei(triangles_.size()), GL_UNSIGNED_INT, triangles_.data());
  glDisableClientState(GL_NORMAL_ARRAY);
  glDisableClientState(GL_VERTEX_ARRAY);
  if (colored) {
    glDisableClientState(GL_COLOR_ARRAY);
    glDisable(GL_COLOR_MATERIAL);
  }
  if (options_.style == Style::kTextured) {
    glDisableClientState(GL_TEXTURE_COORD_ARRAY);
    glDisable(GL_TEXTURE_2D);
  }
}

}  // namespace flagsim::render
