#include "output_name.hpp"

#include <filesystem>

namespace touchcloud {

std::optional<std::string> output_name_problem(const std::string& file_name) {
  const std::filesystem::path rel(file_name);
  const std::filesystem::path normal = rel.lexically_normal();
  const bool escapes = rel.is_absolute() || rel.has_root_path() || (!normal.empty() && *normal.begin() == "..");
  if (escapes) return "output file '" + file_name + "' must stay inside the output folder";
  if (file_name.empty() || normal == "." || normal.filename().empty())
    return "output file '" + file_name + "' names no file";
  if (normal.begin()->string().rfind(kStagingPrefix, 0) == 0)
    return "output file '" + file_name + "' is inside a folder named " + kStagingPrefix +
           "*, which the toolkit reserves for its staging folders";
  return std::nullopt;
}

namespace {
std::string replaced(std::string text, const std::string& field, const std::string& by) {
  for (auto at = text.find(field); at != std::string::npos; at = text.find(field, at + by.size()))
    text.replace(at, field.size(), by);
  return text;
}
}  // namespace

std::string with_pipeline_name(std::string file_name, const std::string& pipeline_name) {
  return replaced(std::move(file_name), kPipelineField, pipeline_name);
}

std::string with_scene_name(std::string file_name, const std::string& scene_name) {
  return replaced(std::move(file_name), kSceneField, scene_name);
}

}  // namespace touchcloud
