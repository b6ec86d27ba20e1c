#include "flagsim/data/mesh_export.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <vector>

#include "flagsim/core/errors.hpp"
#include "flagsim/core/lattice.hpp"

namespace flagsim::data {
namespace {

static_assert(std::endian::native == std::endian::little,
              "PC2 is little-endian; this writer copies the host's bytes");

template <typename T>
void put(std::vector<char>& bytes, T value) {
  const std::size_t at = bytes.size();
  bytes.resize(at + sizeof value);
  std::memcpy(bytes.data() + at, &value, sizeof value);
}

}  // namespace

Pc2Writer::Pc2Writer(std::string path, int points, int samples, float start_frame,
                     float sample_rate)
    : path_(std::move(path)), points_(points), samples_(samples) {
  file_ = std::fopen(path_.c_str(), "wb");
  if (!file_) throw IoError(fmt::format("{}: cannot create the point cache", path_));
  std::vector<char> header(kPc2Signature, kPc2Signature + sizeof kPc2Signature);
  put<std::int32_t>(header, 1);
  put<std::int32_t>(header, points);
  put<float>(header, start_frame);
  put<float>(header, sample_rate);
  put<std::int32_t>(header, samples);
  if (std::fwrite(header.data(), 1, header.size(), file_) != kPc2HeaderBytes)
    throw IoError(fmt::format("{}: writing the point cache failed (disk full?)", path_));
}

Pc2Writer::~Pc2Writer() {
  if (file_) std::fclose(file_);
}

void Pc2Writer::write_sample(std::span<const Vec3> positions_m) {
  if (int(positions_m.size()) != points_ || written_ >= samples_)
    throw IoError(fmt::format("{}: sample {} of {} points, the header says {} of {}", path_,
                              written_, positions_m.size(), samples_, points_));
  std::vector<float> xyz(3 * positions_m.size());
  for (std::size_t i = 0; i < positions_m.size(); ++i)
    for (int c = 0; c < 3; ++c) xyz[3 * i + std::size_t(c)] = float(positions_m[i][c]);
  if (std::fwrite(xyz.data(), sizeof(float), xyz.size(), file_) != xyz.size())
    throw IoError(fmt::format("{}: writing the point cache failed (disk full?)", path_));
  ++written_;
}

void Pc2Writer::finish() {
  const bool flushed = std::fflush(file_) == 0;
  const bool closed = std::fclose(file_) == 0;
  file_ = nullptr;
  if (!flushed || !closed)
    throw IoError(fmt::format("{}: writing the point cache failed (disk full?)", path_));
  if (written_ != samples_)
    throw IoError(
        fmt::format("{}: {} samples written, the header says {}", path_, written_, samples_));
}

std::string obj_text(int rows, int cols, std::span<const Vec3> positions_m,
                     const std::string& comment) {
  const NodeView nodes(rows, cols, positions_m);
  const auto at = [&](int j, int k) -> const Vec3& { return nodes.at(j, k); };
  fmt::memory_buffer out;
  fmt::format_to(std::back_inserter(out), "# {}\n# {} x {} nodes, m, y up\no flag\n", comment, rows,
                 cols);
  // float32 values printed with 9 significant digits read back as the same float32.
  for (int j = 0; j < rows; ++j)
    for (int k = 0; k < cols; ++k) {
      const Vec3 p = at(j, k).cast<float>().cast<double>();
      fmt::format_to(std::back_inserter(out), "v {:.9g} {:.9g} {:.9g}\n", float(p.x()),
                     float(p.y()), float(p.z()));
    }
  for (int j = 0; j < rows; ++j)
    for (int k = 0; k < cols; ++k)
      fmt::format_to(std::back_inserter(out), "vt {:.9g} {:.9g}\n",
                     cols > 1 ? double(k) / (cols - 1) : 0.0,
                     rows > 1 ? 1.0 - double(j) / (rows - 1) : 1.0);
  // Normal: down the column (j + 1) cross along the row (k + 1), one-sided at
  // the edges; at rest (rows going down -y, columns along +x) it is +z.
  for (int j = 0; j < rows; ++j)
    for (int k = 0; k < cols; ++k) {
      const Vec3 down = at(std::min(j + 1, rows - 1), k) - at(std::max(j - 1, 0), k);
      const Vec3 along = at(j, std::min(k + 1, cols - 1)) - at(j, std::max(k - 1, 0));
      Vec3 n = down.cross(along);
      const double length = n.norm();
      n = length > 0.0 && std::isfinite(length) ? Vec3(n / length) : Vec3(0.0, 0.0, 1.0);
      n += Vec3::Zero();  // -0 + 0 = +0: no "-0.000000" in the file
      fmt::format_to(std::back_inserter(out), "vn {:.6f} {:.6f} {:.6f}\n", n.x(), n.y(), n.z());
    }
  // Quads (j, k), (j + 1, k), (j + 1, k + 1), (j, k + 1): counter-clockwise about the normal.
  for (int j = 0; j + 1 < rows; ++j)
    for (int k = 0; k + 1 < cols; ++k) {
      const long a = long(j) * cols + k + 1, b = a + cols;
      fmt::format_to(std::back_inserter(out), "f {0}/{0}/{0} {1}/{1}/{1} {2}/{2}/{2} {3}/{3}/{3}\n",
                     a, b, b + 1, a + 1);
    }
  return fmt::to_string(out);
}

}  // namespace flagsim::data
