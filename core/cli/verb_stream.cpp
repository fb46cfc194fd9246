// touchcloud stream PIPELINE [--frames N] [--set K=V]... [--seed N] [--out DIR]
//
// The pipeline of `run`, its top-level loop driven frame after frame by its
// source (a camera_source's `done` for a recording) until the source ends,
// --frames N frames, or Ctrl-C, which ends the run as the source's end
// would: the outputs and summary.json are written and the status is 0.
#include <atomic>
#include <iomanip>
#include <iostream>

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
    bool quiet = false, progress = false;
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
      // A source's frames_dropped (camera_source's), live.
      stream.on_frame = [&progress](std::int64_t, const std::map<std::string, std::any>&, const RunRecord& record) {
        double dropped = 0;
        bool counted = false;
        for (const auto& [key, series] : record.metrics)
          if (key.size() > 15 && key.compare(key.size() - 15, 15, ".frames_dropped") == 0)
            dropped += series.values.back(), counted = true;
        if (counted) progress.stage(std::to_string(static_cast<long long>(dropped)) + " dropped");
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
