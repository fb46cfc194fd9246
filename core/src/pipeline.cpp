// The Pipeline facade: load (parse, resolve, check) and what a caller may
// read of a loaded pipeline. Running it is pipeline_runner.cpp.
#include "touchcloud/pipeline.hpp"

#include <chrono>

#include "pipeline_model.hpp"

namespace fs = std::filesystem;

namespace touchcloud {

Override parse_override(const std::string& text) {
  const auto eq = text.find('=');
  if (eq == std::string::npos || eq == 0)
    throw InputError("--set '" + text + "' must be STAGE.PARAM=VALUE");
  return {text.substr(0, eq), text.substr(eq + 1)};
}

Pipeline::Pipeline(std::unique_ptr<ResolvedPipeline> impl) : impl_(std::move(impl)) {}
Pipeline::Pipeline(Pipeline&&) noexcept = default;
Pipeline& Pipeline::operator=(Pipeline&&) noexcept = default;
Pipeline::~Pipeline() = default;

Pipeline Pipeline::load(const fs::path& file, const std::vector<Override>& overrides, PluginRegistry& registry) {
  const auto t0 = std::chrono::steady_clock::now();
  std::vector<Diagnostic> diagnostics;
  PipelineDoc doc = parse_pipeline(file, diagnostics);
  if (!diagnostics.empty()) throw InputError(diagnostics);
  auto resolved = resolve_pipeline(std::move(doc), overrides, registry);
  resolved->load_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return Pipeline(std::move(resolved));
}

const std::string& Pipeline::name() const { return impl_->name; }
const fs::path& Pipeline::file() const { return impl_->file; }

std::map<std::string, std::map<std::string, ParamValue>> Pipeline::parameters() const {
  std::map<std::string, std::map<std::string, ParamValue>> out;
  for (const auto* s : impl_->stages) out[s->id] = s->values;
  for (const auto* l : impl_->loops) out[l->id]["max_iterations"] = static_cast<std::int64_t>(l->max_iterations);
  return out;
}

std::vector<std::pair<std::string, MetricSpec>> Pipeline::declared_metrics() const {
  std::vector<std::pair<std::string, MetricSpec>> out;
  for (const auto* s : impl_->stages)
    for (const auto& m : s->ports->metrics()) out.emplace_back(s->id + "." + m.name, m);
  return out;
}

std::vector<std::string> Pipeline::wired_outputs() const {
  std::vector<std::string> out;
  for (const auto* s : impl_->stages)
    for (const auto& port : s->wanted_outputs) out.push_back(s->id + "." + port);
  return out;
}

}  // namespace touchcloud
