#pragma once
// The dense lattice of the cloth (paper 2.1): J rows by K columns of nodes.
//
// Topology only depends on (rows, cols); geometry is the rest state. Node (j, k)
// rests at origin + (k * spacing_x, -j * spacing_y, 0) (contract: "Lattice and
// coordinates"): row 0 is the top edge, column 0 the pole edge, the flag rests
// in the z = 0 plane. Per-node data is stored row-major in one flat array,
// index(j, k) = j * cols + k.
#include <algorithm>
#include <array>
#include <cassert>
#include <cstddef>
#include <span>
#include <vector>

#include "flagsim/core/vec3.hpp"

namespace flagsim {

struct Lattice {
  int rows = 0;                  ///< J, >= 2
  int cols = 0;                  ///< K, >= 2
  double spacing_x_m = 0.0;      ///< rest distance between neighbours along a row, m
  double spacing_y_m = 0.0;      ///< rest distance between neighbours along a column, m
  Vec3 origin_m = Vec3::Zero();  ///< rest position of node (0, 0), m

  /// Lattice of a w x h m rectangle with J x K nodes (both >= 2).
  static Lattice rectangle(int rows, int cols, double width_m, double height_m,
                           const Vec3& origin_m);

  std::size_t node_count() const { return static_cast<std::size_t>(rows) * cols; }
  std::size_t index(int j, int k) const { return static_cast<std::size_t>(j) * cols + k; }
  Vec3 rest_position(int j, int k) const {
    return origin_m + Vec3(k * spacing_x_m, -j * spacing_y_m, 0.0);
  }
  /// All rest positions, row-major [J*K].
  std::vector<Vec3> rest_positions() const;

  /// Indices of the four corners, in the contract's order:
  /// (0,0), (0,K-1), (J-1,0), (J-1,K-1).
  std::array<std::size_t, 4> corners() const;
};

/// Per-node data of a lattice, [J*K] row-major, read by (row, column): a view,
/// it owns nothing. NodeView<const Vec3> reads a frame, NodeView<Vec3> writes one.
template <class T>
class NodeView {
 public:
  NodeView(const Lattice& lattice, std::span<T> nodes)
      : NodeView(lattice.rows, lattice.cols, nodes) {}
  /// A frame read without its Lattice (a file's, a renderer's): `rows` x `cols` nodes.
  NodeView(int rows, int cols, std::span<T> nodes) : rows_(rows), cols_(cols), nodes_(nodes) {
    assert(rows >= 0 && cols >= 0 && nodes.size() == std::size_t(rows) * std::size_t(cols));
  }
  /// Node (j, k): row j (0 the top edge), column k (0 the pole edge).
  T& at(int j, int k) const {
    assert(j >= 0 && j < rows_ && k >= 0 && k < cols_);
    return nodes_[std::size_t(j) * std::size_t(cols_) + std::size_t(k)];
  }
  /// Node (j, k) with j and k clamped into the lattice (an edge repeats itself).
  T& clamped(int j, int k) const {
    return at(std::clamp(j, 0, rows_ - 1), std::clamp(k, 0, cols_ - 1));
  }
  int rows() const { return rows_; }
  int cols() const { return cols_; }

 private:
  int rows_ = 0, cols_ = 0;
  std::span<T> nodes_;
};
template <class T>
NodeView(const Lattice&, std::span<T>) -> NodeView<T>;
template <class T>
NodeView(const Lattice&, std::vector<T>&) -> NodeView<T>;
template <class T>
NodeView(const Lattice&, const std::vector<T>&) -> NodeView<const T>;
template <class T>
NodeView(int, int, std::span<T>) -> NodeView<T>;
template <class T>
NodeView(int, int, std::vector<T>&) -> NodeView<T>;
template <class T>
NodeView(int, int, const std::vector<T>&) -> NodeView<const T>;

/// One link between neighbour nodes: flat indices a, b (b the right or lower
/// neighbour), its rest length, m, and where a LinkField keeps its value.
struct Link {
  std::size_t a = 0, b = 0;
  double rest_m = 0.0;
  bool along_row = true;  ///< a row link (j, k)-(j, k + 1); else a column link (j, k)-(j + 1, k)
  std::size_t slot = 0;   ///< its index in its family's array (LinkField)
};

/// A value per link, in the lattice's two link families, each row-major: row
/// links [J x (K-1)], (j, k)-(j, k + 1) at row(j, k); column links [(J-1) x K],
/// (j, k)-(j + 1, k) at col(j, k). Indexed by a Link from for_each_link too.
template <class T>
class LinkField {
 public:
  LinkField() = default;
  explicit LinkField(const Lattice& lattice, const T& value = T{})
      : cols_(std::size_t(lattice.cols)),
        rows_(std::size_t(lattice.rows) * std::size_t(lattice.cols - 1), value),
        columns_(std::size_t(lattice.rows - 1) * std::size_t(lattice.cols), value) {}

  T& row(int j, int k) { return rows_[std::size_t(j) * (cols_ - 1) + std::size_t(k)]; }
  const T& row(int j, int k) const { return rows_[std::size_t(j) * (cols_ - 1) + std::size_t(k)]; }
  T& col(int j, int k) { return columns_[std::size_t(j) * cols_ + std::size_t(k)]; }
  const T& col(int j, int k) const { return columns_[std::size_t(j) * cols_ + std::size_t(k)]; }
  T& operator[](const Link& link) {
    return link.along_row ? rows_[link.slot] : columns_[link.slot];
  }
  const T& operator[](const Link& link) const {
    return link.along_row ? rows_[link.slot] : columns_[link.slot];
  }
  /// Each family's whole array, row-major.
  std::span<T> rows() { return rows_; }
  std::span<const T> rows() const { return rows_; }
  std::span<T> cols() { return columns_; }
  std::span<const T> cols() const { return columns_; }
  void fill(const T& value) {
    std::fill(rows_.begin(), rows_.end(), value);
    std::fill(columns_.begin(), columns_.end(), value);
  }

 private:
  std::size_t cols_ = 0;  ///< K
  std::vector<T> rows_, columns_;
};

/// Calls visit(link) for every link of the lattice, node by node in row-major
/// order: node (j, k)'s row link to (j, k + 1) (rest spacing_x), then its
/// column link to (j + 1, k) (rest spacing_y). The project's one link order:
/// the Gauss-Seidel passes that go through it depend on it.
template <class Visit>
void for_each_link(const Lattice& lattice, Visit&& visit) {
  const std::size_t stride = std::size_t(lattice.cols);
  std::size_t row_slot = 0;
  for (int j = 0; j < lattice.rows; ++j)
    for (int k = 0; k < lattice.cols; ++k) {
      const std::size_t a = lattice.index(j, k);
      if (k + 1 < lattice.cols) visit(Link{a, a + 1, lattice.spacing_x_m, true, row_slot++});
      // Column link (j, k) sits at j K + k: the index of its upper node.
      if (j + 1 < lattice.rows) visit(Link{a, a + stride, lattice.spacing_y_m, false, a});
    }
}

}  // namespace flagsim
