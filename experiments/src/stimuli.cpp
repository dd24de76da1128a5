#include "sandpaper/experiment/stimuli.hpp"

#include <fmt/format.h>

#include "sandpaper/compiler/knowledge_report.hpp"
#include "sandpaper/experiment/percept_quantity.hpp"

namespace sandpaper::experiment {

std::vector<Stimulus> prepare_stimuli(const Design& design, const compiler::Compiler& compiler) {
  std::vector<Stimulus> out;
  std::string problems;
  auto refuse = [&](const StimulusRef& s, const std::string& why) {
    problems += fmt::format("{}:{}:{}: error: stimulus `{}` {}\n", design.path, s.line, s.column, s.text, why);
  };
  for (const auto& ref : design.stimuli) {
    const auto r = ref.file.empty() ? compiler.compile_text(ref.text, ref.text) : compiler.compile_file(ref.file);
    if (!r.ok()) {
      std::string first;
      for (const auto& d : r.diagnostics.all())
        if (d.severity == compiler::Severity::Error) {
          first = "[" + d.code + "] " + d.message + (d.suggestion.empty() ? "" : " (" + d.suggestion + ")");
          break;
        }
      refuse(ref, "does not compile for device `" + design.device + "`: " + first);
      continue;
    }
    Stimulus s;
    s.name = ref.text;
    s.program = std::make_shared<const schema::PatchProgram>(*r.program);
    if (design.percept != "roughness") {
      const PerceptQuantity* q = find_percept_quantity(design.percept);
      if (!q) throw DesignError(fmt::format("{}: error: percept `{}` cannot be scaled (known: {})\n", design.path,
                                            design.percept, percept_quantity_names()));
      const auto x = stimulus_quantity(*q, *r.program);
      if (!x) {
        refuse(ref, fmt::format("has no {} to scale {} on; give each stimulus {}", q->predictor, q->percept, q->law));
        continue;
      }
      s.quantity = *x;
      s.force_N = r.program->max_lateral_force_N;
      out.push_back(std::move(s));
      continue;
    }
    s.force_N = r.program->max_lateral_force_N;
    const auto k = compiler::assess_knowledge(*r.material, *r.program, compiler.calibration());
    s.period_m = k.texture.period_m;
    s.texture = k.texture.kind;
    s.believable = k.believable;
    if (!(s.force_N > 0)) {
      refuse(ref, "has no texture force to judge (maximum lateral force 0 N); experiments present textures");
      continue;
    }
    if (s.force_N > compiler.device().max_force_N * (1 + 1e-9)) {
      refuse(ref, fmt::format("needs {:.4g} N, more than device `{}` can produce ({:.4g} N)", s.force_N, design.device,
                              compiler.device().max_force_N));
      continue;
    }
    if (!s.believable && design.task != Task::Confidence && k.region)
      refuse(ref, fmt::format("lies in the low-confidence region `{}` ({:.3g} N below {:.3g} N with period {:.3g} mm; {}): "
                              "subjects doubted it was a texture at all, so its roughness is not meaningful; choose a "
                              "stronger or finer stimulus, or use task = \"confidence\"",
                              k.region->id, s.force_N, k.region->force_below_N, s.period_m * 1e3, k.region->where));
    if (design.task == Task::MagnitudeEstimation && !(s.period_m > 0))
      refuse(ref, "has no spatial period; the roughness regression (thesis Figure 20) needs one: use gratings, grids or Perlin textures");
    out.push_back(std::move(s));
  }
  if (!problems.empty()) throw DesignError(problems);
  return out;
}

}  // namespace sandpaper::experiment
