#include "emit/operation_count.hpp"

namespace mbgen::emit {

namespace {

std::size_t own_operations(const GiNaC::ex& e) {
  if (GiNaC::is_a<GiNaC::numeric>(e)) {
    const GiNaC::numeric& n = GiNaC::ex_to<GiNaC::numeric>(e);
    return n.is_rational() && !n.is_integer() ? 1 : 0;
  }
  if (GiNaC::is_a<GiNaC::add>(e) || GiNaC::is_a<GiNaC::mul>(e)) return e.nops() - 1;
  if (GiNaC::is_a<GiNaC::power>(e)) {
    const GiNaC::ex& k = e.op(1);
    if (k.info(GiNaC::info_flags::integer)) {
      const int n = GiNaC::ex_to<GiNaC::numeric>(k).to_int();
      const int m = n < 0 ? -n : n;
      if (m >= 2 && m <= 4) return static_cast<std::size_t>(m - 1 + (n < 0 ? 1 : 0));
    }
    return 1;
  }
  if (GiNaC::is_a<GiNaC::function>(e)) return 1;
  return 0;
}

}  // namespace

std::size_t OperationCounter::count(const GiNaC::ex& e) {
  if (e.nops() == 0) return own_operations(e);
  if (auto it = memo_.find(e); it != memo_.end()) return it->second;
  std::size_t total = own_operations(e);
  // The exponent of a power is printed as a literal, not evaluated, when it is a number.
  const bool numeric_exponent = GiNaC::is_a<GiNaC::power>(e) && GiNaC::is_a<GiNaC::numeric>(e.op(1));
  for (std::size_t i = 0; i < e.nops(); ++i)
    if (!(numeric_exponent && i == 1)) total += count(e.op(i));
  memo_.emplace(e, total);
  return total;
}

}  // namespace mbgen::emit
