// Arithmetic modulo word-sized primes, for exact multimodular computations (internal): an exact integer result
// whose size is bounded in advance is computed modulo enough primes, in machine words, and put together by the
// Chinese remainder theorem. This is what keeps exact determinants of large blocks polynomial in cost and fast.
#pragma once

#include <cln/integer.h>

#include <cstdint>
#include <vector>

namespace mbgen::symbolic::modular {

// The field Z/pZ for an odd prime p < 2^62, elements kept in Montgomery form (a R mod p, R = 2^64), so a
// product is two word multiplications and no division.
class Field {
 public:
  explicit Field(std::uint64_t prime);
  std::uint64_t prime() const { return p_; }

  std::uint64_t add(std::uint64_t a, std::uint64_t b) const {
    const std::uint64_t s = a + b;
    return s >= p_ ? s - p_ : s;
  }
  std::uint64_t sub(std::uint64_t a, std::uint64_t b) const { return a >= b ? a - b : a + p_ - b; }
  std::uint64_t mul(std::uint64_t a, std::uint64_t b) const {
    return reduce(static_cast<unsigned __int128>(a) * b);
  }
  std::uint64_t inverse(std::uint64_t a) const;  // a != 0
  std::uint64_t one() const { return one_; }
  std::uint64_t from_small(std::uint64_t a) const;   // a < p, plain -> Montgomery
  std::uint64_t from_integer(const cln::cl_I& a) const;  // any integer, reduced
  std::uint64_t to_plain(std::uint64_t a) const { return reduce(a); }

 private:
  std::uint64_t reduce(unsigned __int128 t) const {
    const std::uint64_t m = static_cast<std::uint64_t>(t) * neg_inv_;
    const std::uint64_t r =
        static_cast<std::uint64_t>((t + static_cast<unsigned __int128>(m) * p_) >> 64);
    return r >= p_ ? r - p_ : r;
  }
  std::uint64_t p_, neg_inv_, r2_, one_;
  cln::cl_I p_big_;
};

// The k-th prime below 2^62 counting downwards (k = 0, 1, ...): deterministic, the same on every run. Each is
// above 2^61.99, so a product of m of them exceeds 2^(61.99 m).
std::uint64_t prime(int k);

// The integers with given residues modulo primes(0..m-1), in the symmetric range (-P/2, P/2], P their product.
// residues[k] is the plain (not Montgomery) residue modulo prime(k).
class Reconstructor {
 public:
  explicit Reconstructor(int primes);
  int primes() const { return static_cast<int>(primes_.size()); }
  cln::cl_I operator()(const std::vector<std::uint64_t>& residues) const;

 private:
  std::vector<std::uint64_t> primes_;
  std::vector<std::uint64_t> inverse_of_product_;  // (p_0 ... p_{k-1})^-1 mod p_k, plain
  cln::cl_I product_, half_;
};

}  // namespace mbgen::symbolic::modular
