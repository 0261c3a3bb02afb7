// CSV batch driver for the PW85 contact function: see pw85_batch.hpp.
#include "io/cli/pw85_command.hpp"

#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <istream>
#include <ostream>
#include <string>
#include <vector>

#include "contact/ellipsoid/pw85.hpp"

namespace grains::io {
using namespace grains::contact;  // the PW85 solver and its types

namespace {

constexpr int kColumns = 15;

std::string expected_header() {
  return "q1_0,q1_1,q1_2,q1_3,q1_4,q1_5,q2_0,q2_1,q2_2,q2_3,q2_4,q2_5,r_0,r_1,r_2";
}

std::string trim(const std::string& s) {
  const auto a = s.find_first_not_of(" \t\r");
  if (a == std::string::npos) return {};
  const auto b = s.find_last_not_of(" \t\r");
  return s.substr(a, b - a + 1);
}

// Split on commas and parse each field as a double; on failure `why` says what.
bool parse_row(const std::string& line, std::vector<double>& v, std::string& why) {
  v.clear();
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = line.find(',', start);
    const std::string field = trim(line.substr(start, comma == std::string::npos ? std::string::npos : comma - start));
    if (field.empty()) {
      why = "column " + std::to_string(v.size() + 1) + " is empty";
      return false;
    }
    char* end = nullptr;
    const double x = std::strtod(field.c_str(), &end);
    if (end != field.c_str() + field.size()) {
      why = "column " + std::to_string(v.size() + 1) + " ('" + field + "') is not a number";
      return false;
    }
    if (!std::isfinite(x)) {  // NaN, Inf, or overflow (underflow to 0 is fine)
      why = "column " + std::to_string(v.size() + 1) + " ('" + field + "') is not a finite number";
      return false;
    }
    v.push_back(x);
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  if (static_cast<int>(v.size()) != kColumns) {
    why = "expected " + std::to_string(kColumns) + " columns, found " + std::to_string(v.size());
    return false;
  }
  return true;
}

void print(std::ostream& out, double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", x);
  out << buf;
}

}  // namespace

int run_pw85_batch(std::istream& in, std::ostream& out, std::ostream& err) {
  std::string line;
  long line_no = 0;
  // Header: the first non-blank line.
  while (std::getline(in, line)) {
    ++line_no;
    if (!trim(line).empty()) break;
  }
  std::string header = trim(line);
  std::string compact;
  for (char ch : header)
    if (ch != ' ' && ch != '\t') compact += ch;
  if (compact != expected_header()) {
    err << "pw85: line " << line_no << ": expected the header '" << expected_header() << "'";
    if (!header.empty()) err << ", found '" << header << "'";
    err << "\n";
    return 2;
  }
  out << expected_header() << ",mu2,lambda\n";

  int failed = 0;
  long row = 0;
  std::vector<double> v;
  while (std::getline(in, line)) {
    ++line_no;
    if (trim(line).empty()) continue;
    ++row;
    std::string why;
    if (!parse_row(line, v, why)) {
      err << "pw85: line " << line_no << " (row " << row << "): " << why << "\n";
      ++failed;
      continue;
    }
    SymMat3 q1, q2;
    for (int i = 0; i < 6; ++i) {
      q1[i] = v[i];
      q2[i] = v[6 + i];
    }
    const Eigen::Vector3d r(v[12], v[13], v[14]);
    const Pw85Result res = pw85_contact(r, q1, q2);
    if (res.status != Pw85Status::ok) {
      std::string what = to_string(res.status);
      if (res.status == Pw85Status::not_spd)
        what = std::string(is_spd(q1) ? "q2" : "q1") + " is not symmetric positive-definite";
      err << "pw85: line " << line_no << " (row " << row << "): " << what << "\n";
      ++failed;
      continue;
    }
    for (int i = 0; i < kColumns; ++i) {
      print(out, v[i]);
      out << ',';
    }
    print(out, res.mu2);
    out << ',';
    print(out, res.lambda);
    out << '\n';
  }
  if (failed > 0) err << "pw85: " << failed << " of " << row << " rows failed\n";
  return failed > 0 ? 1 : 0;
}

}  // namespace grains::io
