// Marker detection on rendered 1280 x 720 GelStereo images (fox mask scene:
// contact, refraction, pixel noise of 2 grey levels, blur of 0.9 px; the gel
// at rest and pressed 3 mm), on one core: touchcloud's detector against
// OpenCV's SimpleBlobDetector set up for dark dots of that size. Time is per
// image; counters give each method's recall (of markers whose dot lies fully
// in the image), mean centre error and false detections over all four images.
//
//   Detector            one image, touchcloud_marker_detection_lib
//   SimpleBlobDetector  one image, cv::SimpleBlobDetector
//   DetectorStereoFrame both images of a frame, input checks included
//
// Run: build/benchmarks/bin/bench_marker_detection
#include <benchmark/benchmark.h>
#include <opencv2/core.hpp>
#include <opencv2/features2d.hpp>

#include "detector/stereo_markers.hpp"
#include "rendered_markers.hpp"

using namespace touchcloud;
using touchcloud::test::DetectionScore;

namespace {

struct Image {
  const cv::Mat* pixels;
  const touch_simulator::ViewPixels* truth;
};

const std::vector<test::RenderedFrame>& frames() {
  static const std::vector<test::RenderedFrame> f = test::rendered_fox_frames();
  return f;
}

std::vector<Image> images() {
  std::vector<Image> out;
  for (const auto& f : frames()) {
    out.push_back({&f.frame.left, &f.truth.left});
    out.push_back({&f.frame.right, &f.truth.right});
  }
  return out;
}

void report(benchmark::State& state, const DetectionScore& s, double markers_per_image) {
  state.counters["recall"] = s.recall();
  state.counters["mean_error_px"] = s.mean_error_px;
  state.counters["max_error_px"] = s.max_error_px;
  state.counters["false"] = s.false_detections;
  state.counters["markers"] = markers_per_image;
}

template <class Detect>
void run(benchmark::State& state, Detect detect) {
  const auto all = images();
  std::size_t i = 0;
  for (auto _ : state) {
    const Image& image = all[i++ % all.size()];
    auto found = detect(*image.pixels);
    benchmark::DoNotOptimize(found.data());
  }
  DetectionScore total;
  double markers = 0;
  for (const Image& image : all) {
    const auto found = detect(*image.pixels);
    markers += static_cast<double>(found.size()) / all.size();
    total = test::combine(total, test::score_detections(found, *image.truth, image.pixels->size()));
  }
  report(state, total, markers);
}

void Detector(benchmark::State& state) {
  MarkerDetector detector{MarkerDetectorOptions{}};
  run(state, [&](const cv::Mat& image) { return detector.detect(image); });
}

// Dark dots of 5-8 px on a background of 125-210 grey levels: thresholds
// between the dots' cores (~40) and the darkest background, and shape filters
// that pass a round dot.
cv::Ptr<cv::SimpleBlobDetector> simple_blob_detector() {
  cv::SimpleBlobDetector::Params p;
  p.minThreshold = 60;
  p.maxThreshold = 120;
  p.thresholdStep = 10;
  p.minRepeatability = 2;
  p.minDistBetweenBlobs = 3;
  p.filterByColor = true;
  p.blobColor = 0;
  p.filterByArea = true;
  p.minArea = 4;
  p.maxArea = static_cast<float>(M_PI / 4 * 14 * 14);
  p.filterByCircularity = true;
  p.minCircularity = 0.6f;
  p.filterByInertia = true;
  p.minInertiaRatio = 0.3f;
  p.filterByConvexity = true;
  p.minConvexity = 0.8f;
  return cv::SimpleBlobDetector::create(p);
}

void SimpleBlobDetector(benchmark::State& state) {
  auto detector = simple_blob_detector();
  run(state, [&](const cv::Mat& image) {
    std::vector<cv::KeyPoint> keypoints;
    detector->detect(image, keypoints);
    std::vector<Eigen::Vector2d> centres;
    centres.reserve(keypoints.size());
    for (const auto& k : keypoints) centres.emplace_back(k.pt.x, k.pt.y);
    return centres;
  });
}

void DetectorStereoFrame(benchmark::State& state) {
  StereoMarkerDetector detector{MarkerDetectorOptions{}};
  std::vector<StereoFramePtr> stereo;
  for (const auto& f : frames()) stereo.push_back(std::make_shared<const touchcloud::StereoFrame>(f.frame));
  std::size_t i = 0;
  for (auto _ : state) {
    const MarkerSet set = detector.detect(stereo[i++ % stereo.size()]);
    benchmark::DoNotOptimize(set.left.data());
  }
  state.counters["fps"] = benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}

}  // namespace

BENCHMARK(Detector)->Unit(benchmark::kMillisecond);
BENCHMARK(SimpleBlobDetector)->Unit(benchmark::kMillisecond);
BENCHMARK(DetectorStereoFrame)->Unit(benchmark::kMillisecond);
