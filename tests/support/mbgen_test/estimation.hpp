// What the estimators' tests share: the LinearModel, mdof2 and its synthetic data. Header-only; *_test.cpp only.
#pragma once

#include "mbgen_test/linear_model.hpp"
#include "mbgen_test/mdof2.hpp"
#include "mbgen_test/mdof2_data.hpp"

#include "mbgen/estimation/fit.hpp"
