// touchcloud report RUN_DIR [--out FILE]: one self-contained HTML page of a
// run (or of a folder of runs, e.g. a sweep's), RUN_DIR/report.html by default.
#include <iostream>

#include "touchcloud/error.hpp"
#include "touchcloud/file_write.hpp"
#include "report.hpp"
#include "verbs.hpp"

namespace touchcloud::cli {

namespace fs = std::filesystem;

fs::path write_report(const fs::path& run_dir, const fs::path& out_file) {
  const std::vector<RunFolder> runs = find_runs(run_dir);  // InputError before anything is written
  const std::string page = report_html(report_data(runs));
  const fs::path file = out_file.empty() ? run_dir / "report.html" : out_file;
  if (fs::is_directory(file)) throw InputError("--out " + file.string() + " is a folder; give the report's file name");
  // Written under a temporary name and renamed: no half page under the name.
  fs::path partial = file;
  partial += ".partial";
  try {
    write_file(partial, page);
    fs::rename(partial, file);
  } catch (...) {
    std::error_code ec;
    fs::remove(partial, ec);
    throw;
  }
  return file;
}

Action* add_report_verb(CLI::App& app) {
  struct Options {
    std::string run_dir, out;
    bool dry_run = false;
  };
  static Options o;
  static Action action;
  auto* cmd = app.add_subcommand(
      "report", "Write one self-contained HTML page of a run: 3D surface against ground truth, chamfer per touch, "
                "stage times, parameters and versions");
  cmd->add_option("run_dir", o.run_dir, "a run's --out folder (summary.json), or a sweep's --out folder")->required();
  cmd->add_option("--out", o.out, "the HTML file (default: RUN_DIR/report.html)");
  cmd->add_flag("--dry-run", o.dry_run, kDryRunHelp);
  cmd->callback([] {
    action = [] {
      if (o.dry_run) {
        std::cout << "report " << o.run_dir << ": command line ok, nothing written (--dry-run)\n";
        return kExitOk;
      }
      const fs::path file = write_report(o.run_dir, o.out);
      std::cout << "wrote " << file.string() << "\n";
      return kExitOk;
    };
  });
  return &action;
}

}  // namespace touchcloud::cli
