#include "touchcloud/imaging/mask_blobs.hpp"

#include <algorithm>
#include <cstdint>

namespace touchcloud::imaging {

int MaskBlobs::root(int run) {
  while (parent_[run] != run) {
    parent_[run] = parent_[parent_[run]];  // path halving
    run = parent_[run];
  }
  return run;
}

namespace {

// The first pixel at or after `from` whose bit is `set`, or `cols`.
int next_pixel(const std::vector<std::uint64_t>& bits, int from, bool set, int cols) {
  std::size_t k = static_cast<std::size_t>(from / 64);
  if (k >= bits.size()) return cols;
  std::uint64_t word = (set ? bits[k] : ~bits[k]) & (~std::uint64_t{0} << (from % 64));
  while (word == 0) {
    if (++k == bits.size()) return cols;
    word = set ? bits[k] : ~bits[k];
  }
  return std::min(cols, static_cast<int>(k * 64) + __builtin_ctzll(word));
}

}  // namespace

void MaskBlobs::find(int rows, int cols, const std::function<void(int, RowBits&)>& row_bits) {
  runs_.clear();
  parent_.clear();
  blobs_.clear();
  int previous_begin = 0, previous_end = 0;  // the previous row's runs
  for (int y = 0; y < rows; ++y) {
    bits_.assign(static_cast<std::size_t>((cols + 63) / 64), 0);
    row_bits(y, bits_);
    const int row_begin = static_cast<int>(runs_.size());
    int above = previous_begin;  // the first run above that a run from here on can touch
    for (int begin = next_pixel(bits_, 0, true, cols); begin < cols;
         begin = next_pixel(bits_, begin, true, cols)) {
      const int end = next_pixel(bits_, begin, false, cols);
      const int id = static_cast<int>(runs_.size());
      runs_.push_back({y, begin, end});
      parent_.push_back(id);
      // 8-connected: a run of the row above touches when it reaches within a pixel.
      while (above < previous_end && runs_[above].x_end < begin) ++above;
      for (int p = above; p < previous_end && runs_[p].x_begin <= end; ++p) {
        const int a = root(p), b = root(id);
        if (a != b) parent_[std::max(a, b)] = std::min(a, b);  // the earlier run stays root
      }
      begin = end;
    }
    previous_begin = row_begin;
    previous_end = static_cast<int>(runs_.size());
  }

  // Blobs in order of their first run; roots are always earlier runs.
  run_blob_.assign(runs_.size(), 0);
  for (int r = 0; r < static_cast<int>(runs_.size()); ++r) {
    const int top = root(r);
    const Run& run = runs_[r];
    const cv::Rect span(run.x_begin, run.y, run.x_end - run.x_begin, 1);
    if (top == r) {
      run_blob_[r] = static_cast<int>(blobs_.size());
      blobs_.push_back({span, 0});
    } else {
      run_blob_[r] = run_blob_[top];
      blobs_[run_blob_[r]].box |= span;
    }
    blobs_[run_blob_[r]].area += span.width;
  }
}

}  // namespace touchcloud::imaging
