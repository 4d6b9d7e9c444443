#include "symbolic/modular.hpp"

#include <mutex>
#include <stdexcept>

namespace mbgen::symbolic::modular {

namespace {

using u128 = unsigned __int128;

std::uint64_t mulmod(std::uint64_t a, std::uint64_t b, std::uint64_t m) {
  return static_cast<std::uint64_t>(static_cast<u128>(a) * b % m);
}

std::uint64_t powmod(std::uint64_t a, std::uint64_t e, std::uint64_t m) {
  std::uint64_t r = 1;
  for (; e; e >>= 1, a = mulmod(a, a, m))
    if (e & 1) r = mulmod(r, a, m);
  return r;
}

// Miller-Rabin with the first twelve primes as bases: deterministic below 3.3e24, so for every 64-bit n.
bool is_prime(std::uint64_t n) {
  static const std::uint64_t bases[] = {2, 3, 5, 7, 11, 13, 17, 19, 23, 29, 31, 37};
  if (n < 2) return false;
  for (std::uint64_t b : bases)
    if (n % b == 0) return n == b;
  std::uint64_t d = n - 1;
  int r = 0;
  while (d % 2 == 0) d /= 2, ++r;
  for (std::uint64_t b : bases) {
    std::uint64_t x = powmod(b, d, n);
    if (x == 1 || x == n - 1) continue;
    bool composite = true;
    for (int i = 1; i < r && composite; ++i) {
      x = mulmod(x, x, n);
      if (x == n - 1) composite = false;
    }
    if (composite) return false;
  }
  return true;
}

}  // namespace

Field::Field(std::uint64_t prime) : p_(prime), p_big_(static_cast<cln::cl_I>(prime)) {
  if (prime % 2 == 0 || prime >= (std::uint64_t{1} << 62)) throw std::invalid_argument("Field: unsupported modulus");
  std::uint64_t inv = 1;  // p^-1 mod 2^64 by Newton's iteration (each step doubles the correct bits)
  for (int i = 0; i < 6; ++i) inv *= 2 - prime * inv;
  neg_inv_ = 0 - inv;
  const std::uint64_t r = static_cast<std::uint64_t>((static_cast<u128>(1) << 64) % prime);
  r2_ = mulmod(r, r, prime);
  one_ = r;
}

std::uint64_t Field::from_small(std::uint64_t a) const { return mul(a, r2_); }

std::uint64_t Field::from_integer(const cln::cl_I& a) const {
  return from_small(cln::cl_I_to_UQ(cln::mod(a, p_big_)));
}

std::uint64_t Field::inverse(std::uint64_t a) const {
  // Fermat: a^(p-2), by squaring in Montgomery form (about 90 products and no division: faster than extended
  // Euclid's 40 divisions; one inverse per pivot is a third of the band elimination's time).
  if (a == 0) throw std::domain_error("Field::inverse of zero");
  std::uint64_t r = one_;
  for (std::uint64_t e = p_ - 2; e; e >>= 1, a = mul(a, a))
    if (e & 1) r = mul(r, a);
  return r;
}

std::uint64_t prime(int k) {
  static std::mutex mutex;
  static std::vector<std::uint64_t> primes;
  const std::lock_guard<std::mutex> lock(mutex);
  std::uint64_t candidate = primes.empty() ? (std::uint64_t{1} << 62) - 1 : primes.back() - 2;
  while (static_cast<int>(primes.size()) <= k) {
    while (!is_prime(candidate)) candidate -= 2;
    primes.push_back(candidate);
    candidate -= 2;
  }
  return primes[static_cast<std::size_t>(k)];
}

Reconstructor::Reconstructor(int primes) : product_(1) {
  for (int k = 0; k < primes; ++k) {
    const std::uint64_t p = prime(k);
    const Field f(p);
    std::uint64_t partial = f.one();  // p_0 ... p_{k-1} mod p, Montgomery
    for (std::uint64_t q : primes_) partial = f.mul(partial, f.from_small(q % p));
    inverse_of_product_.push_back(f.to_plain(f.inverse(partial)));
    primes_.push_back(p);
    product_ = product_ * static_cast<cln::cl_I>(p);
  }
  half_ = cln::ash(product_, -1);
}

cln::cl_I Reconstructor::operator()(const std::vector<std::uint64_t>& residues) const {
  // Garner: x = v_0 + v_1 p_0 + v_2 p_0 p_1 + ..., each mixed-radix digit v_k computed modulo p_k.
  const std::size_t m = primes_.size();
  std::vector<std::uint64_t> v(m);
  for (std::size_t k = 0; k < m; ++k) {
    const std::uint64_t p = primes_[k];
    std::uint64_t x = 0;  // v_0 + v_1 p_0 + ... + v_{k-1} p_0...p_{k-2} mod p, by Horner from the top digit
    for (std::size_t j = k; j-- > 0;) x = static_cast<std::uint64_t>((static_cast<u128>(x) * (primes_[j] % p) + v[j]) % p);
    const std::uint64_t r = residues[k] % p;
    v[k] = mulmod(r >= x ? r - x : r + p - x, inverse_of_product_[k], p);
  }
  cln::cl_I x = 0;
  for (std::size_t k = m; k-- > 0;) x = x * static_cast<cln::cl_I>(primes_[k]) + static_cast<cln::cl_I>(v[k]);
  return x > half_ ? x - product_ : x;
}

}  // namespace mbgen::symbolic::modular
