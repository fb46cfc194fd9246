// A network's training loop, whatever the network: the learning-rate
// schedule (constant, then halved at a fixed period: the GS-DepthNet paper's), shuffled
// batches from the stage's seeded generator, one record per epoch with the
// loss terms and validation metrics, and the training curve (CSV + PNG).
// Torch-free: the network's own code supplies one epoch as a function.
#pragma once

#include <cstdint>
#include <functional>
#include <random>
#include <string>
#include <utility>
#include <vector>

namespace touchcloud::learning {

struct LearningRateSchedule {
  double initial = 1e-4;
  int constant_epochs = 30;  // epochs at the initial rate
  int halve_every = 10;      // then halved every this many epochs
  // The rate of epoch `epoch` (from 0).
  double rate(int epoch) const;
};

// Sample indices 0..n-1 shuffled by `rng`, cut into batches of `batch_size`
// (the last one shorter when n is not a multiple).
std::vector<std::vector<std::int64_t>> shuffled_batches(std::int64_t n, std::int64_t batch_size, std::mt19937_64& rng);

struct EpochRecord {
  int epoch = 0;  // from 0
  double learning_rate = 0;
  double seconds = 0;
  std::vector<std::pair<std::string, double>> values;  // loss terms and metrics, in a fixed order
  double value(const std::string& name) const;         // NaN when absent
};

// The log line of an epoch: "epoch 3/20: loss 0.123, ..., lr 0.001, 41.2 s"
// (values to 5 decimals, seconds to 0.1).
std::string epoch_line(const EpochRecord& record, int epochs);

struct TrainingLoop {
  LearningRateSchedule schedule;
  int first_epoch = 0;  // > 0 when resuming
  int epochs = 1;       // the last epoch is epochs - 1
  // Runs one epoch at a learning rate and returns its record's values.
  std::function<std::vector<std::pair<std::string, double>>(int epoch, double learning_rate)> run_epoch;
  // After each epoch (progress, checkpoint).
  std::function<void(const EpochRecord&)> after_epoch;

  std::vector<EpochRecord> run() const;
};

// epoch,learning_rate,seconds,<value names...>: one line per record.
std::string curve_csv(const std::vector<EpochRecord>& records);
// A PNG plot of `names` (log scale) against the epoch; RunError when OpenCV
// cannot encode it.
std::string curve_png(const std::vector<EpochRecord>& records, const std::vector<std::string>& names);

}  // namespace touchcloud::learning
