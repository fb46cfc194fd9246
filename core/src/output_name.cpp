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

std::string with_pipeline_name(std::string file_name, const std::string& pipeline_name) {
  const std::string field = kPipelineField;
  for (auto at = file_name.find(field); at != std::string::npos; at = file_name.find(field, at + pipeline_name.size()))
    file_name.replace(at, field.size(), pipeline_name);
  return file_name;
}

}  // namespace touchcloud
