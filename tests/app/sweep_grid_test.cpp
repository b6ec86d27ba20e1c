#include "sweep_grid.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "flagsim/core/errors.hpp"

namespace flagsim::app {
namespace {

SweepOptions lists(std::string coarse, std::string substeps = "", std::string infill = "",
                   std::string relax = "", std::string backend = "") {
  SweepOptions o;
  o.coarse = std::move(coarse);
  o.substeps = std::move(substeps);
  o.infill = std::move(infill);
  o.relax = std::move(relax);
  o.backend = std::move(backend);
  return o;
}

TEST(SweepGrid, TheReferenceFirstThenTheHybridsWithTheCoarseLatticeSlowest) {
  const std::vector<SweepPoint> grid = sweep_grid(lists("5x7, 9X13", "100,200"));
  ASSERT_EQ(grid.size(), 5u);
  EXPECT_EQ(grid[0].label, "mass-spring reference");
  EXPECT_EQ(grid[0].sets, std::vector<std::string>{"scene.mode=\"mass-spring\""});
  EXPECT_EQ(grid[1].label, "hybrid 5x7 substeps 100");
  EXPECT_EQ(grid[1].sets, (std::vector<std::string>{"scene.mode=\"hybrid\"", "flag.coarse=[5,7]",
                                                    "solver.substeps=100"}));
  EXPECT_EQ(grid[2].label, "hybrid 5x7 substeps 200");
  EXPECT_EQ(grid[3].label, "hybrid 9x13 substeps 100");
  EXPECT_EQ(grid[4].label, "hybrid 9x13 substeps 200");
}

// Issue 33, item 11: Bullet runs only when asked for, after mass-spring,
// whatever order the list gives; a mode named twice runs once.
TEST(SweepGrid, OtherReferencesOnlyWhenAskedForAfterMassSpring) {
  SweepOptions o = lists("9x13");
  o.references = "xpbd,mass-spring,bullet,xpbd";
  const std::vector<SweepPoint> grid = sweep_grid(o);
  ASSERT_EQ(grid.size(), 4u);
  EXPECT_EQ(grid[0].label, "mass-spring reference");
  EXPECT_EQ(grid[1].label, "xpbd reference");
  EXPECT_EQ(grid[1].sets, std::vector<std::string>{"scene.mode=\"xpbd\""});
  EXPECT_EQ(grid[2].label, "bullet reference");
  EXPECT_EQ(grid[3].label, "hybrid 9x13");
}

TEST(SweepGrid, TheRelaxationCapMultipliesOnlyThePaperSolversPoints) {
  const std::vector<SweepPoint> grid =
      sweep_grid(lists("9x13", "", "smooth,paper", "100,8000", "spring-damper,xpbd"));
  std::vector<std::string> labels;
  for (std::size_t i = 1; i < grid.size(); ++i) labels.push_back(grid[i].label);
  EXPECT_EQ(labels,
            (std::vector<std::string>{
                "hybrid 9x13 spring-damper smooth", "hybrid 9x13 spring-damper paper relax 100",
                "hybrid 9x13 spring-damper paper relax 8000", "hybrid 9x13 xpbd smooth",
                "hybrid 9x13 xpbd paper relax 100", "hybrid 9x13 xpbd paper relax 8000"}));
  EXPECT_EQ(grid.back().sets.back(), "infill.relax_iterations=8000");
}

// sweep_grid(o) refuses `bad` (one list's text) with a message naming `flag`
// and saying what it `expected`.
void expect_refused(const SweepOptions& o, const std::string& bad, const std::string& flag,
                    const std::string& expected) {
  try {
    sweep_grid(o);
    ADD_FAILURE() << bad << ": accepted";
  } catch (const UserError& e) {
    EXPECT_NE(std::string(e.what()).find(flag), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
  }
}

// Issue 31: contact on and off side by side. 0 leaves the scene's own pole.
TEST(SweepGrid, PoleRadiiCrossTheHybridPointsAndZeroKeepsTheScenesPole) {
  SweepOptions o = lists("9x13", "", "", "", "spring-damper,implicit");
  o.pole_radius = "0, .04,1";
  const std::vector<SweepPoint> grid = sweep_grid(o);
  std::vector<std::string> labels;
  for (std::size_t i = 1; i < grid.size(); ++i) labels.push_back(grid[i].label);
  EXPECT_EQ(labels, (std::vector<std::string>{
                        "hybrid 9x13 spring-damper", "hybrid 9x13 spring-damper pole 0.04 m",
                        "hybrid 9x13 spring-damper pole 1.0 m", "hybrid 9x13 implicit",
                        "hybrid 9x13 implicit pole 0.04 m", "hybrid 9x13 implicit pole 1.0 m"}));
  EXPECT_EQ(grid[2].sets,
            (std::vector<std::string>{"scene.mode=\"hybrid\"", "flag.coarse=[9,13]",
                                      "solver.backend=\"spring-damper\"", "pole.radius=0.04"}));
  for (const char* bad : {"0.04,-1", "2", "0.04,", "4cm"}) {
    o.pole_radius = bad;
    expect_refused(o, bad, "--pole-radius", "expected pole radii in m");
  }
}

// Self-contact on and off side by side. 0 leaves the scene's own [contact].
TEST(SweepGrid, ContactThicknessesCrossTheHybridPointsAndZeroKeepsTheScenesOwn) {
  SweepOptions o = lists("9x13", "", "", "", "");
  o.contact_thickness = "0,.005";
  const std::vector<SweepPoint> grid = sweep_grid(o);
  ASSERT_EQ(grid.size(), 3u);
  EXPECT_EQ(grid[1].label, "hybrid 9x13");
  EXPECT_EQ(grid[2].label, "hybrid 9x13 contact 0.005 m");
  EXPECT_EQ(grid[2].sets.back(), "contact.thickness=0.005");
  for (const char* bad : {"-0.005", "5mm", "0.005,", "1.5"}) {
    o.contact_thickness = bad;
    expect_refused(o, bad, "--contact-thickness", "expected self-contact thicknesses in m");
  }
}

TEST(SweepGrid, AnItemItCannotReadIsNamedWithItsFlag) {
  const auto message = [](const SweepOptions& o) {
    try {
      sweep_grid(o);
    } catch (const UserError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(message(lists("")), "sweep: --coarse is required (e.g. --coarse 5x7,9x13)");
  EXPECT_EQ(message(lists("9x13,9by13")),
            "--coarse 9by13: expected coarse lattices as JcxKc, e.g. 5x7,9x13");
  EXPECT_EQ(message(lists("9x13,")), "--coarse : expected coarse lattices as JcxKc, e.g. 5x7,9x13");
  EXPECT_EQ(message(lists("9x13", "0")),
            "--substeps 0: expected counts of at least 1, comma-separated");
  EXPECT_EQ(message(lists("9x13", "", "fast")),
            "--infill fast: expected infill solvers smooth and/or paper");
  EXPECT_EQ(message(lists("9x13", "", "", "", "euler")),
            "--backend euler: expected backends spring-damper, bullet, implicit and/or xpbd");
  SweepOptions bullet = lists("9x13");
  bullet.references = "bullet";
  EXPECT_EQ(message(bullet),
            "--references bullet: every error is measured against mass-spring; list it too, "
            "e.g. --references mass-spring,bullet");
  bullet.references = "mass-spring,havok";
  EXPECT_EQ(message(bullet),
            "--references havok: expected full-lattice modes mass-spring, bullet, implicit "
            "and/or xpbd");
}

}  // namespace
}  // namespace flagsim::app
