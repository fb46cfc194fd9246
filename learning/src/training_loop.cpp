#include "touchcloud/learning/training_loop.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numeric>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "touchcloud/error.hpp"
#include "touchcloud/number_text.hpp"

namespace touchcloud::learning {

double LearningRateSchedule::rate(int epoch) const {
  if (epoch < constant_epochs || halve_every <= 0) return initial;
  return initial * std::pow(0.5, (epoch - constant_epochs) / halve_every + 1);
}

std::vector<std::vector<std::int64_t>> shuffled_batches(std::int64_t n, std::int64_t batch_size, std::mt19937_64& rng) {
  std::vector<std::int64_t> order(static_cast<std::size_t>(n));
  std::iota(order.begin(), order.end(), std::int64_t{0});
  // Fisher-Yates with the generator's raw draws (std::shuffle's use of the
  // generator differs between standard libraries).
  for (std::int64_t i = n - 1; i > 0; --i) std::swap(order[i], order[rng() % static_cast<std::uint64_t>(i + 1)]);
  std::vector<std::vector<std::int64_t>> batches;
  for (std::int64_t start = 0; start < n; start += batch_size)
    batches.emplace_back(order.begin() + start, order.begin() + std::min(n, start + batch_size));
  return batches;
}

double EpochRecord::value(const std::string& name) const {
  for (const auto& [n, v] : values)
    if (n == name) return v;
  return std::numeric_limits<double>::quiet_NaN();
}

std::vector<EpochRecord> TrainingLoop::run() const {
  std::vector<EpochRecord> records;
  for (int epoch = first_epoch; epoch < epochs; ++epoch) {
    EpochRecord r;
    r.epoch = epoch;
    r.learning_rate = schedule.rate(epoch);
    const auto start = std::chrono::steady_clock::now();
    r.values = run_epoch(epoch, r.learning_rate);
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    for (const auto& [name, v] : r.values)
      if (!std::isfinite(v))
        throw RunError("training diverged: '" + name + "' is " + std::to_string(v) + " in epoch " +
                       std::to_string(epoch + 1) + " (learning rate " + number_text(r.learning_rate) + ")");
    records.push_back(r);
    if (after_epoch) after_epoch(r);
  }
  return records;
}

std::string curve_csv(const std::vector<EpochRecord>& records) {
  std::string text = "epoch,learning_rate,seconds";
  if (!records.empty())
    for (const auto& [name, v] : records.front().values) text += "," + name;
  text += "\n";
  for (const auto& r : records) {
    text += std::to_string(r.epoch + 1) + "," + number_text(r.learning_rate) + "," + number_text(r.seconds);
    for (const auto& [name, v] : r.values) text += "," + number_text(v);
    text += "\n";
  }
  return text;
}

std::string curve_png(const std::vector<EpochRecord>& records, const std::vector<std::string>& names) {
  const int w = 800, h = 500, left = 70, right = 180, top = 20, bottom = 50;
  cv::Mat plot(h, w, CV_8UC3, cv::Scalar(255, 255, 255));
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const auto& r : records)
    for (const auto& n : names) {
      const double v = r.value(n);
      if (std::isfinite(v) && v > 0) lo = std::min(lo, std::log10(v)), hi = std::max(hi, std::log10(v));
    }
  if (!std::isfinite(lo)) lo = -1, hi = 0;
  if (hi - lo < 1e-6) lo -= 0.5, hi += 0.5;
  const int first = records.empty() ? 0 : records.front().epoch, last = records.empty() ? 1 : records.back().epoch;
  auto px = [&](int epoch, double log_v) {
    const double fx = last > first ? double(epoch - first) / (last - first) : 0.5;
    return cv::Point(left + int(fx * (w - left - right)), top + int((hi - log_v) / (hi - lo) * (h - top - bottom)));
  };
  cv::rectangle(plot, {left, top}, {w - right, h - bottom}, cv::Scalar(0, 0, 0));
  cv::putText(plot, "epoch " + std::to_string(first + 1) + ".." + std::to_string(last + 1), {left, h - 15},
              cv::FONT_HERSHEY_SIMPLEX, 0.5, cv::Scalar(0, 0, 0));
  cv::putText(plot, "1e" + number_text(std::round(hi * 100) / 100), {5, top + 10}, cv::FONT_HERSHEY_SIMPLEX, 0.4, cv::Scalar(0, 0, 0));
  cv::putText(plot, "1e" + number_text(std::round(lo * 100) / 100), {5, h - bottom}, cv::FONT_HERSHEY_SIMPLEX, 0.4, cv::Scalar(0, 0, 0));
  const cv::Scalar colours[] = {{200, 0, 0}, {0, 150, 0}, {0, 0, 220}, {180, 0, 180}, {0, 150, 180}, {100, 100, 100}};
  for (std::size_t k = 0; k < names.size(); ++k) {
    const cv::Scalar colour = colours[k % 6];
    cv::putText(plot, names[k], {w - right + 10, top + 20 + 20 * int(k)}, cv::FONT_HERSHEY_SIMPLEX, 0.5, colour);
    for (std::size_t i = 1; i < records.size(); ++i) {
      const double a = records[i - 1].value(names[k]), b = records[i].value(names[k]);
      if (a > 0 && b > 0) cv::line(plot, px(records[i - 1].epoch, std::log10(a)), px(records[i].epoch, std::log10(b)), colour, 2);
    }
  }
  std::vector<std::uint8_t> bytes;
  if (!cv::imencode(".png", plot, bytes)) throw RunError("OpenCV could not encode the training curve as PNG");
  return std::string(bytes.begin(), bytes.end());
}

std::string epoch_line(const EpochRecord& r, int epochs) {
  std::string line = "epoch " + std::to_string(r.epoch + 1) + "/" + std::to_string(epochs) + ": ";
  for (const auto& [name, v] : r.values) line += name + " " + number_text(std::round(v * 1e5) / 1e5) + ", ";
  return line + "lr " + number_text(r.learning_rate) + ", " + number_text(std::round(r.seconds * 10) / 10) + " s";
}

}  // namespace touchcloud::learning
