#include "flagsim/os/child_process.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace flagsim {
namespace {

TEST(ChildProcess, ExecArgvPointsAtEachArgumentThenNull) {
  const std::vector<std::string> argv = {"/bin/echo", "two words", ""};
  const std::vector<char*> c = exec_argv(argv);
  ASSERT_EQ(c.size(), 4u);
  for (std::size_t i = 0; i < argv.size(); ++i) EXPECT_EQ(c[i], argv[i].c_str()) << i;
  EXPECT_EQ(c.back(), nullptr);
}

TEST(ChildProcess, ArgumentsReachTheProgramAsTheyAreWithNoShell) {
  std::string output;
  // A shell would expand the variable and split the words; exec does neither.
  EXPECT_EQ(run_capturing({"/bin/echo", "$HOME two  spaces", ";", "x"}, output), 0);
  EXPECT_EQ(output, "$HOME two  spaces ; x\n");
}

TEST(ChildProcess, ExitCodesComeBackAndAProgramThatCannotStartIsMinusOne) {
  std::string output;
  EXPECT_EQ(run_capturing({"/bin/false"}, output), 1);
  EXPECT_EQ(run_quietly({"/bin/true"}), 0);
  EXPECT_EQ(run_quietly({"/no/such/program"}), -1);
  EXPECT_EQ(run_capturing({"/no/such/program"}, output), -1);
}

}  // namespace
}  // namespace flagsim
