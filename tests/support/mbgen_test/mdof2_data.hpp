// Synthetic mdof2 data by routes independent of the code under test: FRFs from the closed-form transfer functions,
// time records by exact modal zero-order-hold simulation. Compiled once in mdof2_data.cpp: the eigensolver and the
// complex inverse took 12 s of template instantiation in each of the 16 test files that include this header.
#pragma once

#include "mbgen_test/mdof2.hpp"

#include "mbgen/data/frf_data.hpp"
#include "mbgen/data/time_record.hpp"

#include <Eigen/Core>

#include <random>

namespace mbgen::test {

// FRF data set d1/F1, d2/F1 of mdof2 from the closed form, with complex Gaussian noise of standard deviation
// `relative_noise` times the channel's RMS |H| (40 dB SNR: 0.01).
FrfData mdof2_frf_data(const Mdof2Values& v, const Eigen::VectorXd& f_hz, double relative_noise, std::mt19937& rng);

// Adds to `values` the noise mdof2_frf_data adds: complex Gaussian, of standard deviation `relative_noise` times
// their RMS magnitude.
void add_relative_noise(Eigen::VectorXcd& values, double relative_noise, std::mt19937& rng);

// Exact zero-order-hold response from rest of M q'' + C q' + K q = B u, y = Cd q, by modal superposition of the
// first-order system: z = V^-1 x decouples into z+ = e^{l h} z + (e^{l h} - 1)/l (V^-1 B) u.
Eigen::MatrixXd zoh_modal_response(const Eigen::MatrixXd& M, const Eigen::MatrixXd& C, const Eigen::MatrixXd& K,
                                   const Eigen::MatrixXd& B, const Eigen::MatrixXd& Cd, const Eigen::MatrixXd& u,
                                   double h);

// mdof2 time record: white Gaussian force (held), outputs d1, d2 with noise at `relative_noise` times their RMS.
TimeRecord mdof2_time_record(const Mdof2Values& v, Eigen::Index samples, double h, double relative_noise,
                             std::mt19937& rng, double added_mass2 = 0);

}  // namespace mbgen::test
