#include "sweep_grid.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <regex>
#include <utility>

#include "flagsim/core/errors.hpp"
#include "flagsim/scene/scene.hpp"

namespace flagsim::app {
namespace {

template <typename T>
std::vector<T> parse_list(const std::string& flag, const std::string& text,
                          T (*parse)(const std::string&, const std::string&)) {
  std::vector<T> values;
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t comma = std::min(text.find(',', start), text.size());
    values.push_back(parse(flag, text.substr(start, comma - start)));
    start = comma + 1;
  }
  return values;
}

std::pair<int, int> parse_lattice(const std::string& flag, const std::string& item) {
  static const std::regex pattern(R"(^\s*(\d{1,5})\s*[xX]\s*(\d{1,5})\s*$)");
  std::smatch m;
  if (!std::regex_match(item, m, pattern))
    throw UserError(
        fmt::format("{} {}: expected coarse lattices as JcxKc, e.g. 5x7,9x13", flag, item));
  return {std::stoi(m[1]), std::stoi(m[2])};
}

int parse_count(const std::string& flag, const std::string& item) {
  static const std::regex pattern(R"(^\s*(\d{1,7})\s*$)");
  std::smatch m;
  if (!std::regex_match(item, m, pattern) || std::stoi(m[1]) < 1)
    throw UserError(
        fmt::format("{} {}: expected counts of at least 1, comma-separated", flag, item));
  return std::stoi(m[1]);
}

// One of a table's names, kept as the name (the sweep writes it into --set).
template <typename E, std::size_t N>
std::string parse_name(const std::string& flag, const std::string& item, std::string_view what,
                       const NameTable<E, N>& table) {
  if (value_in(table, item)) return item;
  std::vector<std::string_view> names = names_in(table);
  const std::string_view last = names.back();
  names.pop_back();
  throw UserError(fmt::format("{} {}: expected {} {} and/or {}", flag, item, what,
                              fmt::join(names, ", "), last));
}

// A radius in m from 0 to 1, as the TOML float --set takes ("0.04"), or ""
// for 0 (the scene's own pole).
// A length from 0 to 1 m as a TOML float (the key's text), "" for 0 (the
// scene's own setting); else the error names the flag and what it `expects`.
std::string parse_metres(const std::string& flag, const std::string& item, const char* expects) {
  static const std::regex pattern(R"(^\s*(\d{1,3}(\.\d{1,9})?|\.\d{1,9})\s*$)");
  std::smatch m;
  if (!std::regex_match(item, m, pattern) || std::stod(m[1]) > 1.0)
    throw UserError(fmt::format("{} {}: expected {}", flag, item, expects));
  if (std::stod(m[1]) == 0.0) return "";
  std::string number = m[1];
  if (number.front() == '.') number = fmt::format("0{}", number);
  if (number.find('.') == std::string::npos) number += ".0";  // a TOML float, as the key reads
  return number;
}

std::string parse_radius(const std::string& flag, const std::string& item) {
  return parse_metres(flag, item,
                      "pole radii in m from 0 (the scene's own pole) to 1, e.g. 0,0.04");
}

std::string parse_thickness(const std::string& flag, const std::string& item) {
  return parse_metres(flag, item,
                      "self-contact thicknesses in m from 0 (the scene's own [contact]) to 1, "
                      "e.g. 0,0.005");
}

std::string parse_infill_solver(const std::string& flag, const std::string& item) {
  return parse_name(flag, item, "infill solvers", kInfillSolverNames);
}

std::string parse_backend(const std::string& flag, const std::string& item) {
  return parse_name(flag, item, "backends", kBackendNames);
}

std::string parse_reference(const std::string& flag, const std::string& item) {
  for (const char* mode : {"mass-spring", "bullet", "implicit", "xpbd"})
    if (item == mode) return item;
  throw UserError(fmt::format(
      "{} {}: expected full-lattice modes mass-spring, bullet, implicit and/or xpbd", flag, item));
}

}  // namespace

std::vector<SweepPoint> sweep_grid(const SweepOptions& o) {
  // The references: mass-spring first (every error is against it), then the
  // others asked for, each once. Bullet used to run by default; it was most
  // of a small sweep's time (issue 33, item 11), so it is asked for by name.
  const auto references = parse_list<std::string>("--references", o.references, parse_reference);
  if (std::find(references.begin(), references.end(), "mass-spring") == references.end())
    throw UserError(fmt::format(
        "--references {}: every error is measured against mass-spring; list it too, e.g. "
        "--references mass-spring,{}",
        o.references, references.front()));
  std::vector<SweepPoint> points = {{"mass-spring reference", {"scene.mode=\"mass-spring\""}}};
  for (const std::string& mode : references)
    if (std::none_of(points.begin(), points.end(), [&](const SweepPoint& p) {
          return p.sets.front() == fmt::format("scene.mode=\"{}\"", mode);
        }))
      points.push_back({mode + " reference", {fmt::format("scene.mode=\"{}\"", mode)}});
  if (o.coarse.empty()) throw UserError("sweep: --coarse is required (e.g. --coarse 5x7,9x13)");
  const auto coarse = parse_list<std::pair<int, int>>("--coarse", o.coarse, parse_lattice);
  const auto substeps = o.substeps.empty() ? std::vector<int>{0}
                                           : parse_list<int>("--substeps", o.substeps, parse_count);
  const auto relax =
      o.relax.empty() ? std::vector<int>{0} : parse_list<int>("--relax", o.relax, parse_count);
  // Empty: the scene's own infill solver.
  const auto infill = o.infill.empty()
                          ? std::vector<std::string>{""}
                          : parse_list<std::string>("--infill", o.infill, parse_infill_solver);
  // Empty: the scene's own solver.backend.
  const auto backends = o.backend.empty()
                            ? std::vector<std::string>{""}
                            : parse_list<std::string>("--backend", o.backend, parse_backend);
  // Empty: the scene's own pole.
  const auto radii = o.pole_radius.empty()
                         ? std::vector<std::string>{""}
                         : parse_list<std::string>("--pole-radius", o.pole_radius, parse_radius);
  // Empty: the scene's own [contact].
  const auto thicknesses =
      o.contact_thickness.empty()
          ? std::vector<std::string>{""}
          : parse_list<std::string>("--contact-thickness", o.contact_thickness, parse_thickness);
  for (const auto& [jc, kc] : coarse)
    for (const std::string& backend : backends)
      for (const std::string& radius : radii)
        for (const std::string& thickness : thicknesses)
          for (int s : substeps)
            for (const std::string& solver : infill)
              // The relaxation cap is the paper solver's; the smooth one gets one point.
              for (int r : (solver == "smooth" ? std::vector<int>{0} : relax)) {
                SweepPoint p{fmt::format("hybrid {}x{}", jc, kc),
                             {"scene.mode=\"hybrid\"", fmt::format("flag.coarse=[{},{}]", jc, kc)}};
                const auto add = [&p](std::string set, const std::string& label) {
                  p.sets.push_back(std::move(set));
                  p.label += " " + label;
                };
                if (!backend.empty()) add(fmt::format("solver.backend=\"{}\"", backend), backend);
                if (!radius.empty())
                  add(fmt::format("pole.radius={}", radius), fmt::format("pole {} m", radius));
                if (!thickness.empty())
                  add(fmt::format("contact.thickness={}", thickness),
                      fmt::format("contact {} m", thickness));
                if (s > 0) add(fmt::format("solver.substeps={}", s), fmt::format("substeps {}", s));
                if (!solver.empty()) add(fmt::format("infill.solver=\"{}\"", solver), solver);
                if (r > 0)
                  add(fmt::format("infill.relax_iterations={}", r), fmt::format("relax {}", r));
                points.push_back(p);
              }
  return points;
}

}  // namespace flagsim::app
