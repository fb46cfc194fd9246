// touchcloud stream PIPELINE [--frames N] [--set K=V]... [--seed N] [--out DIR] [--view [--port N]]
//
// The pipeline of `run`, its top-level loop driven frame after frame by its
// source (a camera_source's `done` for a recording) until the source ends,
// --frames N frames, or Ctrl-C, which ends the run as the source's end
// would: the outputs and summary.json are written and the status is 0.
// --view serves the live view (live_view.hpp) while it runs, and after the
// end until Ctrl-C.
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <deque>
#include <iomanip>
#include <iostream>
#include <mutex>

#include "live_view.hpp"

#include "progress_line.hpp"
#include "run_printout.hpp"
#include "seed_option.hpp"
#include "touchcloud/interrupt_cleanup.hpp"
#include "touchcloud/stream.hpp"
#include "verbs.hpp"

namespace touchcloud::cli {

Action* add_stream_verb(CLI::App& app) {
  struct Options {
    std::string pipeline;
    std::vector<std::string> sets;
    std::uint64_t seed = 0;
    std::string out;
    std::optional<std::int64_t> frames;
    bool quiet = false, progress = false, view = false;
    int port = 8765;
  };
  static Options o;
  static Action action;
  auto* cmd = app.add_subcommand(
      "stream", "Run a pipeline's per-frame loop on a camera or recording until it ends, --frames N or Ctrl-C; "
                "summary.json adds frame counts, latency percentiles and the rate");
  cmd->add_option("pipeline", o.pipeline, "pipeline YAML file with a top-level loop around its source")->required();
  cmd->add_option("--frames", o.frames, "stop after this many frames")->check(CLI::PositiveNumber);
  cmd->add_option("--set", o.sets, kSetHelp);
  cmd->add_option("--seed", o.seed, "seed for every random draw")->check(seed_value())->capture_default_str();
  cmd->add_option("--out", o.out, "output folder (default: out/<pipeline name>)");
  cmd->add_flag("-q,--quiet", o.quiet, "print no stage logs");
  cmd->add_flag("--progress", o.progress,
                "show frames, rate and drops also when stderr is not a terminal (logs, CI)");
  cmd->add_flag("--view", o.view,
                "serve a live view on 127.0.0.1 (camera image, depth, contact mask, cloud, rate, latency, drops) "
                "while the stream runs, and after its end until Ctrl-C");
  cmd->add_option("--port", o.port, "the live view's port (0: any free port; the URL is printed)")
      ->check(CLI::Range(0, 65535))
      ->capture_default_str();
  cmd->callback([] {
    action = [] {
      std::vector<Override> overrides;
      for (const auto& s : o.sets) overrides.push_back(parse_override(s));
      PluginRegistry registry;
      Pipeline p = Pipeline::load(o.pipeline, overrides, registry);
      std::atomic<bool> stop{false};
      RunOptions options;
      options.seed = o.seed;
      options.out_dir = output_folder(p, o.out);
      options.quiet = o.quiet;
      StreamOptions stream;
      stream.frames = o.frames;
      stream.stop = &stop;
      ProgressLine progress(0, "frames", o.progress);
      options.log_sink = [&progress](const std::string& line) {
        progress.print_above(line.substr(0, line.size() - (!line.empty() && line.back() == '\n')));
      };
      options.on_loop_iteration = [&progress](const std::string&, std::int64_t done, std::int64_t) {
        progress.set(static_cast<std::size_t>(done), 0, "frames");
      };
      std::unique_ptr<LiveView> view;
      if (o.view) {
        view = std::make_unique<LiveView>(o.port);
        stream.capture_types = live_view_types();
        std::cout << "live view: " << view->url() << std::endl;
      }
      LiveFrameReader reader;
      std::deque<std::chrono::steady_clock::time_point> recent;  // the last two seconds' frames
      // A source's frames_dropped (camera_source's), live; the view's figures.
      stream.on_frame = [&](std::int64_t frame, const std::map<std::string, std::any>& outputs,
                            const RunRecord& record) {
        const auto sum = [&](const std::string& suffix, bool& counted) {
          double total = 0;
          for (const auto& [key, series] : record.metrics)
            if (key.size() > suffix.size() && key.compare(key.size() - suffix.size(), suffix.size(), suffix) == 0)
              total += series.values.back(), counted = true;
          return total;
        };
        bool counted = false, refusing = false, timed = false;
        const double dropped = sum(".frames_dropped", counted);
        if (counted) progress.stage(std::to_string(static_cast<long long>(dropped)) + " dropped");
        if (!view) return;
        const auto now = std::chrono::steady_clock::now();
        recent.push_back(now);
        while (now - recent.front() > std::chrono::seconds(2)) recent.pop_front();
        LiveFigures f;
        f.frame = frame + 1;
        f.dropped = static_cast<std::int64_t>(dropped);
        f.refused = static_cast<std::int64_t>(sum(".pairs_refused", refusing));
        f.latency_ms = sum(".latency_ms", timed);
        if (!timed) f.latency_ms = -1;
        const double span_s = std::chrono::duration<double>(recent.back() - recent.front()).count();
        f.rate_fps = recent.size() > 1 && span_s > 0 ? static_cast<double>(recent.size() - 1) / span_s : 0.0;
        view->show(reader.read(outputs), f);
      };
      // Ctrl-C ends the stream after the frame in hand; a second one ends
      // the process at once (nothing written).
      stop_on_interrupt([&stop] { stop = true; });
      RunResult r;
      try {
        r = stream_pipeline(p, options, stream);
      } catch (...) {
        stop_on_interrupt({});
        throw;
      }
      stop_on_interrupt({});
      progress.finish();
      // A stream that ended by itself keeps its last frame on view until Ctrl-C.
      if (view && !stop) {
        std::mutex m;
        std::condition_variable closed;
        bool interrupted = false;
        stop_on_interrupt([&] {
          std::lock_guard lock(m);
          interrupted = true;
          closed.notify_all();
        });
        view->ended();
        std::cout << "the stream has ended; the live view stays at " << view->url() << " until Ctrl-C" << std::endl;
        std::unique_lock lock(m);
        closed.wait(lock, [&] { return interrupted; });
        stop_on_interrupt({});
      }
      view.reset();
      std::int64_t frames = 0;
      for (const auto& [loop, n] : r.loop_iterations) frames = std::max<std::int64_t>(frames, n);
      std::cout << "pipeline '" << p.name() << "' streamed " << frames << " frames in " << std::fixed
                << std::setprecision(3) << r.wall_time_s << " s"
                << (stop ? " (stopped by Ctrl-C)" : o.frames && frames == *o.frames ? " (--frames)" : " (end of source)")
                << "\n";
      print_metrics_and_files(r, options.out_dir);
      return kExitOk;
    };
  });
  return &action;
}

}  // namespace touchcloud::cli
