// touchcloud.stream(...): a pipeline's per-frame loop run on its own thread
// (as `touchcloud stream` runs it), each frame's outputs handed to Python as
// they come. The run waits while Python has two frames it has not taken, so
// a slow consumer holds the pipeline back (a camera source then counts the
// frames it drops); leaving the loop early stops the run.
#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <deque>
#include <mutex>
#include <thread>

#include <pybind11/stl.h>

#include "bindings.hpp"
#include "touchcloud/stream.hpp"
#include "touchcloud/thread_end.hpp"
#include "touchcloud/types/frame_stamp.hpp"
#include "value_arrays.hpp"

namespace py = pybind11;

namespace touchcloud::python {

namespace {

class Stream {
 public:
  Stream(const std::string& file, std::optional<std::int64_t> frames, std::uint64_t seed, const py::dict& set,
         const std::optional<std::string>& out, const std::optional<std::vector<std::string>>& outputs, bool quiet)
      : pipeline_(load_pipeline(file, set, std::nullopt)), out_(out), outputs_asked_(outputs.has_value()) {
    if (frames && *frames < 1) throw py::value_error("frames must be at least 1");
    if (!out) throw py::value_error("stream needs out: the folder its outputs and summary.json go to");
    options_.seed = seed;
    options_.quiet = quiet;
    options_.capture = outputs ? *outputs : pipeline_.wired_outputs();
    options_.out_dir = *out;
    stream_.frames = frames;
    stream_.stop = &stop_;
    stream_.capture_types = {"frame_stamp"};
    stream_.on_frame = [this](std::int64_t iteration, const std::map<std::string, std::any>& values, const RunRecord&) {
      std::unique_lock lock(mutex_);
      changed_.wait(lock, [&] { return stop_ || frames_.size() < 2; });
      if (stop_) return;
      frames_.push_back({iteration, values});
      changed_.notify_all();
    };
    thread_ = std::thread([this] {
      run_to_end(
          [this] {
            RunResult r = stream_pipeline(pipeline_, options_, stream_);
            std::lock_guard lock(mutex_);
            result_ = std::move(r);
          },
          mutex_, changed_, error_, ended_);
    });
  }
  ~Stream() { close(); }

  // The next frame: {'iteration', 'stamp', 'outputs'}; StopIteration at the
  // end, the run's Result then in `result`.
  py::dict next() {
    std::pair<std::int64_t, std::map<std::string, std::any>> frame;
    {
      py::gil_scoped_release unlocked;
      std::unique_lock lock(mutex_);
      changed_.wait(lock, [&] { return !frames_.empty() || ended_; });
      if (frames_.empty()) {
        lock.unlock();
        finish();
      }
      frame = std::move(frames_.front());
      frames_.pop_front();
      changed_.notify_all();
    }
    py::dict outputs;
    py::object stamp = py::none();
    for (const auto& [key, value] : frame.second) {
      if (stamp.is_none() && value.type() == typeid(FrameStamp)) stamp = to_python(key, value);
      const bool asked = std::find(options_.capture.begin(), options_.capture.end(), key) != options_.capture.end();
      if (!asked) continue;  // a stamp the stream added
      try {
        outputs[py::str(key)] = to_python(key, value);
      } catch (const py::type_error&) {
        if (outputs_asked_) throw;
      }
    }
    return py::dict(py::arg("iteration") = frame.first, py::arg("stamp") = stamp, py::arg("outputs") = outputs);
  }

  // Stops the run after the frame in hand and waits for it (the GIL held).
  void close() {
    {
      std::lock_guard lock(mutex_);
      stop_ = true;
      changed_.notify_all();
    }
    if (thread_.joinable()) {
      py::gil_scoped_release unlocked;
      thread_.join();
    }
    if (result_py_.is_none() && result_) result_py_ = py::cast(make_result(*result_, outputs_asked_, out_));
  }

  py::object result() const { return result_py_; }

 private:
  // The run has ended and every frame was taken: the error, or StopIteration.
  [[noreturn]] void finish() {
    {
      py::gil_scoped_acquire locked;
      close();
      if (error_) std::rethrow_exception(error_);
    }
    throw py::stop_iteration();
  }

  Pipeline pipeline_;
  RunOptions options_;
  StreamOptions stream_;
  std::optional<std::string> out_;
  bool outputs_asked_;
  std::atomic<bool> stop_{false};
  std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<std::pair<std::int64_t, std::map<std::string, std::any>>> frames_;
  bool ended_ = false;
  std::optional<RunResult> result_;
  std::exception_ptr error_;
  py::object result_py_ = py::none();
  std::thread thread_;
};

}  // namespace

void bind_stream(py::module_& m) {
  py::class_<Stream>(m, "Stream", "A pipeline streaming frame after frame: iterate for each frame's outputs")
      .def("__iter__", [](Stream& s) -> Stream& { return s; })
      .def("__next__", &Stream::next)
      .def("close", &Stream::close, "Stops the run after the frame in hand (as Ctrl-C does to touchcloud stream)")
      .def("__enter__", [](Stream& s) -> Stream& { return s; })
      .def("__exit__", [](Stream& s, py::args) { s.close(); })
      .def_property_readonly("result", &Stream::result,
                             "the run's Result once the stream has ended (None before)");
  m.def(
      "stream",
      [](const std::string& file, std::optional<std::int64_t> frames, std::uint64_t seed, const py::dict& set,
         const std::optional<std::string>& out, const std::optional<std::vector<std::string>>& outputs, bool quiet) {
        return std::make_unique<Stream>(file, frames, seed, set, out, outputs, quiet);
      },
      py::arg("pipeline"), py::kw_only(), py::arg("frames") = py::none(), py::arg("seed") = 0,
      py::arg("set") = py::dict(), py::arg("out") = py::none(), py::arg("outputs") = py::none(),
      py::arg("quiet") = true,
      "Streams a pipeline as `touchcloud stream` does, yielding each frame as {'iteration', 'stamp', 'outputs'}: "
      "stamp the frame's {'sequence', 'timestamp_s'}, outputs 'stage.port' -> NumPy arrays (images, maps, clouds). "
      "frames: stop after this many; out: the output folder (required); outputs: the 'stage.port' names to hand "
      "back (None: every output some stage reads). Leaving the loop early, or close(), stops the run; `result` then "
      "holds its Result.");
}

}  // namespace touchcloud::python
