// FFTW's planner (plan creation and destruction) is not thread-safe and is shared by the whole process:
// every part of the runtime that plans FFTW transforms holds this one mutex while doing so. Executing a plan
// needs no lock.
#pragma once

#include <mutex>

namespace mbgen {

std::mutex& fftw_planner_mutex();

}  // namespace mbgen
