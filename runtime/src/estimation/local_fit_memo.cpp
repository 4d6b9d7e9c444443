#include "local_fit_memo.hpp"

#include "mbgen/estimation/fit.hpp"

namespace mbgen {

std::shared_ptr<estimation::LocalFitMemo> make_local_fit_memo() {
  return std::make_shared<estimation::LocalFitMemo>();
}

}  // namespace mbgen

namespace mbgen::estimation {

void Fingerprint::add(const void* data, std::size_t bytes) {
  const auto* p = static_cast<const unsigned char*>(data);
  for (std::size_t i = 0; i < bytes; ++i) {
    h_ ^= p[i];
    h_ *= 1099511628211ULL;
  }
}

void Fingerprint::add(const Eigen::VectorXd& v) {
  add(static_cast<int>(v.size()));
  add(v.data(), sizeof(double) * static_cast<std::size_t>(v.size()));
}

std::optional<LmResult> LocalFitMemo::find(const Key& key) const {
  std::lock_guard<std::mutex> lock(mutex_);
  const auto it = runs_.find(key);
  if (it == runs_.end()) return std::nullopt;
  return it->second;
}

void LocalFitMemo::store(const Key& key, const LmResult& result) {
  std::lock_guard<std::mutex> lock(mutex_);
  runs_.emplace(key, result);
}

}  // namespace mbgen::estimation
