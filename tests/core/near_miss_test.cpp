#include "flagsim/core/near_miss.hpp"

#include <gtest/gtest.h>

namespace flagsim::detail {
namespace {

TEST(NearMiss, EditDistance) {
  EXPECT_EQ(edit_distance("kitten", "sitting"), 3);
  EXPECT_EQ(edit_distance("", "abc"), 3);
  EXPECT_EQ(edit_distance("same", "same"), 0);
  EXPECT_EQ(edit_distance("wnid", "wind"), 1);  // a swap of neighbours is one typo
}

TEST(NearMiss, SuggestsOnlyPlausibleTypos) {
  const std::string_view keys[] = {"stretch_modulus", "areal_density", "damping", "pin"};
  EXPECT_EQ(closest_name("strech_modulus", keys), "stretch_modulus");
  EXPECT_EQ(closest_name("dampng", keys), "damping");
  EXPECT_EQ(closest_name("areal", keys), "areal_density");  // a prefix
  EXPECT_EQ(closest_name("colour", keys), "");
}

}  // namespace
}  // namespace flagsim::detail
