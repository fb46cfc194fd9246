// touchcloud validate PIPELINE [--set K=V]...: checks without running.
#include <iostream>

#include "touchcloud/pipeline.hpp"
#include "verbs.hpp"

namespace touchcloud::cli {

Action* add_validate_verb(CLI::App& app) {
  struct Options {
    std::string pipeline;
    std::vector<std::string> sets;
    std::string scene;
  };
  static Options o;
  static Action action;
  auto* cmd = app.add_subcommand("validate", "Check a pipeline (plugins, parameters, wiring, input files) without running it");
  cmd->add_option("pipeline", o.pipeline, "pipeline YAML file")->required();
  cmd->add_option("--set", o.sets, kSetHelp);
  cmd->add_option("--scene", o.scene, kSceneHelp);
  cmd->callback([] {
    action = [] {
      std::vector<Override> overrides;
      for (const auto& s : o.sets) overrides.push_back(parse_override(s));
      if (!o.scene.empty()) overrides.push_back({kPipelineSceneKey, o.scene, "--scene"});
      PluginRegistry registry;
      Pipeline p = Pipeline::load(o.pipeline, overrides, registry);
      std::size_t stages = p.parameters().size();
      std::cout << o.pipeline << ": ok (pipeline '" << p.name() << "', " << stages << " stages and loops)\n";
      return kExitOk;
    };
  });
  return &action;
}

}  // namespace touchcloud::cli
