#pragma once
// `grains pw85 [FILE]`: the PW85 contact function over a CSV table.
//
// Input: a header line, then one pair per line with 15 comma-separated
// numbers  q1_0..q1_5,q2_0..q2_5,r_0,r_1,r_2  (Q1, Q2 as packed upper
// triangles in row-major order, see ellipsoid.hpp; r = c2 - c1). Blank lines
// are skipped. Output: the header with ",mu2,lambda" appended, then for every
// good row the 15 input values and mu2, lambda, all printed with %.17g (so
// they read back to the same doubles). A bad row (wrong column count, a field
// that is not a number, NaN/Inf, a matrix that is not symmetric
// positive-definite, a solve that does not converge) writes one message to
// `err` naming its line and data-row number, is left out of `out`, and the
// other rows are still processed.
#include <iosfwd>

namespace grains::io {

// Returns 0 when every row was processed, 1 when some row failed, 2 when the
// header is missing or wrong.
int run_pw85_batch(std::istream& in, std::ostream& out, std::ostream& err);

}  // namespace grains::io
