#include "report.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "flagsim/core/errors.hpp"
#include "temp_dir.hpp"

namespace flagsim::app {
namespace {

ReportRow a_row() {
  ReportRow row;
  row.point = 3;
  row.label = "hybrid 9x13 substeps 1";
  row.mode = "hybrid";
  row.backend = "spring-damper";
  row.fine = "129x193";
  row.coarse = "9x13";
  row.substeps = 12;
  row.relax_iterations = 8000;
  row.frames = 61;
  row.ms_per_frame = 3.25;
  row.max_strain = 0.0091;
  row.p99_strain = 0.0052;
  row.flap_hz = 4.5;
  row.status = RunState::kDiverged;
  row.infill_solver = "paper";
  return row;
}

TEST(Report, ARowReadsBackAsWritten) {
  const ReportRow back = parse_csv_line(csv_line(a_row()));
  EXPECT_EQ(back.point, 3);
  EXPECT_EQ(back.label, "hybrid 9x13 substeps 1");
  EXPECT_EQ(back.backend, "spring-damper");
  EXPECT_EQ(back.coarse, "9x13");
  EXPECT_EQ(back.relax_iterations, 8000);
  EXPECT_EQ(back.frames, 61);
  EXPECT_EQ(back.ms_per_frame, 3.25);
  EXPECT_EQ(back.p99_strain, 0.0052);
  ASSERT_TRUE(back.flap_hz.has_value());
  EXPECT_EQ(*back.flap_hz, 4.5);
  EXPECT_FALSE(back.tracking_rms_m.has_value());  // empty cells stay empty
  EXPECT_EQ(back.status, RunState::kDiverged);
  EXPECT_EQ(back.infill_solver, "paper");
}

TEST(Report, TheStatusColumnHoldsTheContractsWord) {
  const std::string line = csv_line(a_row());
  EXPECT_NE(line.find(",diverged,paper,"), std::string::npos) << line;
  std::string foreign = line;
  foreign.replace(foreign.find(",diverged,"), 10, ",exploded,");
  try {
    (void)parse_csv_line(foreign);
    FAIL() << "a status outside the contract was read";
  } catch (const UserError& e) {
    EXPECT_STREQ(e.what(),
                 "a report row's status \"exploded\": expected running, complete, diverged, "
                 "interrupted");
  }
}

TEST(Report, WrittenRowsAreReadBackByCsvRows) {
  const test::TempDir dir;
  const std::string path = dir.file("report.csv");
  write_report(path, {a_row(), a_row()});
  const std::vector<std::string> rows = csv_rows(path);
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[0], csv_line(a_row()));
  write_report("", {a_row()});  // no path: nothing written, nothing thrown
}

TEST(Report, CsvRowsRefusesAForeignFileNamingIt) {
  const test::TempDir dir;
  const std::string path = dir.write("other.csv", "a,b,c\n1,2,3\n");
  EXPECT_THROW((void)csv_rows(path), UserError);
  const std::string short_row = dir.write("short.csv", csv_header() + "\n1,2,3\n");
  try {
    (void)csv_rows(short_row);
    FAIL();
  } catch (const UserError& e) {
    EXPECT_EQ(std::string(e.what()).rfind(short_row + ":2: not a row", 0), 0u) << e.what();
  }
}

TEST(Report, AReportPathMustBeAFileInAWritableDirectory) {
  const test::TempDir dir;
  check_report_path("");                      // the table only
  check_report_path(dir.file("report.csv"));  // a new file in an existing directory
  EXPECT_THROW(check_report_path(dir.file("missing/report.csv")), UserError);
  EXPECT_THROW(check_report_path(dir.path()), UserError);  // a directory, not a file
  {
    // Made when the command can make it (as run makes its output's), and
    // removed again when nothing was written there.
    CreatedDirectories directories;
    check_report_path(dir.file("new/deeper/report.csv"), &directories);
    EXPECT_TRUE(std::filesystem::is_directory(dir.file("new/deeper")));
  }
  EXPECT_FALSE(std::filesystem::exists(dir.file("new")));
  dir.write("plain", "a file");
  CreatedDirectories directories;
  EXPECT_THROW(check_report_path(dir.file("plain/report.csv"), &directories), UserError);
}

}  // namespace
}  // namespace flagsim::app
