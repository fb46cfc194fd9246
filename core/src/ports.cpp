#include "touchcloud/ports.hpp"

namespace touchcloud {

namespace {
const PortSpec* find_port(const std::vector<PortSpec>& ports, std::string_view name) {
  for (const auto& p : ports)
    if (p.name == name) return &p;
  return nullptr;
}
}  // namespace

const PortSpec* PortSet::find_input(std::string_view name) const { return find_port(inputs_, name); }
const PortSpec* PortSet::find_output(std::string_view name) const { return find_port(outputs_, name); }

StageIO::StageIO(const PortSet& ports, std::map<std::string, std::any> inputs, std::set<std::string> wanted,
                 std::set<std::string> after_loop, bool final_call)
    : ports_(ports),
      inputs_(std::move(inputs)),
      wanted_(std::move(wanted)),
      after_loop_(std::move(after_loop)),
      final_call_(final_call) {}

bool StageIO::has(std::string_view input) const { return inputs_.count(std::string(input)) > 0; }

const std::any& StageIO::input_any(std::string_view name) const {
  auto it = inputs_.find(std::string(name));
  if (it != inputs_.end()) return it->second;
  if (!ports_.find_input(name))
    throw RunError("the stage asked for input '" + std::string(name) + "', which it never declared");
  throw RunError("input '" + std::string(name) + "' has no value (an optional input not wired, fed from a "
                 "previous iteration that has not happened yet, or an output that its stage produces only on "
                 "the call that ends its loop, which ended without it)");
}

std::string StageIO::type_mismatch(std::string_view name, const char* wanted, const char* held) const {
  return "input '" + std::string(name) + "' holds a value of C++ type " + held + ", not " + wanted;
}

void StageIO::set_output(std::string_view name, std::string_view type, std::any value) {
  const PortSpec* spec = ports_.find_output(name);
  if (!spec) throw RunError("the stage produced output '" + std::string(name) + "', which it never declared");
  if (spec->type != type)
    throw RunError("output '" + std::string(name) + "' is declared as " + spec->type + " but was given a " +
                   std::string(type));
  outputs_[std::string(name)] = std::move(value);
}

}  // namespace touchcloud
