// YAML -> PipelineDoc, keeping the line and column of everything.
#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cstring>
#include <cmath>
#include <fstream>
#include <regex>
#include <set>

#include "nearest_name.hpp"
#include "pipeline_model.hpp"
#include "yaml_document_checks.hpp"

namespace fs = std::filesystem;

namespace touchcloud {

SourceLocation location_of(const YAML::Node& node, const fs::path& file) {
  const YAML::Mark mark = node.Mark();
  if (mark.is_null()) return {file.string(), 0, 0};
  return {file.string(), mark.line + 1, mark.column + 1};
}

namespace {

const std::regex kIdPattern("[A-Za-z_][A-Za-z0-9_]*");
const std::regex kRefPattern("([A-Za-z_][A-Za-z0-9_]*)\\.([A-Za-z_][A-Za-z0-9_]*)(@previous)?");

class Parser {
 public:
  Parser(fs::path file, std::vector<Diagnostic>& diagnostics) : file_(std::move(file)), diags_(diagnostics) {}

  PipelineDoc parse(const YAML::Node& root) {
    PipelineDoc doc;
    doc.file = file_;
    doc.name = file_.stem().string();
    if (!root.IsMap()) {
      error(root, "a pipeline is a mapping with 'pipeline' and 'stages'");
      return doc;
    }
    check_keys(root, {"pipeline", "description", "scene", "stages"}, "pipeline");
    if (const auto name = root["pipeline"]) {
      // The name picks the default output folder (out/<name>): an
      // identifier cannot lead it anywhere else.
      if (name.IsScalar() && std::regex_match(name.Scalar(), kIdPattern)) doc.name = name.Scalar();
      else
        error(name, "'pipeline' is the pipeline's name, an identifier (letters, digits, '_'; not starting with a "
                    "digit), got '" + (name.IsScalar() ? quoted_excerpt(name.Scalar()) : std::string("a list or mapping")) + "'");
    }
    if (const auto scene = root["scene"]) {
      if (!scene.IsScalar()) error(scene, "'scene' is the scene file (YAML) every stage with a 'scene' parameter takes");
      else doc.scene = ParamDoc{"scene", scene, location_of(scene, file_), false};
    }
    const auto stages = root["stages"];
    if (!stages) error(root, "the pipeline has no 'stages'");
    else doc.nodes = parse_nodes(stages);
    return doc;
  }

 private:
  void error(const YAML::Node& at, std::string message) {
    diags_.push_back({location_of(at, file_), std::move(message)});
  }

  void check_keys(const YAML::Node& map, const std::vector<std::string>& allowed, const std::string& what) {
    for (const auto& kv : map) {
      const std::string key = kv.first.as<std::string>("");
      if (std::find(allowed.begin(), allowed.end(), key) == allowed.end()) {
        std::string list;
        for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
        // Quote no more than a key: a file that is not a pipeline (a password
        // file) must not be echoed back line by line.
        error(kv.first, "unknown key '" + quoted_excerpt(key) + "' in " + what + did_you_mean(key, allowed) +
                            " (allowed: " + list + ")");
      }
    }
  }

  std::vector<NodeDoc> parse_nodes(const YAML::Node& list) {
    std::vector<NodeDoc> nodes;
    if (!list.IsSequence()) {
      error(list, "'stages' is a list of stages, each starting with '- id:'");
      return nodes;
    }
    if (list.size() == 0) error(list, "'stages' is empty");
    for (const auto& item : list) {
      // An alias repeats a stage (and may hold the loop it is in): refuse it
      // rather than recurse or multiply.
      const YAML::Mark m = item.Mark();
      if (!m.is_null() && !stage_marks_.insert({m.line, m.column}).second) {
        error(item, "this stage appears a second time (a YAML alias); every stage is written once, with its own id");
        continue;
      }
      nodes.push_back(parse_node(item));
    }
    return nodes;
  }

  NodeDoc parse_node(const YAML::Node& item) {
    NodeDoc node;
    node.where = location_of(item, file_);
    if (!item.IsMap()) {
      error(item, "a stage is a mapping with 'id' and 'plugin' (or 'loop')");
      return node;
    }
    const auto id = item["id"];
    if (!id) error(item, "the stage has no 'id'");
    else if (!id.IsScalar() || !std::regex_match(id.Scalar(), kIdPattern))
      error(id, "stage id '" + (id.IsScalar() ? quoted_excerpt(id.Scalar()) : std::string("?")) +
                    "' is not an identifier (letters, digits, '_'; not starting with a digit)");
    else {
      node.id = id.Scalar();
      node.where = location_of(id, file_);
    }

    if (const auto loop = item["loop"]) {
      check_keys(item, {"id", "loop", "description"}, "loop '" + node.id + "'");
      node.is_loop = true;
      parse_loop(loop, node);
      return node;
    }
    check_keys(item, {"id", "plugin", "params", "inputs", "background", "own_scene", "description"},
               "stage '" + node.id + "'");
    const auto plugin = item["plugin"];
    if (!plugin) error(item, "stage '" + node.id + "' names no 'plugin' (or 'loop')");
    else if (!plugin.IsScalar()) error(plugin, "'plugin' is a plugin name");
    else {
      node.plugin = plugin.Scalar();
      node.plugin_where = location_of(plugin, file_);
    }
    if (const auto params = item["params"]) {
      if (!params.IsMap()) error(params, "'params' is a mapping of parameter names to values");
      else
        for (const auto& kv : params)
          node.params.push_back({kv.first.as<std::string>(""), kv.second,
                                 location_of(kv.second.IsNull() ? kv.first : kv.second, file_), false});
    }
    if (const auto background = item["background"]) {
      bool value = false;
      if (!background.IsScalar() || !YAML::convert<bool>::decode(background, value))
        error(background, "'background' is true or false");
      node.background = value;
    }
    if (const auto own_scene = item["own_scene"]) {
      bool value = false;
      if (!own_scene.IsScalar() || !YAML::convert<bool>::decode(own_scene, value))
        error(own_scene, "'own_scene' is true or false");
      node.own_scene = value;
      node.own_scene_where = location_of(own_scene, file_);
    }
    if (const auto inputs = item["inputs"]) {
      if (!inputs.IsMap()) error(inputs, "'inputs' maps this stage's inputs to 'stage.output'");
      else
        for (const auto& kv : inputs)
          if (auto ref = parse_ref(kv.second)) {
            ref->port = kv.first.as<std::string>("");
            node.inputs.push_back(*ref);
          }
    }
    return node;
  }

  void parse_loop(const YAML::Node& loop, NodeDoc& node) {
    if (!loop.IsMap()) {
      error(loop, "'loop' is a mapping with 'max_iterations' and 'stages'");
      return;
    }
    check_keys(loop, {"max_iterations", "until", "stages"}, "loop '" + node.id + "'");
    const auto max = loop["max_iterations"];
    if (!max) error(loop, "loop '" + node.id + "' has no 'max_iterations' (its budget)");
    else {
      node.max_iterations_where = location_of(max, file_);
      std::int64_t n = 0;
      const std::string s = max.IsScalar() ? max.Scalar() : "";
      const auto r = std::from_chars(s.data(), s.data() + s.size(), n);
      if (r.ec != std::errc() || r.ptr != s.data() + s.size())
        error(max, "'max_iterations' must be an integer, got '" + s + "'");
      else if (n < 1)
        error(max, "'max_iterations' must be >= 1, got " + s);
      else
        node.max_iterations = n;
    }
    if (const auto until = loop["until"]) node.until = parse_ref(until);
    const auto stages = loop["stages"];
    if (!stages) error(loop, "loop '" + node.id + "' has no 'stages'");
    else node.body = parse_nodes(stages);
  }

  std::optional<InputRefDoc> parse_ref(const YAML::Node& value) {
    std::smatch m;
    const std::string text = value.IsScalar() ? value.Scalar() : "";
    if (!value.IsScalar() || !std::regex_match(text, m, kRefPattern)) {
      error(value, "'" + text + "' is not an output reference: write 'stage.output' or 'stage.output@previous'");
      return std::nullopt;
    }
    InputRefDoc ref;
    ref.stage = m[1];
    ref.output = m[2];
    ref.previous = m[3].matched;
    ref.where = location_of(value, file_);
    return ref;
  }

  fs::path file_;
  std::vector<Diagnostic>& diags_;
  std::set<std::pair<int, int>> stage_marks_;  // line and column of every stage read
};

template <class T>
bool parse_number(const std::string& s, T& out) {
  const auto r = std::from_chars(s.data(), s.data() + s.size(), out);
  return r.ec == std::errc() && r.ptr == s.data() + s.size() && !s.empty();
}

bool parse_double(const std::string& text, double& out) {
  // YAML allows a leading '+'; from_chars does not.
  const std::string s = (!text.empty() && text[0] == '+') ? text.substr(1) : text;
  return parse_number(s, out);
}

// A YAML sequence of `T`, each element read by `parse`; `what` names them in
// the error ("numbers", "whole numbers").
template <class T, class Parse>
std::optional<ParamValue> convert_list(const YAML::Node& value, const char* what, const char* example, Parse parse,
                                       std::string& error) {
  if (!value.IsSequence()) {
    error = std::string("expected a list of ") + what + " like " + example + ", got '" +
            (value.IsScalar() ? value.Scalar() : std::string("a mapping")) + "'";
    return std::nullopt;
  }
  std::vector<T> list;
  for (const auto& item : value) {
    T x{};
    if (!item.IsScalar() || !parse(item.Scalar(), x)) {
      error = std::string("expected a list of ") + what + ", but element " + std::to_string(list.size()) + " is '" +
              (item.IsScalar() ? item.Scalar() : std::string("not a number")) + "'";
      return std::nullopt;
    }
    list.push_back(x);
  }
  return ParamValue(list);
}

}  // namespace

PipelineDoc parse_pipeline(const fs::path& file, std::vector<Diagnostic>& diagnostics) {
  // A folder or a FIFO opens as a stream too: refuse anything but a file.
  if (auto why = not_a_regular_file(file)) {
    diagnostics.push_back({{file.string()}, "cannot read the pipeline file: " + *why});
    return {};
  }
  std::ifstream in(file);
  if (!in) {
    diagnostics.push_back({{file.string()}, "cannot read the pipeline file: " + std::string(std::strerror(errno))});
    return {};
  }
  YAML::Node root;
  try {
    root = YAML::Load(in);
  } catch (const YAML::Exception& e) {
    diagnostics.push_back({{file.string(), e.mark.line + 1, e.mark.column + 1}, "malformed YAML: " + yaml_error_text(e)});
    return {};
  }
  if (!root || root.IsNull()) {
    diagnostics.push_back({{file.string()}, "the pipeline file is empty"});
    return {};
  }
  const std::size_t before = diagnostics.size();
  check_duplicate_keys(root, file, diagnostics);
  if (diagnostics.size() > before) return {};
  return Parser(file, diagnostics).parse(root);
}

std::optional<ParamValue> convert_param(const ParamSpec& spec, const YAML::Node& value, std::string& error) {
  if (!value || value.IsNull()) {
    error = "has no value (expected " + std::string(to_string(spec.type)) + ")";
    return std::nullopt;
  }
  const bool scalar = value.IsScalar();
  const std::string s = scalar ? value.Scalar() : "";
  switch (spec.type) {
    case ParamType::Bool: {
      if (scalar && (s == "true" || s == "false")) return ParamValue(s == "true");
      error = "expected a bool (true or false), got '" + (scalar ? s : "a " + std::string(value.IsMap() ? "mapping" : "list")) + "'";
      return std::nullopt;
    }
    case ParamType::Int: {
      std::int64_t i = 0;
      if (scalar && parse_number(s, i)) return ParamValue(i);
      error = "expected an integer, got '" + (scalar ? s : std::string("a list or mapping")) + "'";
      return std::nullopt;
    }
    case ParamType::Double: {
      double d = 0;
      if (scalar && parse_double(s, d)) return ParamValue(d);
      error = "expected a number, got '" + (scalar ? s : std::string("a list or mapping")) + "'";
      return std::nullopt;
    }
    case ParamType::String:
    case ParamType::Choice: {
      if (scalar) return ParamValue(s);
      error = "expected a string, got a list or mapping";
      return std::nullopt;
    }
    case ParamType::DoubleList:
      return convert_list<double>(value, "numbers", "[1, 2, 3]", parse_double, error);
    case ParamType::IntList:
      return convert_list<std::int64_t>(value, "whole numbers", "[14, 14]", parse_number<std::int64_t>, error);
  }
  error = "unsupported parameter type";
  return std::nullopt;
}

}  // namespace touchcloud
