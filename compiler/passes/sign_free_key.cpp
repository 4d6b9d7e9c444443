#include "passes/sign_free_key.hpp"

#include <algorithm>
#include <numeric>
#include <sstream>

namespace mbgen::passes {
namespace {

std::string exact_text(const GiNaC::ex& e) {
  std::ostringstream text;
  text << e;
  return text.str();
}

bool is_unit(const GiNaC::ex& e) {
  return GiNaC::is_a<GiNaC::numeric>(e) && GiNaC::abs(GiNaC::ex_to<GiNaC::numeric>(e)).is_equal(1);
}

}  // namespace

std::pair<GiNaC::ex, int> strip_unit_factor(const GiNaC::ex& e) {
  if (!GiNaC::is_a<GiNaC::mul>(e) || e.nops() != 2) return {e, 1};
  for (std::size_t i = 0; i < 2; ++i) {
    if (is_unit(e.op(i))) return {e.op(1 - i), GiNaC::ex_to<GiNaC::numeric>(e.op(i)).is_negative() ? -1 : 1};
  }
  return {e, 1};
}

const std::pair<std::string, int>& SignFreeKeys::entry(const GiNaC::ex& e) {
  if (auto it = memo_.find(e); it != memo_.end()) return it->second;
  auto computed = compute(e);
  return memo_.emplace(e, std::move(computed)).first->second;
}

std::string SignFreeKeys::signed_key(const GiNaC::ex& e) { return (sign(e) < 0 ? "-" : "") + key(e); }

std::pair<std::string, int> SignFreeKeys::compute(const GiNaC::ex& e) {
  using namespace GiNaC;
  if (is_a<numeric>(e)) {
    const numeric& n = ex_to<numeric>(e);
    return {exact_text(abs(n)), n.is_negative() ? -1 : 1};
  }
  if (is_a<symbol>(e)) return {ex_to<symbol>(e).get_name(), 1};
  if (is_a<constant>(e)) return {exact_text(e), 1};
  if (auto [factor, unit] = strip_unit_factor(e); unit != 1 || !factor.is_equal(e)) {
    const auto& inner = entry(factor);
    return {inner.first, unit * inner.second};
  }
  if (is_a<add>(e)) {
    std::vector<std::size_t> order = operand_order(e);
    const int first = sign(e.op(order.front()));
    std::string k = "+(";
    for (std::size_t i : order) k += (sign(e.op(i)) == first ? "+" : "-") + key(e.op(i)) + ",";
    return {k + ")", first};
  }
  if (is_a<mul>(e)) {
    std::vector<std::string> factors;
    int s = 1;
    for (std::size_t i = 0; i < e.nops(); ++i) {
      s *= sign(e.op(i));
      if (!is_unit(e.op(i))) factors.push_back(key(e.op(i)));
    }
    std::sort(factors.begin(), factors.end());
    std::string k = "*(";
    for (const std::string& f : factors) k += f + ",";
    return {k + ")", s};
  }
  if (is_a<power>(e)) {
    const ex& base = e.op(0);
    const ex& expo = e.op(1);
    if (expo.info(info_flags::integer)) {
      const bool odd = !expo.info(info_flags::even);
      return {"^(" + key(base) + "," + exact_text(expo) + ")", odd ? sign(base) : 1};
    }
    return {"^(" + signed_key(base) + "," + signed_key(expo) + ")", 1};
  }
  std::string k = is_a<function>(e) ? ex_to<function>(e).get_name() : "?" + exact_text(e);
  k += "(";
  for (std::size_t i = 0; i < e.nops(); ++i) k += signed_key(e.op(i)) + ",";
  return {k + ")", 1};
}

std::vector<std::size_t> SignFreeKeys::operand_order(const GiNaC::ex& e) {
  std::vector<std::size_t> order(e.nops());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::vector<const std::string*> keys(order.size());
  for (std::size_t i = 0; i < order.size(); ++i) keys[i] = &key(e.op(i));
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return *keys[a] < *keys[b]; });
  return order;
}

SignFreeKeys::FactorSign SignFreeKeys::factor_sign(const GiNaC::ex& f) {
  if (GiNaC::is_a<GiNaC::add>(f)) {
    const bool negative = sign(f) < 0;
    return {negative, negative};
  }
  if (GiNaC::is_a<GiNaC::power>(f) && GiNaC::is_a<GiNaC::add>(f.op(0)) && f.op(1).info(GiNaC::info_flags::integer) &&
      sign(f.op(0)) < 0)
    return {true, !f.op(1).info(GiNaC::info_flags::even)};
  return {};
}

}  // namespace mbgen::passes
