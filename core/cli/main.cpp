// touchcloud: run, validate and inspect visuotactile pipelines.
#include <cstdlib>
#include <iostream>

#include "touchcloud/blas_environment.hpp"
#include "touchcloud/error.hpp"
#include "touchcloud/file_write.hpp"
#include "touchcloud/interrupt_cleanup.hpp"
#include "touchcloud/version.hpp"
#include "mpi_dispatch.hpp"
#include "verbs.hpp"

namespace {

// Located diagnostics print compiler-style (FILE:LINE:COL: error: ...), one a
// line; the last line always begins "touchcloud: error:". It claims only that
// nothing was written: bad data found by a stage comes after stages have run.
void report(const touchcloud::InputError& e) {
  const auto& diags = e.diagnostics();
  if (diags.size() == 1 && diags[0].where.line == 0) {
    const std::string at = diags[0].where.str();
    std::cerr << "touchcloud: error: " << (at.empty() ? "" : at + ": ") << diags[0].message << "\n";
    return;
  }
  for (const auto& d : diags) std::cerr << d.str() << "\n";
  std::cerr << "touchcloud: error: " << diags.size() << (diags.size() == 1 ? " problem" : " problems")
            << " found; nothing was written\n";
}

}  // namespace

int main(int argc, char** argv) {
  using namespace touchcloud::cli;
  // First, before any thread starts: Ctrl-C and SIGTERM remove the staging
  // folder of the run in progress.
  touchcloud::clean_up_on_interrupt();
  // A file-size limit fails a write as a full disk does (exit 1 naming the file).
  touchcloud::ignore_file_size_signal();
  // OpenBLAS (loaded with the GP plugin) reads its settings when it loads:
  // its idle threads sleep at once (fox mask main job: 4.2-4.3 s against
  // 4.4-5.1 s), and an AVX-512 CPU gets AVX-512 kernels.
  touchcloud::prepare_blas_environment();
  CLI::App app{"touchcloud " + std::string(touchcloud::kVersion) +
               ": point clouds and shapes from visuotactile sensors"};
  app.set_version_flag("--version", std::string(touchcloud::kVersion));
  app.require_subcommand(1);
  const std::vector<Action*> actions = {
      add_run_verb(app),
      add_stream_verb(app),
      add_validate_verb(app),
      add_plugins_verb(app),
      add_score_verb(app),
      add_sweep_verb(app),
      add_report_verb(app),
  };

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::cerr << "touchcloud: error: " << e.what() << " (see touchcloud --help)\n";
    return kExitBadInput;
  }

  try {
    for (Action* a : actions)
      if (*a) return (*a)();
    return kExitBadInput;
  } catch (const touchcloud::InputError& e) {
    // Under mpirun every rank checks the same input; rank 0 says what it found.
    if (launched_rank() == 0) report(e);
    return kExitBadInput;
  } catch (const std::exception& e) {
    std::cerr << "touchcloud: error: " << e.what() << "\n";
    return kExitRunFailed;
  }
}
