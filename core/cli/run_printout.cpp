#include "run_printout.hpp"

#include <algorithm>
#include <iomanip>
#include <iostream>

namespace touchcloud::cli {

std::filesystem::path output_folder(const Pipeline& p, const std::string& out) {
  // The pipeline's name is an identifier (the parser checks it), and a
  // name taken from the file is one component: the default stays in out/.
  if (out.empty() && (p.name().empty() || p.name() == "." || p.name() == ".." ||
                      p.name().find('/') != std::string::npos))
    throw InputError("pipeline name '" + p.name() + "' cannot name a folder in out/; give --out DIR");
  return out.empty() ? std::filesystem::path("out") / p.name() : std::filesystem::path(out);
}

void print_metrics_and_files(const RunResult& r, const std::filesystem::path& out_dir) {
  std::size_t width = 36;
  for (const auto& [name, series] : r.record.metrics) width = std::max(width, name.size() + 1);
  for (const auto& [name, series] : r.record.metrics)
    std::cout << "  " << std::left << std::setw(static_cast<int>(width)) << name << std::defaultfloat
              << std::setprecision(6) << series.values.back()
              << (series.spec.unit.empty() ? "" : " " + series.spec.unit) << "\n";
  std::cout << "wrote " << r.record.outputs.size() + 1 << " files to " << out_dir.string() << " (summary.json";
  for (const auto& f : r.record.outputs) std::cout << ", " << f;
  std::cout << ")\n";
}

}  // namespace touchcloud::cli
