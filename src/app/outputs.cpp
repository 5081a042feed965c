#include "app/outputs.hpp"

#include "app/commands.hpp"
#include "app/messages.hpp"

namespace curvemesh::app {

bool outputs_distinct(const std::vector<base::NamedPath>& inputs, const std::vector<base::NamedPath>& outputs) {
  std::vector<base::NamedPath> given;
  for (const base::NamedPath& o : outputs)
    if (!o.second.empty()) given.push_back(o);
  const std::string clash = base::output_clash(inputs, given);
  if (clash.empty()) return true;
  say(clash);
  return false;
}

int write_together(const std::function<void(base::OutputFiles&)>& add) {
  try {
    base::OutputFiles files;
    add(files);
    files.commit();
  } catch (const base::OutputError& e) {
    say(e.what());
    return kInvalidInput;
  }
  return kOk;
}

}  // namespace curvemesh::app
