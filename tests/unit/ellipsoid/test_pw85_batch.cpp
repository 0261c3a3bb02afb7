// The `grains pw85` CSV batch: good rows reproduce pw85_contact exactly, bad
// rows are reported with their row number and do not stop the others.
#include <gtest/gtest.h>

#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

#include "contact/ellipsoid/pw85.hpp"
#include "io/cli/pw85_command.hpp"

namespace grains::contact {
using io::run_pw85_batch;

namespace {

const std::string kHeader = "q1_0,q1_1,q1_2,q1_3,q1_4,q1_5,q2_0,q2_1,q2_2,q2_3,q2_4,q2_5,r_0,r_1,r_2";

std::vector<double> split(const std::string& line) {
  std::vector<double> v;
  std::stringstream ss(line);
  std::string f;
  while (std::getline(ss, f, ',')) v.push_back(std::strtod(f.c_str(), nullptr));
  return v;
}

TEST(Pw85Batch, GoodRowsMatchTheSolverBitForBit) {
  const std::string in = kHeader + "\n" +
                         "1,0,0,1,0,1,1,0,0,1,0,1,3,0,0\n"                       // unit spheres, mu = 1.5
                         "4,0.5,0.1,2,0.2,1,1,0,0,9,0,0.25,0.3,-2.5,1.7\n"
                         "\n"                                                     // blank line skipped
                         " 1e-4 , 0,0,1e-4,0,1e-2, 2,1,0,2,0,1, 0.01,0.02,0.03\r\n";  // spaces, CRLF
  std::istringstream is(in);
  std::ostringstream out, err;
  EXPECT_EQ(run_pw85_batch(is, out, err), 0);
  EXPECT_EQ(err.str(), "");
  std::istringstream os(out.str());
  std::string line;
  std::getline(os, line);
  EXPECT_EQ(line, kHeader + ",mu2,lambda");
  int rows = 0;
  while (std::getline(os, line)) {
    const std::vector<double> v = split(line);
    ASSERT_EQ(v.size(), 17u) << line;
    SymMat3 q1, q2;
    for (int i = 0; i < 6; ++i) {
      q1[i] = v[i];
      q2[i] = v[6 + i];
    }
    const Pw85Result res = pw85_contact(Eigen::Vector3d(v[12], v[13], v[14]), q1, q2);
    EXPECT_EQ(v[15], res.mu2) << "%.17g must round-trip";
    EXPECT_EQ(v[16], res.lambda);
    ++rows;
  }
  EXPECT_EQ(rows, 3);
  EXPECT_NE(out.str().find("1,0,0,1,0,1,1,0,0,1,0,1,3,0,0,2.25,0.5\n"), std::string::npos) << out.str();
}

TEST(Pw85Batch, BadRowsAreReportedAndSkipped) {
  const std::string in = kHeader + "\n" +
                         "1,0,0,1,0,1,1,0,0,1,0,1,3,0,0\n"          // row 1 ok
                         "1,0,0,1,0,1,1,0,0,1,0,1,3,0\n"            // row 2: 14 columns
                         "1,0,0,1,0,1,1,0,0,1,0,1,3,0,0,7\n"        // row 3: 16 columns
                         "1,0,0,1,0,nan,1,0,0,1,0,1,3,0,0\n"        // row 4: NaN
                         "1,0,0,1,0,1,1,0,0,1,0,1,inf,0,0\n"        // row 5: Inf
                         "1,2,0,1,0,1,1,0,0,1,0,1,3,0,0\n"          // row 6: q1 indefinite
                         "1,0,0,1,0,1,1,0,0,-1,0,1,3,0,0\n"         // row 7: q2 not SPD
                         "1,0,0,1,0,1,1,0,0,1,0,1,abc,0,0\n"        // row 8: not a number
                         "1,0,0,1,0,1,1,0,0,1,0,1,,0,0\n"           // row 9: empty field
                         "1,0,0,1,0,1,1,0,0,1,0,1,1e999,0,0\n"      // row 10: overflow
                         "4,0,0,4,0,4,1,0,0,1,0,1,0,0,1.5\n";       // row 11 ok
  std::istringstream is(in);
  std::ostringstream out, err;
  EXPECT_EQ(run_pw85_batch(is, out, err), 1);
  const std::string e = err.str();
  for (int row : {2, 3, 4, 5, 6, 7, 8, 9, 10})
    EXPECT_NE(e.find("(row " + std::to_string(row) + ")"), std::string::npos) << "row " << row << "\n" << e;
  EXPECT_EQ(e.find("(row 1)"), std::string::npos);
  EXPECT_EQ(e.find("(row 11)"), std::string::npos);
  EXPECT_NE(e.find("line 3 (row 2): expected 15 columns, found 14"), std::string::npos) << e;
  EXPECT_NE(e.find("(row 6): q1 is not symmetric positive-definite"), std::string::npos) << e;
  EXPECT_NE(e.find("(row 7): q2 is not symmetric positive-definite"), std::string::npos) << e;
  EXPECT_NE(e.find("9 of 11 rows failed"), std::string::npos) << e;
  // The two good rows are in the output, nothing else.
  std::istringstream os(out.str());
  std::string line;
  int lines = 0;
  while (std::getline(os, line)) ++lines;
  EXPECT_EQ(lines, 3);
  EXPECT_NE(out.str().find(",2.25,0.5\n"), std::string::npos);
  EXPECT_NE(out.str().find("4,0,0,4,0,4,1,0,0,1,0,1,0,0,1.5,0.25,"), std::string::npos) << out.str();
}

TEST(Pw85Batch, MissingOrWrongHeader) {
  for (const std::string& in : {std::string(""), std::string("1,0,0,1,0,1,1,0,0,1,0,1,3,0,0\n"),
                               std::string("a,b,c\n1,0,0,1,0,1,1,0,0,1,0,1,3,0,0\n")}) {
    std::istringstream is(in);
    std::ostringstream out, err;
    EXPECT_EQ(run_pw85_batch(is, out, err), 2);
    EXPECT_NE(err.str().find("expected the header"), std::string::npos);
    EXPECT_EQ(out.str(), "");
  }
}

}  // namespace
}  // namespace grains::contact
