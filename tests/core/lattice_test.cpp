#include "flagsim/core/lattice.hpp"

#include <gtest/gtest.h>

#include <set>
#include <span>
#include <type_traits>
#include <utility>
#include <vector>

namespace flagsim {
namespace {

TEST(Lattice, RestPositionsFollowTheContract) {
  const Lattice lattice = Lattice::rectangle(3, 5, 2.0, 1.0, Vec3(0.0, 2.0, 0.0));
  EXPECT_DOUBLE_EQ(lattice.spacing_x_m, 0.5);
  EXPECT_DOUBLE_EQ(lattice.spacing_y_m, 0.5);
  // Row 0 is the top edge, +x from the pole to the fly end, z = 0.
  EXPECT_EQ(lattice.rest_position(0, 0), Vec3(0.0, 2.0, 0.0));
  EXPECT_EQ(lattice.rest_position(0, 4), Vec3(2.0, 2.0, 0.0));
  EXPECT_EQ(lattice.rest_position(2, 0), Vec3(0.0, 1.0, 0.0));
  const auto positions = lattice.rest_positions();
  ASSERT_EQ(positions.size(), 15u);
  EXPECT_EQ(positions[lattice.index(1, 3)], Vec3(1.5, 1.5, 0.0));
}

TEST(Lattice, CornersInContractOrder) {
  const Lattice lattice = Lattice::rectangle(4, 6, 1.0, 1.0, Vec3::Zero());
  const auto corners = lattice.corners();
  EXPECT_EQ(corners[0], lattice.index(0, 0));
  EXPECT_EQ(corners[1], lattice.index(0, 5));
  EXPECT_EQ(corners[2], lattice.index(3, 0));
  EXPECT_EQ(corners[3], lattice.index(3, 5));
}

TEST(Lattice, EveryLinkOnceInRowMajorOrderWithItsRestLength) {
  // 3 x 4 nodes: 3 x 3 row links (rest 1/3 m) and 2 x 4 column links (rest 1 m).
  const Lattice lattice = Lattice::rectangle(3, 4, 1.0, 2.0, Vec3::Zero());
  std::vector<Link> links;
  for_each_link(lattice, [&](const Link& link) { links.push_back(link); });
  ASSERT_EQ(links.size(), 17u);
  std::set<std::pair<std::size_t, std::size_t>> seen;
  std::size_t last_a = 0;
  for (const Link& link : links) {
    EXPECT_TRUE(seen.emplace(link.a, link.b).second) << link.a << "-" << link.b;
    EXPECT_GE(link.a, last_a);  // node by node
    last_a = link.a;
    if (link.b == link.a + 1) {
      EXPECT_NE(link.b % 4, 0u) << "a row link does not wrap to the next row";
      EXPECT_DOUBLE_EQ(link.rest_m, lattice.spacing_x_m);
    } else {
      EXPECT_EQ(link.b, link.a + 4);
      EXPECT_DOUBLE_EQ(link.rest_m, lattice.spacing_y_m);
    }
  }
  // Node (0, 0): its row link, then its column link.
  EXPECT_EQ(links[0].b, lattice.index(0, 1));
  EXPECT_EQ(links[1].b, lattice.index(1, 0));
  // The last node with a link is (2, 2), to (2, 3).
  EXPECT_EQ(links.back().a, lattice.index(2, 2));
  EXPECT_EQ(links.back().b, lattice.index(2, 3));
}

TEST(Lattice, ALinkFieldHoldsOneValueForEveryLinkWhereItsLinkSays) {
  const Lattice lattice = Lattice::rectangle(3, 4, 1.0, 2.0, Vec3::Zero());
  LinkField<int> field(lattice, -1);
  EXPECT_EQ(field.rows().size(), 9u);  // 3 x 3 row links
  EXPECT_EQ(field.cols().size(), 8u);  // 2 x 4 column links
  int n = 0;
  for_each_link(lattice, [&](const Link& link) { field[link] = n++; });
  for (int value : field.rows()) EXPECT_GE(value, 0);  // every slot written once
  for (int value : field.cols()) EXPECT_GE(value, 0);
  // (j, k)'s row link and column link, in the visiting order.
  for (int j = 0; j < 3; ++j)
    for (int k = 0; k < 4; ++k) {
      std::vector<int> mine;
      for_each_link(lattice, [&](const Link& link) {
        if (link.a == lattice.index(j, k)) mine.push_back(field[link]);
      });
      std::size_t i = 0;
      if (k + 1 < 4) {
        EXPECT_EQ(field.row(j, k), mine.at(i++)) << j << "," << k;
      }
      if (j + 1 < 3) {
        EXPECT_EQ(field.col(j, k), mine.at(i++)) << j << "," << k;
      }
      EXPECT_EQ(i, mine.size());
    }
}

TEST(Lattice, ANodeViewReadsAndWritesNode_j_k_WhereTheFlatIndexKeepsIt) {
  const Lattice lattice = Lattice::rectangle(3, 4, 1.0, 2.0, Vec3::Zero());
  std::vector<Vec3> nodes = lattice.rest_positions();
  const NodeView<const Vec3> read(lattice, std::span<const Vec3>(nodes));
  for (int j = 0; j < 3; ++j)
    for (int k = 0; k < 4; ++k) {
      EXPECT_EQ(&read.at(j, k), &nodes[lattice.index(j, k)]) << j << "," << k;
      EXPECT_EQ(read.at(j, k), lattice.rest_position(j, k)) << j << "," << k;
    }
  // A const array gives a read-only view, a mutable one a writable view.
  static_assert(
      std::is_same_v<decltype(NodeView(lattice, std::as_const(nodes))), NodeView<const Vec3>>);
  static_assert(std::is_same_v<decltype(NodeView(3, 4, nodes)), NodeView<Vec3>>);
  NodeView write(lattice, nodes);
  write.at(2, 1) = Vec3(7.0, 8.0, 9.0);
  EXPECT_EQ(nodes[lattice.index(2, 1)], Vec3(7.0, 8.0, 9.0));
  // Clamped reads repeat the edge: one past each side is the edge node.
  EXPECT_EQ(&read.clamped(-1, 0), &read.at(0, 0));
  EXPECT_EQ(&read.clamped(3, 4), &read.at(2, 3));
  EXPECT_EQ(&read.clamped(1, -5), &read.at(1, 0));
  EXPECT_EQ(read.rows(), 3);
  EXPECT_EQ(read.cols(), 4);
}

}  // namespace
}  // namespace flagsim
