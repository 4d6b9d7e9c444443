#include "emit/operation_count.hpp"

#include <catch2/catch.hpp>

using namespace mbgen::emit;

TEST_CASE("operations are counted as the printer writes them") {
  const GiNaC::symbol x("x"), y("y"), z("z");
  OperationCounter c;
  CHECK(c.count(x) == 0);
  CHECK(c.count(GiNaC::numeric(7)) == 0);
  CHECK(c.count(GiNaC::numeric(3, 4)) == 1);              // Scalar(3)/Scalar(4)
  CHECK(c.count(x * y + z) == 2);
  CHECK(c.count(x * y * z) == 2);
  CHECK(c.count(GiNaC::pow(x, 3)) == 2);                  // x*x*x
  CHECK(c.count(GiNaC::pow(x, -2)) == 2);                 // Scalar(1)/(x*x)
  CHECK(c.count(GiNaC::pow(x, 7)) == 1);                  // pow(x, Scalar(7))
  CHECK(c.count(GiNaC::sqrt(x)) == 1);
  CHECK(c.count(GiNaC::sin(x + y)) == 2);
  CHECK(c.count(GiNaC::numeric(3, 4) * x) == 2);          // the coefficient's quotient and the product
  // A repeated subexpression counts at each occurrence (the tree, as evaluated without CSE).
  const GiNaC::ex s = GiNaC::sin(x + y);
  CHECK(c.count(s * z + s) == 2 + 2 + 2);
}
