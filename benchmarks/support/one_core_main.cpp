// main() of the benchmarks that use OpenCV: its thread pool is held to one
// thread, so what is measured is one core's work.
#include <benchmark/benchmark.h>
#include <opencv2/core/utility.hpp>

int main(int argc, char** argv) {
  cv::setNumThreads(1);
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
