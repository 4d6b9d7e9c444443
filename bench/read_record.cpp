// read_record FILE: reads a measured data file as `mbgen fit` does and prints the peak memory of the process per
// value read (docs/limits.md states it). A record of N samples and C columns holds N*C doubles once read.
#include <mbgen/data/data_set.hpp>

#include <sys/resource.h>

#include <chrono>
#include <cstdio>
#include <variant>

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: read_record FILE\n");
    return 2;
  }
  rusage before{};
  getrusage(RUSAGE_SELF, &before);
  const auto start = std::chrono::steady_clock::now();
  const mbgen::DataSet data = mbgen::read_data_file(argv[1]);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  rusage after{};
  getrusage(RUSAGE_SELF, &after);
  long values = 0;
  if (const auto* t = std::get_if<mbgen::TimeRecord>(&data.content))
    values = static_cast<long>(t->samples()) * static_cast<long>(t->signals.size() + 1);
  else
    for (const auto& c : std::get<mbgen::FrfData>(data.content).channels) values += 2 * static_cast<long>(c.values.size());
  const double peak = double(after.ru_maxrss - before.ru_maxrss) * 1024;  // ru_maxrss is in KiB
  std::printf("%ld values read in %.2f s; peak memory %.0f MB above the start, %.1f bytes per value\n", values,
              seconds, peak / 1e6, values ? peak / double(values) : 0.0);
  return 0;
}
