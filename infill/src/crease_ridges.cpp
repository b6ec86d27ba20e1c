#include "flagsim/infill/crease_ridges.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace flagsim::infill {
namespace {

// A coarse triple with less rest angle than this holds no crease, rad.
constexpr double kLeastCrease = 1e-3;
// A ridge is laid out to this many decay lengths from its line (e^-8: 3e-4 of its height).
constexpr double kRidgeReach = 8.0;
// The sharpest ridge, rad: slopes of 11.5 degrees either side, 23 degrees of
// turning on the line (the cloth's median is about 1). A crease hidden more than
// this is a fold the coarse cloth is about to show (a folded flag hoisted
// has its creases flat at t = 0; they pop out within tenths of a second), and
// steeper ridges made the projection work longer for nothing more to see.
constexpr double kMostKink = 0.4;

}  // namespace

CreaseRidges::CreaseRidges(const Lattice& fine, const CellGrid& grid,
                           const CreaseRidgeParams& params)
    : fine_(fine),
      grid_(grid),
      params_(params),
      offsets_(fine.node_count(), 0.0),
      row_ridges_(std::size_t(grid.coarse_rows)),
      col_ridges_(std::size_t(grid.coarse_cols)) {}

void CreaseRidges::set_rest(std::span<const double> coarse_rest_rad) {
  const std::size_t triples =
      std::size_t(grid_.coarse_rows) * std::size_t(std::max(0, grid_.coarse_cols - 2)) +
      std::size_t(std::max(0, grid_.coarse_rows - 2)) * std::size_t(grid_.coarse_cols);
  assert(coarse_rest_rad.size() >= triples);
  rest_.assign(coarse_rest_rad.begin(), coarse_rest_rad.begin() + std::ptrdiff_t(triples));
}

bool CreaseRidges::any() const {
  return std::any_of(rest_.begin(), rest_.end(),
                     [](double angle) { return std::abs(angle) > kLeastCrease; });
}

void CreaseRidges::find_ridges(std::span<const Vec3> coarse_m, bool rows, int fiber,
                               std::vector<Ridge>& out) const {
  out.clear();
  const int Jc = grid_.coarse_rows, Kc = grid_.coarse_cols;
  const int nodes = rows ? Kc : Jc;
  const int across = rows ? Jc : Kc;
  if (rest_.empty() || nodes < 3) return;
  const std::size_t row_triples = std::size_t(Jc) * std::size_t(Kc - 2);
  // Rest angle of the triple centred at node i of this fiber, and the node's position.
  const auto rest = [&](int i) {
    return rows ? rest_[std::size_t(fiber) * std::size_t(Kc - 2) + std::size_t(i - 1)]
                : rest_[row_triples + std::size_t(i - 1) * std::size_t(Kc) + std::size_t(fiber)];
  };
  // Node i of the fiber `f` of this family (f = fiber: this one).
  const auto node_of = [&](int f, int i) -> const Vec3& {
    return coarse_m[rows ? grid_.coarse_index(f, i) : grid_.coarse_index(i, f)];
  };
  const auto node = [&](int i) -> const Vec3& { return node_of(fiber, i); };
  // Dense and coarse rest spacings along the fiber, m.
  const double dense_link = rows ? fine_.spacing_x_m : fine_.spacing_y_m;
  const double spacing = dense_link * (rows ? grid_.col_stride : grid_.row_stride);
  for (int first = 1; first + 1 < nodes; ++first) {
    if (!(std::abs(rest(first)) > kLeastCrease)) continue;
    // A run of creased triples on one side is one crease line.
    const double side = std::copysign(1.0, rest(first));
    int last = first;
    while (last + 2 < nodes && side * rest(last + 1) > kLeastCrease) ++last;
    double angle = 0.0, weight = 0.0, moment = 0.0;
    for (int i = first; i <= last; ++i) {
      angle += rest(i);
      weight += std::abs(rest(i));
      moment += std::abs(rest(i)) * i;
    }
    const double place = moment / weight;
    // What the coarse cloth shows of it: its signed turning across the run
    // about the fold axis (the cross fiber's chord at the node nearest the
    // line; creased_bending.hpp's angle, with its sign).
    const int at = std::clamp(int(std::lround(place)), first, last);
    const Vec3 axis =
        rows ? node_of(std::max(0, fiber - 1), at) - node_of(std::min(across - 1, fiber + 1), at)
             : node_of(std::min(across - 1, fiber + 1), at) - node_of(std::max(0, fiber - 1), at);
    const Vec3 in = node(first) - node(first - 1), out_link = node(last + 1) - node(last);
    const double axis_length = axis.norm();
    const Vec3 tau = axis_length > 0.0 ? Vec3(axis / axis_length) : Vec3::Zero();
    const double shown =
        std::atan2(in.cross(out_link).dot(tau), in.dot(out_link) - in.dot(tau) * out_link.dot(tau));
    // The tension along the fiber there: Y times the mean strain of its links.
    double length = 0.0;
    for (int i = first - 1; i <= last; ++i) length += (node(i + 1) - node(i)).norm();
    const double strain = length / ((last - first + 2) * spacing) - 1.0;
    const double tension = params_.stretch_modulus_n_m * std::max(strain, 0.0);
    double decay = dense_link;
    if (tension > 0.0) decay = std::min(decay, std::sqrt(params_.rigidity_j / tension));
    const double kink = std::min(
        kMostKink, std::max(0.0, side * (angle - shown)) / (1.0 + params_.width_m / (2.0 * decay)));
    const double sharpen = std::clamp(2.0 * shown / angle - 1.0, 0.0, 1.0);
    // A fold toward the front (a valley seen from it) puts its line behind
    // its sides: the ridge stands on the back, against the normal.
    if (kink > 0.0 || sharpen > 0.0)
      out.push_back({place, -side * 0.5 * kink * decay, decay, sharpen});
    first = last;
  }
}

namespace {

// Half the zone a crease's shown turning is gathered from, in coarse cells:
// the smooth surface rounds a coarse node's turning over the cells either side
// of it, and a fold shared by two nodes over one cell more.
constexpr double kSharpenedCells = 1.5;
// Least turning across a crease's zone worth sharpening, rad.
constexpr double kLeastShownTurning = 0.02;

// Adds to `offsets` (weighted) the normal offsets that replace `surface` over
// [place - half, place + half] along one fiber (nodes `node(i)`, i = 0..count-1)
// by its two tangents at the zone's ends: each node goes to the nearer of the
// two lines, its foot there, so the fiber turns where they meet. Where that is
// comes from the coarse cloth's turning, which the physics puts in the crease's
// shares either side of its line (fold_rest_angles): on the line.
template <typename Node>
void sharpen(const Node& node, int count, double place, double half, double weight,
             std::span<const Vec3> surface, std::span<const Vec3> normals,
             std::vector<double>& offsets) {
  const int a = std::max(0, int(std::floor(place - half)));
  const int b = std::min(count - 1, int(std::ceil(place + half)));
  if (b - a < 3) return;
  const Vec3& sa = surface[node(a)];
  const Vec3& sb = surface[node(b)];
  const Vec3 ta = (surface[node(a + 1)] - sa).normalized();
  const Vec3 tb = (sb - surface[node(b - 1)]).normalized();
  if (std::atan2(ta.cross(tb).norm(), ta.dot(tb)) < kLeastShownTurning) return;
  // The tangent lines sa + t ta and sb - u tb: their nearest points.
  const Vec3 d = -tb, r = sa - sb;
  const double bb = ta.dot(d), dd = ta.dot(r), ee = d.dot(r), det = 1.0 - bb * bb;
  if (!(det > 1e-12)) return;
  const double t = (bb * ee - dd) / det, u = (ee - bb * dd) / det;
  const double reach = (sb - sa).norm();
  if (!(t > 0.0 && u > 0.0 && t < reach && u < reach)) return;  // tangents that do not meet ahead
  const Vec3 apex = 0.5 * ((sa + t * ta) + (sb + u * d));
  for (int i = a + 1; i < b; ++i) {
    const std::size_t n = node(i);
    const Vec3& p = surface[n];
    const Vec3 foot =
        (p - apex).dot(ta) <= 0.0 ? sa + (p - sa).dot(ta) * ta : sb + (p - sb).dot(tb) * tb;
    offsets[n] += weight * (foot - p).dot(normals[n]);
  }
}

}  // namespace

void CreaseRidges::add_family(bool rows, std::span<const Vec3> surface_m,
                              std::span<const Vec3> normals) {
  // Rows' ridges lie across k, interpolated in j between coarse rows; columns' the other way.
  const int J = fine_.rows, K = fine_.cols;
  const int across_count = rows ? J : K;  // dense fibers of the family
  const int stride_across = rows ? grid_.row_stride : grid_.col_stride;
  const int stride_along = rows ? grid_.col_stride : grid_.row_stride;
  const int along_count = rows ? K : J;
  const double link_m = rows ? fine_.spacing_x_m : fine_.spacing_y_m;
  const std::vector<std::vector<Ridge>>& ridges = rows ? row_ridges_ : col_ridges_;
  const int coarse_fibers = int(ridges.size());
  for (int f = 0; f < across_count; ++f) {
    const auto node = [&](int i) { return rows ? fine_.index(f, i) : fine_.index(i, f); };
    const int below = std::min(f / stride_across, coarse_fibers - 1);
    const double t = double(f - below * stride_across) / stride_across;
    for (const int c : {below, below + 1}) {
      const double weight = c == below ? 1.0 - t : t;
      if (weight <= 0.0 || c >= coarse_fibers) continue;
      for (const Ridge& ridge : ridges[std::size_t(c)]) {
        const double place = ridge.place * stride_along;  // dense index along the fiber
        if (ridge.sharpen > 0.0)
          sharpen(node, along_count, place, kSharpenedCells * stride_along, weight * ridge.sharpen,
                  surface_m, normals, offsets_);
        if (ridge.height_m == 0.0) continue;
        const double reach = kRidgeReach * ridge.decay_m / link_m;
        const int from = std::max(0, int(std::ceil(place - reach)));
        const int to = std::min(along_count - 1, int(std::floor(place + reach)));
        for (int i = from; i <= to; ++i) {
          offsets_[node(i)] +=
              weight * ridge.height_m * std::exp(-std::abs(i - place) * link_m / ridge.decay_m);
        }
      }
    }
  }
}

const std::vector<double>& CreaseRidges::offsets(std::span<const Vec3> coarse_m,
                                                 std::span<const Vec3> surface_m,
                                                 std::span<const Vec3> normals) {
  std::fill(offsets_.begin(), offsets_.end(), 0.0);
  for (int jc = 0; jc < grid_.coarse_rows; ++jc)
    find_ridges(coarse_m, true, jc, row_ridges_[std::size_t(jc)]);
  for (int kc = 0; kc < grid_.coarse_cols; ++kc)
    find_ridges(coarse_m, false, kc, col_ridges_[std::size_t(kc)]);
  add_family(true, surface_m, normals);
  add_family(false, surface_m, normals);
  return offsets_;
}

void add_dense_ridges(CreaseRidges& ridges, const Lattice& fine, std::span<Vec3> positions_m,
                      std::span<const std::uint8_t> held, std::vector<Vec3>& normals,
                      std::vector<Vec3>& copy) {
  copy.assign(positions_m.begin(), positions_m.end());
  normals.resize(copy.size());
  const NodeView at(fine, std::span<const Vec3>(copy));
  for (int j = 0; j < fine.rows; ++j)
    for (int k = 0; k < fine.cols; ++k) {
      const Vec3 along_row = at.clamped(j, k + 1) - at.clamped(j, k - 1);
      const Vec3 along_col = at.clamped(j + 1, k) - at.clamped(j - 1, k);
      normals[fine.index(j, k)] = along_row.cross(along_col).normalized();
    }
  const std::vector<double>& offsets = ridges.offsets(copy, copy, normals);
  for (std::size_t i = 0; i < positions_m.size(); ++i)
    if (held.empty() || !held[i]) positions_m[i] += offsets[i] * normals[i];
}

}  // namespace flagsim::infill
