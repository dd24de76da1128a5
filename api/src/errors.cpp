// The API's exceptions and the Material handle.
#include "sandpaper/sandpaper.hpp"

namespace sandpaper {
namespace {

std::string level_message(const std::string& percept, const std::string& name, const std::vector<std::string>& known) {
  std::string list;
  for (const auto& k : known) list += (list.empty() ? "" : ", ") + k;
  std::string message = "unknown " + percept + " level \"" + name + "\"; known levels: " + (list.empty() ? "none" : list);
  if (auto close = compiler::closest_match(name, known); !close.empty()) message += " (did you mean \"" + close + "\"?)";
  return message;
}

}  // namespace

CompileError::CompileError(compiler::Diagnostics diagnostics)
    : Error(compiler::format_diagnostics(diagnostics)), diagnostics_(std::move(diagnostics)) {}

UnknownLevel::UnknownLevel(std::string name, std::vector<std::string> known, const std::string& percept)
    : Error(level_message(percept, name, known)), name_(std::move(name)), known_(std::move(known)) {}

Material::Material(schema::PatchProgram program)
    : program_(std::make_shared<const schema::PatchProgram>(std::move(program))) {}

std::vector<std::string> Material::warnings() const {
  std::vector<std::string> out;
  for (const auto& w : program_->warnings) out.push_back(w.message + " [" + w.code + "]");
  return out;
}

}  // namespace sandpaper
