// OutputErrorProblem::expected_noise_cost (output_error.hpp): the cost a fit can at best come down to.
#include "output_error.hpp"

#include "mbgen/data/frf_noise.hpp"

#include <stdexcept>
#include <limits>
#include <variant>

namespace mbgen::estimation {

double OutputErrorProblem::expected_noise_cost(const std::vector<DataSet>& data) const {
  double sum = 0;
  for (std::size_t d = 0; d < data.size() && d < sets_.size(); ++d) {
    if (!data[d].is_frf() || !sets_[d].frf) return std::numeric_limits<double>::quiet_NaN();
    const FrfData& f = std::get<FrfData>(data[d].content);
    for (std::size_t c = 0; c < f.channels.size() && c < sets_[d].sigma.size(); ++c) {
      // A complex noise of standard deviation s puts s^2 / 2 in each of the real and imaginary residual, which
      // are divided by the weighting sigma: s^2 / sigma^2 per line.
      try {
        const FrfNoise noise = frf_noise(f.f_hz, f.channels[c]);
        sum += noise.sigma.cwiseQuotient(sets_[d].sigma[c]).squaredNorm();
      } catch (const std::runtime_error&) {  // no noise estimate; a logic_error is a bug and goes on
        return std::numeric_limits<double>::quiet_NaN();
      }
    }
  }
  return sum;
}

}  // namespace mbgen::estimation
