// Every enum the scene file names has one table of names: each value named
// once, each name read back as its value, the tables in the contract's order.
#include "flagsim/core/enum_names.hpp"

#include <gtest/gtest.h>

#include <set>
#include <string>

#include "flagsim/scene/scene.hpp"

namespace flagsim {
namespace {

template <typename E, std::size_t N>
void expect_a_name_per_value(const NameTable<E, N>& table, std::size_t values) {
  EXPECT_EQ(N, values);  // every enumerator has its entry
  std::set<std::string_view> names;
  std::set<int> seen;
  for (const auto& [value, name] : table) {
    EXPECT_TRUE(names.insert(name).second) << name << " twice";
    EXPECT_TRUE(seen.insert(int(value)).second) << name << ": its value named twice";
    EXPECT_EQ(value_in(table, name), value) << name;
    EXPECT_EQ(name_in(table, value), name);
    EXPECT_EQ(name.data()[name.size()], '\0') << name;  // to_string hands out .data()
  }
  EXPECT_EQ(value_in(table, ""), std::nullopt);
  EXPECT_EQ(value_in(table, std::string(table[0].name) + "x"), std::nullopt);
}

TEST(EnumNames, EveryValueHasOneNameThatReadsBack) {
  expect_a_name_per_value(kModeNames, 6);
  expect_a_name_per_value(kPinNames, 5);
  expect_a_name_per_value(kInfillSolverNames, 2);
  expect_a_name_per_value(kBackendNames, 4);
  expect_a_name_per_value(kLinearSolverNames, 2);
  expect_a_name_per_value(kRenderStyleNames, 3);
}

TEST(EnumNames, ToStringAndTheListsFollowTheTables) {
  EXPECT_STREQ(to_string(Mode::kMassSpring), "mass-spring");
  EXPECT_STREQ(to_string(Backend::kSpringDamper), "spring-damper");
  EXPECT_STREQ(to_string(LinearSolver::kCholesky), "cholesky");
  EXPECT_STREQ(to_string(RenderStyle::kTextured), "textured");
  EXPECT_STREQ(to_string(PinSet::kCorners), "corners");
  EXPECT_STREQ(to_string(InfillSolverKind::kPaper), "paper");
  // The order users are told them in (contract, error messages).
  const std::vector<std::string_view> backends = names_in(kBackendNames);
  EXPECT_EQ(backends,
            (std::vector<std::string_view>{"spring-damper", "bullet", "implicit", "xpbd"}));
  EXPECT_EQ(name_in(kBackendNames, Backend(99)), "?");
}

}  // namespace
}  // namespace flagsim
