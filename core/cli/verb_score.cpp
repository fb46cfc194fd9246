// touchcloud score --gt GT EST... [--json]: scores reconstructions against
// ground truth (a CAD mesh, sampled, or a cloud).
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <chrono>
#include <condition_variable>
#include <cstdlib>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <map>
#include <mutex>
#include <optional>
#include <sstream>
#include <thread>

#include <nlohmann/json.hpp>

#include "mpi_dispatch.hpp"
#include "progress_line.hpp"
#include "score_inputs.hpp"
#include "touchcloud/scoring/cloud_metrics.hpp"
#include "touchcloud/scoring/ground_truth.hpp"
#include "seed_option.hpp"
#include "touchcloud/number_text.hpp"
#include "verbs.hpp"

namespace fs = std::filesystem;

namespace touchcloud::cli {

namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

struct GroundTruthSummary {
  std::string file;
  std::string kind;
  std::size_t points = 0, triangles = 0, dropped_nonfinite = 0;
  std::size_t hidden_points = 0;  // samples not visible (--visible from_above)
  std::size_t seen_points = 0;    // of a mesh scored whole, the samples a press from above sees; 0: all or none
  double area_mm2 = 0, spacing_mm = 0, load_time_s = 0;
  std::string error;  // when it could not be loaded
};

struct Outcome {
  ScorePair pair;
  const GroundTruthSummary* gt = nullptr;
  std::optional<scoring::CloudScore> score;
  std::size_t dropped_nonfinite = 0;
  double time_s = 0;
  std::string error;
  bool bad_input = true;  // an InputError (exit 2), or a failure while scoring (exit 1)
  RunPlace place;         // who scored it
};

struct Options {
  std::string gt;
  std::vector<std::string> estimates;
  bool json = false;
  std::size_t samples = 0;
  std::uint64_t seed = 0;
  std::vector<std::string> metrics{"all"};
  double fscore_threshold_mm = scoring::kDefaultFscoreThresholdMm;
  int threads = 0;
  bool drop_nonfinite = false;
  bool progress = false;
  bool dry_run = false;
  scoring::Visibility visible = scoring::Visibility::all;
};

NonFinitePoints nonfinite_rule(const Options& o) {
  return o.drop_nonfinite ? NonFinitePoints::Drop : NonFinitePoints::Refuse;
}

// Loads one ground truth; its summary keeps what the report shows.
scoring::GroundTruth load(const std::string& file, const Options& o, int threads, GroundTruthSummary& summary) {
  const auto t0 = Clock::now();
  summary.file = file;
  scoring::GroundTruthOptions options;
  options.mesh_samples = o.samples;
  options.seed = o.seed;
  options.nonfinite = nonfinite_rule(o);
  options.threads = threads;
  options.visible = o.visible;
  options.flag_seen_from_above = scoring::MetricSelection::parse(o.metrics).fscore;  // for visible recall
  scoring::GroundTruthFile read = scoring::read_ground_truth(file, options);
  // A mesh in metres scores as a speck: every distance would be the object's size.
  if (read.kind == scoring::GroundTruthKind::Mesh)
    if (auto why = scoring::unit_mistake(read.mesh))
      throw InputError(file + ": " + *why + " Ground truth is in mm: scale the mesh, or make a scene of it "
                       "(touchcloud-make-scene MESH --scale S) and give that to --gt");
  scoring::GroundTruth gt = scoring::index_ground_truth(std::move(read), options);
  summary.seen_points = static_cast<std::size_t>(std::count(gt.seen_from_above.begin(), gt.seen_from_above.end(), true));
  summary.kind = scoring::to_string(gt.kind);
  summary.points = gt.points.size();
  summary.triangles = gt.triangles;
  summary.area_mm2 = gt.area_mm2;
  summary.spacing_mm = gt.sample_spacing_mm();
  summary.dropped_nonfinite = gt.dropped_nonfinite;
  summary.hidden_points = gt.hidden_points;
  summary.load_time_s = seconds_since(t0);
  return gt;
}

void score_one(Outcome& out, const scoring::GroundTruth& gt, scoring::ScoreOptions options, const Options& o) {
  const auto t0 = Clock::now();
  if (!gt.seen_from_above.empty()) options.seen_from_above = &gt.seen_from_above;
  try {
    scoring::Estimate est = scoring::read_estimate(out.pair.estimate, nonfinite_rule(o));
    out.dropped_nonfinite = est.dropped_nonfinite;
    out.score = scoring::score_estimate(est.points, gt.points, options);
  } catch (const InputError& e) {
    out.error = e.what();
  } catch (const std::exception& e) {
    out.error = out.pair.estimate + ": " + e.what();
    out.bad_input = false;
  }
  out.time_s = seconds_since(t0);
}

// Scores every outcome in `group` against one ground truth: several estimates
// at once when there are enough of them, else all threads on each one.
void score_group(std::vector<Outcome*>& group, const scoring::GroundTruth& gt, scoring::ScoreOptions options,
                 const Options& o, int threads, ProgressLine& progress) {
  const int workers = static_cast<int>(std::min<std::size_t>(threads, group.size()));
  options.threads = std::max(1, threads / workers);
  std::atomic<std::size_t> next{0};
  const auto work = [&] {
    for (std::size_t i; (i = next++) < group.size();) {
      score_one(*group[i], gt, options, o);
      progress.done_one();
    }
  };
  std::vector<std::thread> pool;
  for (int w = 1; w < workers; ++w) pool.emplace_back(work);
  work();
  for (auto& t : pool) t.join();
}

std::string format_fixed(double v, int digits) {
  std::ostringstream s;
  s << std::fixed << std::setprecision(digits) << v;
  return s.str();
}

nlohmann::ordered_json gt_json(const GroundTruthSummary& g, const Options& o) {
  nlohmann::ordered_json j = {{"file", g.file}};
  if (!g.error.empty()) return j;
  j["kind"] = g.kind;
  j["points"] = g.points;
  if (g.kind == "mesh") {
    j["triangles"] = g.triangles;
    j["area_mm2"] = g.area_mm2;
    j["sample_spacing_mm"] = g.spacing_mm;
    j["seed"] = o.seed;
    j["visible"] = scoring::to_string(o.visible);
    if (o.visible != scoring::Visibility::all) j["hidden_points"] = g.hidden_points;
    if (g.seen_points > 0) j["seen_from_above_points"] = g.seen_points;
  } else if (g.dropped_nonfinite > 0) {
    j["dropped_nonfinite"] = g.dropped_nonfinite;
  }
  j["load_time_s"] = g.load_time_s;
  return j;
}

nlohmann::ordered_json outcome_json(const Outcome& r, const Options& o) {
  nlohmann::ordered_json j = {{"estimate", r.pair.estimate}};
  j["ground_truth"] = r.gt ? gt_json(*r.gt, o) : nlohmann::ordered_json{{"file", r.pair.ground_truth}};
  if (!r.score) {
    j["status"] = "error";
    j["error"] = r.error;
    if (r.gt) {  // it got as far as a rank
      j["rank"] = r.place.rank;
      j["host"] = r.place.host;
    }
    return j;
  }
  j["status"] = "ok";
  j["estimate_points"] = r.score->estimate_points;
  if (r.dropped_nonfinite > 0) j["dropped_nonfinite"] = r.dropped_nonfinite;
  nlohmann::ordered_json metrics = nlohmann::ordered_json::object();
  for (const auto& m : r.score->to_score().metrics) metrics[m.name + (m.unit.empty() ? "" : "_" + m.unit)] = m.value;
  j["metrics"] = metrics;
  if (r.score->metrics.fscore) j["fscore_threshold_mm"] = r.score->fscore_threshold_mm;
  j["time_s"] = r.time_s;
  j["rank"] = r.place.rank;
  j["host"] = r.place.host;
  return j;
}


void print_table(const std::vector<Outcome>& outcomes, const std::vector<const GroundTruthSummary*>& gts,
                 const Options& o, const scoring::ScoreOptions& options) {
  for (const auto* g : gts) {
    if (!g->error.empty()) continue;
    std::cout << "# ground truth " << g->file << ": " << g->kind << ", " << g->points << " points";
    if (g->kind == "mesh")
      std::cout << " sampled from " << format_fixed(g->area_mm2, 1) << " mm^2 (mean spacing "
                << format_fixed(g->spacing_mm, 3) << " mm, seed " << o.seed << ")"
                << (o.visible == scoring::Visibility::from_above
                        ? ", visible from above only (" + std::to_string(g->hidden_points) + " hidden samples left out)"
                        : ", the whole surface" +
                              (g->seen_points > 0 ? " (" + std::to_string(g->seen_points) +
                                                        " samples seen from above: visible recall)"
                                                  : std::string()));
    std::cout << "\n";
  }
  std::size_t name_width = 8, gt_width = 12;
  for (const auto& r : outcomes) {
    name_width = std::max(name_width, r.pair.estimate.size());
    gt_width = std::max(gt_width, r.pair.ground_truth.size());
  }
  const bool show_gt = gts.size() > 1;

  // Column titles from a score with every selected metric.
  scoring::CloudScore shape;
  shape.metrics = options.metrics;
  std::vector<std::string> titles;
  for (const auto& m : scoring::metric_names())
    if (shape.metrics.*m.selected)
      titles.push_back(m.value == &scoring::CloudScore::fscore
                           ? "F@" + format_fixed(options.fscore_threshold_mm, 2) + "mm" : m.column);
  const bool any_visible = std::any_of(outcomes.begin(), outcomes.end(),
                                       [](const Outcome& r) { return r.score && r.score->visible_recall; });
  if (any_visible) titles.push_back("visible rec");
  std::cout << std::left << std::setw(static_cast<int>(name_width)) << "estimate";
  if (show_gt) std::cout << "  " << std::setw(static_cast<int>(gt_width)) << "ground truth";
  std::cout << std::right << std::setw(10) << "points";
  for (const auto& t : titles) std::cout << std::setw(14) << t;
  std::cout << "\n";

  for (const auto& r : outcomes) {
    std::cout << std::left << std::setw(static_cast<int>(name_width)) << r.pair.estimate;
    if (show_gt) std::cout << "  " << std::setw(static_cast<int>(gt_width)) << r.pair.ground_truth;
    if (!r.score) {
      std::cout << "  error: " << r.error << "\n";
      continue;
    }
    std::cout << std::right << std::setw(10) << r.score->estimate_points;
    for (const auto& m : r.score->to_score().metrics) std::cout << std::setw(14) << format_fixed(m.value, 3);
    if (any_visible && !r.score->visible_recall) std::cout << std::setw(14) << "-";
    std::cout << "\n";
  }
}

// Across the ranks of an MPI job: one estimate a job, in ground-truth order,
// so that each rank samples and indexes a ground truth once for its run of
// estimates of it, and reads its estimates itself (only scores travel).
// Each rank's threads share the host's cores with the other ranks there.
nlohmann::json encode(const Outcome& r, const GroundTruthSummary& g) {
  const auto num = [](double v) { return number_text(v); };  // every bit, NaN too
  nlohmann::json j = {{"error", r.error}, {"bad_input", r.bad_input}, {"dropped", r.dropped_nonfinite},
                      {"time", num(r.time_s)}};
  j["gt"] = {{"file", g.file},       {"kind", g.kind},          {"points", g.points},
             {"triangles", g.triangles}, {"dropped", g.dropped_nonfinite}, {"area", num(g.area_mm2)},
             {"spacing", num(g.spacing_mm)}, {"load_time", num(g.load_time_s)}, {"error", g.error},
             {"hidden", g.hidden_points}, {"seen", g.seen_points}};
  if (r.score) {
    nlohmann::json s = {{"estimate_points", r.score->estimate_points},
                        {"ground_truth_points", r.score->ground_truth_points},
                        {"fscore_threshold_mm", num(r.score->fscore_threshold_mm)}};
    for (const auto& m : scoring::metric_names()) s[m.name] = num((*r.score).*m.value);
    if (r.score->visible_recall) s["visible_recall"] = num(*r.score->visible_recall);
    j["score"] = s;
  }
  return j;
}

void decode(const nlohmann::json& j, Outcome& r, GroundTruthSummary& g, const scoring::ScoreOptions& options) {
  const auto num = [](const nlohmann::json& v) { return std::strtod(v.get<std::string>().c_str(), nullptr); };
  r.error = j.at("error").get<std::string>();
  r.bad_input = j.at("bad_input").get<bool>();
  r.dropped_nonfinite = j.at("dropped").get<std::size_t>();
  r.time_s = num(j.at("time"));
  if (g.file.empty()) {  // the first report of this ground truth
    const auto& t = j.at("gt");
    g.file = t.at("file").get<std::string>();
    g.kind = t.at("kind").get<std::string>();
    g.points = t.at("points").get<std::size_t>();
    g.triangles = t.at("triangles").get<std::size_t>();
    g.dropped_nonfinite = t.at("dropped").get<std::size_t>();
    g.hidden_points = t.at("hidden").get<std::size_t>();
    g.seen_points = t.at("seen").get<std::size_t>();
    g.area_mm2 = num(t.at("area"));
    g.spacing_mm = num(t.at("spacing"));
    g.load_time_s = num(t.at("load_time"));
    g.error = t.at("error").get<std::string>();
  }
  if (j.contains("score")) {
    const auto& s = j.at("score");
    scoring::CloudScore score;
    score.metrics = options.metrics;
    score.estimate_points = s.at("estimate_points").get<std::size_t>();
    score.ground_truth_points = s.at("ground_truth_points").get<std::size_t>();
    score.fscore_threshold_mm = num(s.at("fscore_threshold_mm"));
    for (const auto& m : scoring::metric_names()) score.*m.value = num(s.at(m.name));
    if (s.contains("visible_recall")) score.visible_recall = num(s.at("visible_recall"));
    r.score = score;
  }
}

void score_on_ranks(RankTeam& team, std::vector<Outcome>& outcomes, const std::vector<std::string>& gt_order,
                    std::map<std::string, std::vector<Outcome*>>& groups,
                    std::map<std::string, GroundTruthSummary>& summaries, scoring::ScoreOptions options,
                    const Options& o, ProgressLine& progress) {
  const int threads = o.threads > 0 ? o.threads
                                    : std::max(1, scoring::resolve_threads(0) / team.ranks_on_host());
  options.threads = threads;
  std::vector<std::size_t> jobs;
  for (const auto& file : gt_order)
    for (Outcome* r : groups[file]) jobs.push_back(static_cast<std::size_t>(r - outcomes.data()));

  // The ground truth this rank loaded last, kept for the next estimates of it.
  std::optional<std::string> loaded_file;
  std::optional<scoring::GroundTruth> loaded;
  GroundTruthSummary loaded_summary;
  const auto work = [&](std::size_t i) {
    Outcome r;
    r.pair = outcomes[i].pair;
    const std::string& file = r.pair.ground_truth;
    try {
      if (loaded_file != file) {
        loaded.reset();
        loaded_summary = GroundTruthSummary{};
        loaded_file = file;
        try {
          loaded = load(file, o, threads, loaded_summary);
        } catch (const InputError& e) {
          loaded_summary.file = file;
          loaded_summary.error = e.what();
        }
      }
      if (loaded)
        score_one(r, *loaded, options, o);
      else
        r.error = "ground truth " + loaded_summary.error;
    } catch (const std::exception& e) {  // as score_one: a failure while scoring
      r.error = r.pair.estimate + ": " + e.what();
      r.bad_input = false;
    }
    return encode(r, loaded_summary).dump();
  };
  const auto finished = [&](std::size_t i, const RunPlace& place, const std::string& row) {
    Outcome& r = outcomes[i];
    GroundTruthSummary& g = summaries[r.pair.ground_truth];
    decode(nlohmann::json::parse(row), r, g, options);
    r.gt = &g;
    r.place = place;
    progress.done_one();
  };
  const auto describe = [&](std::size_t i) { return outcomes[i].pair.estimate; };
  const auto on_stop = [] { return std::string("nothing was printed; run the same command again"); };
  team.run(jobs, work, finished, describe, on_stop);
}

int run_score(const Options& o) {
  if (!(o.fscore_threshold_mm > 0) || !std::isfinite(o.fscore_threshold_mm))
    throw InputError("--fscore-threshold must be a positive, finite number of mm, not " +
                     number_text(o.fscore_threshold_mm));
  scoring::ScoreOptions options;
  options.metrics = scoring::MetricSelection::parse(o.metrics);
  options.fscore_threshold_mm = o.fscore_threshold_mm;
  const int threads = scoring::resolve_threads(o.threads);

  std::vector<Outcome> outcomes;
  for (auto& p : expand_score_arguments(o.estimates, o.gt)) {
    Outcome r;
    r.pair = p;
    r.error = p.error;
    outcomes.push_back(std::move(r));
  }
  RankTeam team;  // under mpirun: the estimates spread over its ranks
  for (auto& r : outcomes) r.place = RunPlace{0, team.host()};

  // Group by ground truth, in order of first use; each is loaded once and
  // dropped before the next.
  std::vector<std::string> gt_order;
  std::map<std::string, std::vector<Outcome*>> groups;
  for (auto& r : outcomes) {
    if (!r.error.empty()) continue;
    if (!groups.count(r.pair.ground_truth)) gt_order.push_back(r.pair.ground_truth);
    groups[r.pair.ground_truth].push_back(&r);
  }
  std::map<std::string, GroundTruthSummary> summaries;
  std::vector<const GroundTruthSummary*> gts;
  ProgressLine progress(outcomes.size(), "estimates", o.progress, team.rank() == 0);
  for (const auto& r : outcomes)
    if (!r.error.empty()) progress.done_one();
  if (team.size() > 1) {
    for (const auto& file : gt_order) gts.push_back(&summaries[file]);
    score_on_ranks(team, outcomes, gt_order, groups, summaries, options, o, progress);
    if (team.rank() != 0) return kExitOk;  // rank 0 prints every result
    // The one ground truth of the command line is the whole input: stop.
    if (summaries.count(o.gt) && !summaries[o.gt].error.empty()) throw InputError(summaries[o.gt].error);
  } else {
    for (const auto& file : gt_order) {
      GroundTruthSummary& summary = summaries[file];
      gts.push_back(&summary);
      progress.stage("loading ground truth " + file);
      std::optional<scoring::GroundTruth> gt;
      try {
        gt = load(file, o, threads, summary);
      } catch (const InputError& e) {
        // The one ground truth of the command line is the whole input: stop.
        if (file == o.gt) throw;
        summary.error = e.what();
      }
      for (Outcome* r : groups[file]) r->gt = &summary;
      if (!gt) {
        for (Outcome* r : groups[file]) {
          r->error = "ground truth " + summary.error;
          progress.done_one();
        }
        continue;
      }
      progress.stage("");
      score_group(groups[file], *gt, options, o, threads, progress);
    }
  }

  progress.finish();
  std::size_t failed = 0;
  bool any_bad_input = false;
  for (const auto& r : outcomes)
    if (!r.score) {
      ++failed;
      any_bad_input = any_bad_input || r.bad_input;
    }
  if (o.json) {
    nlohmann::ordered_json all = nlohmann::ordered_json::array();
    for (const auto& r : outcomes) all.push_back(outcome_json(r, o));
    std::cout << all.dump(2) << "\n";
  } else {
    print_table(outcomes, gts, o, options);
  }
  std::cout << std::flush;
  if (failed == 0) return kExitOk;
  for (const auto& r : outcomes)
    if (!r.score) std::cerr << "touchcloud: error: " << r.error << "\n";
  std::cerr << "touchcloud: error: " << failed << " of " << outcomes.size() << " estimates could not be scored";
  if (failed < outcomes.size()) std::cerr << "; the rest were scored";
  std::cerr << "\n";
  return any_bad_input ? kExitBadInput : kExitRunFailed;
}

}  // namespace

Action* add_score_verb(CLI::App& app) {
  static Options o;
  static Action action;
  auto* cmd = app.add_subcommand("score", "Score estimated clouds against ground truth (a CAD mesh or a cloud)");
  cmd->add_option("--gt", o.gt,
                  "ground truth: a mesh in mm (.stl, .obj, .ply with faces; sampled uniformly by area), a scene "
                  "(.yaml: its object scaled and posed as simulated) or a cloud (.pcd, .ply); optional when every "
                  "estimate comes from a manifest that names its own. A mesh under 5 mm or over 2 m across is "
                  "refused as in another unit");
  cmd->add_option("estimates", o.estimates,
                  "estimated clouds (.pcd, .ply): files, folders (every cloud under them, e.g. a `touchcloud run` "
                  "output folder), globs, or CSV manifests of 'estimate, ground truth' rows (paths relative to "
                  "the manifest)")
      ->required();
  cmd->add_flag("--json", o.json, "print a JSON array with one record per estimate instead of a table");
  cmd->add_flag("--progress", o.progress,
                "show progress (estimates scored, rate, time left) also when stderr is not a terminal (logs, CI)");
  cmd->add_option("--samples", o.samples,
                  "points sampled from a mesh ground truth (default 0: 100 per mm^2 of surface, i.e. 0.1 mm mean "
                  "spacing, at least 100000 and at most 10000000; see docs/scoring.md)")
      ->capture_default_str();
  cmd->add_option("--seed", o.seed, "seed of the mesh sampling")->check(seed_value())->capture_default_str();
  cmd->add_option("--metrics", o.metrics,
                  "metrics to compute, comma-separated: chamfer_est_to_gt (the paper's Eq. 11), chamfer_gt_to_est, "
                  "chamfer_symmetric (mean of both), hausdorff, fscore, or all; chamfer_est_to_gt alone skips "
                  "the ground truth -> estimate search")
      ->delimiter(',')
      ->allow_extra_args(false)  // one list per --metrics, so estimates after it stay estimates
      ->capture_default_str();
  cmd->add_option("--fscore-threshold", o.fscore_threshold_mm,
                  "F-score distance threshold in mm (default: the sensor's 1.5 mm spatial resolution)")
      ->capture_default_str();
  cmd->add_option("--visible", o.visible,
                  "the part of a mesh or scene scored against: all, or from_above (only what a press straight down "
                  "can reach: samples with no surface above them; a closed object's sides and bottom are left out)")
      ->transform(CLI::CheckedTransformer(
          std::map<std::string, scoring::Visibility>{{"all", scoring::Visibility::all},
                                                     {"from_above", scoring::Visibility::from_above}},
          CLI::ignore_case))
      ->capture_default_str();
  cmd->add_option("--threads", o.threads, "threads to use (default 0: all cores)")->check(CLI::NonNegativeNumber);
  cmd->add_flag("--drop-nonfinite", o.drop_nonfinite,
                "drop points with NaN or infinite coordinates instead of refusing the file");
  cmd->add_flag("--dry-run", o.dry_run, kDryRunHelp);
  cmd->footer(
      "Distances are in mm (as the clouds are), computed in double precision.\n"
      "Exit status: 0 every estimate was scored; 2 bad input: a usage error or an unreadable ground truth "
      "given with --gt (nothing is scored), or some estimates were unreadable, empty or had no ground truth "
      "(the others are scored and printed; each failure is reported on stderr and in its record); "
      "1 some estimates failed while scoring, for another reason.");
  cmd->callback([] {
    action = [] {
      if (!o.dry_run) return run_score(o);
      std::cout << "score: command line ok, nothing scored (--dry-run)\n";
      return kExitOk;
    };
  });
  return &action;
}

}  // namespace touchcloud::cli
