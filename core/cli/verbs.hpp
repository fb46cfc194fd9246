// The verbs of the touchcloud CLI. Each adds its subcommand to the app and
// returns the action to run when that subcommand was parsed.
#pragma once

#include <functional>

#include <CLI/CLI.hpp>

namespace touchcloud::cli {

using Action = std::function<int()>;  // returns the exit status

Action* add_run_verb(CLI::App& app);
Action* add_stream_verb(CLI::App& app);
Action* add_validate_verb(CLI::App& app);
Action* add_plugins_verb(CLI::App& app);
Action* add_score_verb(CLI::App& app);
Action* add_sweep_verb(CLI::App& app);
Action* add_report_verb(CLI::App& app);

// Help of --set, shared by run and validate: where relative paths start.
inline constexpr const char* kSetHelp =
    "override a parameter: STAGE.PARAM=VALUE (repeatable). A relative file path given here is relative to "
    "the current directory; one in the pipeline file, to that file's folder";

// Help of --scene, shared by run, validate and sweep.
inline constexpr const char* kSceneHelp =
    "the scene file for every stage that takes a scene (replacing the pipeline's 'scene:' and the stages' own, "
    "except those marked own_scene: true); relative to the current directory";

// Help of --dry-run, shared by run, sweep, score and report (the guide's
// commands that need minutes are checked with it: docs.commands).
inline constexpr const char* kDryRunHelp =
    "check the command line (and the pipeline with its overrides, as validate does) and stop: nothing runs and "
    "nothing is written";

// Exit statuses of the CLI contract.
inline constexpr int kExitOk = 0;
inline constexpr int kExitRunFailed = 1;
inline constexpr int kExitBadInput = 2;

}  // namespace touchcloud::cli
