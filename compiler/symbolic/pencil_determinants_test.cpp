// The multimodular determinants against GiNaC's (minor expansion) on small pencils, including the cases that leave
// the fast path: a zero pivot (dense elimination), a scrambled numbering (reverse Cuthill-McKee), rational entries
// with large denominators and numbers of many digits (many primes).
#include <catch2/catch.hpp>

#include <ginac/ginac.h>

#include "symbolic/modular.hpp"
#include "symbolic/pencil_determinants.hpp"

using namespace mbgen::symbolic;

namespace {

struct Lcg {
  std::uint64_t state;
  long next(long range) {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    return static_cast<long>((state >> 33) % static_cast<std::uint64_t>(range));
  }
  // A rational with a numerator of up to `digits` digits, sometimes zero (sparsity).
  cln::cl_RA rational(int digits, int zero_in = 3) {
    if (next(zero_in) == 0) return 0;
    cln::cl_I num = 0;
    for (int d = 0; d < digits; ++d) num = num * 10 + next(10);
    if (next(2)) num = -num;
    return num / cln::cl_I(1 + next(999));
  }
};

GiNaC::ex to_ex(const cln::cl_RA& x) { return GiNaC::numeric(x); }

// The reference: GiNaC's determinants of P(s) and of each bordered matrix, ascending coefficients.
void check_against_ginac(const RationalPencil& rp) {
  const GiNaC::symbol s("s");
  const auto n = static_cast<unsigned>(rp.n);
  GiNaC::matrix p(n, n);
  for (unsigned i = 0; i < n; ++i)
    for (unsigned j = 0; j < n; ++j)
      p(i, j) = to_ex(rp.M[i * n + j]) * s * s + to_ex(rp.C[i * n + j]) * s + to_ex(rp.K[i * n + j]);
  const PencilPolynomials got = exact_polynomials(rp);
  REQUIRE(got.determinant.size() == 2 * n + 1);
  const GiNaC::ex det = GiNaC::expand(p.determinant());
  for (unsigned k = 0; k <= 2 * n; ++k) CHECK(to_ex(got.determinant[k]) == det.coeff(s, static_cast<int>(k)));
  for (std::size_t o = 0; o < rp.outputs.size(); ++o)
    for (std::size_t u = 0; u < rp.inputs.size(); ++u) {
      GiNaC::matrix bordered(n + 1, n + 1);
      for (unsigned i = 0; i < n; ++i) {
        for (unsigned j = 0; j < n; ++j) bordered(i, j) = p(i, j);
        bordered(i, n) = to_ex(rp.inputs[u][i]);
        bordered(n, i) = to_ex(rp.outputs[o].d[i]) + to_ex(rp.outputs[o].v[i]) * s + to_ex(rp.outputs[o].a[i]) * s * s;
      }
      const GiNaC::ex num = GiNaC::expand(-bordered.determinant());
      REQUIRE(got.numerators[o][u].size() == 2 * n + 1);
      for (unsigned k = 0; k <= 2 * n; ++k) CHECK(to_ex(got.numerators[o][u][k]) == num.coeff(s, static_cast<int>(k)));
    }
}

RationalPencil random_pencil(int n, int digits, std::uint64_t seed, int zero_in = 3) {
  Lcg g{seed};
  RationalPencil rp;
  rp.n = n;
  const auto N = static_cast<std::size_t>(n);
  for (auto* m : {&rp.M, &rp.C, &rp.K}) {
    m->assign(N * N, 0);
    for (std::size_t k = 0; k < N * N; ++k) (*m)[k] = g.rational(digits, zero_in);
  }
  for (std::size_t i = 0; i < N; ++i) rp.M[i * N + i] = 1 + g.next(50);  // a non-singular M, degree 2n
  for (int u = 0; u < 2; ++u) {
    rp.inputs.emplace_back(N, 0);
    for (auto& b : rp.inputs.back()) b = g.rational(digits);
  }
  RationalPencil::OutputRow row{std::vector<cln::cl_RA>(N, 0), std::vector<cln::cl_RA>(N, 0), std::vector<cln::cl_RA>(N, 0)};
  for (auto* part : {&row.d, &row.v, &row.a})
    for (auto& c : *part) c = g.rational(digits);
  rp.outputs.push_back(row);
  return rp;
}

}  // namespace

TEST_CASE("multimodular determinants equal GiNaC's: dense random pencils, small and large numbers") {
  check_against_ginac(random_pencil(4, 3, 1, 1000));
  check_against_ginac(random_pencil(5, 3, 2));
  check_against_ginac(random_pencil(5, 60, 3));  // coefficients of hundreds of digits: several primes
}

TEST_CASE("multimodular determinants: a zero leading pivot and a singular M") {
  RationalPencil rp = random_pencil(5, 4, 4);
  rp.M[0] = rp.C[0] = rp.K[0] = 0;  // P(s)(0, 0) = 0: the band elimination stops, dense pivoting takes over
  check_against_ginac(rp);
  for (std::size_t j = 0; j < 5; ++j) rp.M[5 + j] = 0;  // M's second row zero: det P has degree < 2n
  check_against_ginac(rp);
}

TEST_CASE("multimodular determinants: a banded pencil numbered out of order is renumbered") {
  // A tridiagonal chain 0-1-2-3-4-5 with its coordinates listed as 3, 0, 5, 1, 4, 2.
  const int perm[6] = {3, 0, 5, 1, 4, 2};
  RationalPencil rp = random_pencil(6, 5, 5, 1000);
  Lcg g{6};
  for (auto* m : {&rp.M, &rp.C, &rp.K}) {
    m->assign(36, 0);
    for (int i = 0; i < 6; ++i)
      for (int j = std::max(0, i - 1); j <= std::min(5, i + 1); ++j)
        (*m)[static_cast<std::size_t>(perm[i] * 6 + perm[j])] = g.rational(5, 1000) + (i == j ? 7 : 0);
  }
  check_against_ginac(rp);
}

TEST_CASE("gcd degree modulo a prime") {
  const std::uint64_t p = modular::prime(0);
  // (s + 1)(s + 2) and (s + 1)(s - 3): gcd s + 1
  CHECK(gcd_degree_modulo({2, 3, 1}, {p - 3, p - 2, 1}, p) == 1);
  CHECK(gcd_degree_modulo({2, 3, 1}, {5, 1}, p) == 0);
  CHECK(gcd_degree_modulo({0}, {0}, p) == -1);
}

TEST_CASE("Chinese remainders in the symmetric range") {
  const modular::Reconstructor crt(3);
  // Negative values by negation: CLN's cl_I(int) shifts a negative int left (undefined behaviour, UBSan).
  const cln::cl_I x = cln::expt_pos(-cln::cl_I(7), 60);                   // 169 bits, under 3 primes' 186
  const cln::cl_I y = -(cln::expt_pos(cln::cl_I(10), 54) + 12345);
  for (const cln::cl_I& v : {x, y, cln::cl_I(0), -cln::cl_I(1)}) {
    std::vector<std::uint64_t> r;
    for (int k = 0; k < 3; ++k) r.push_back(cln::cl_I_to_UQ(cln::mod(v, cln::cl_I(modular::prime(k)))));
    CHECK(crt(r) == v);
  }
}
