// The `domains` section (docs/scenario-format.md, docs/decomposition.md): the decomposition of
// the model into subdomains, one model::Domain per entry in file order. Every part in exactly one
// domain; a rigid body's parts in one domain (a rigid body is one set of dofs).
#include <map>

#include "core/errors.h"
#include "core/log_escape.h"
#include "solver/io/scenario_names.h"
#include "solver/io/scenario_sections.h"

namespace crashlink::io::detail {

void read_domains(const YamlNode& section, ScenarioBuild& b) {
  auto& m = b.model;
  struct Where {
    std::string domain;
    int line = 0;
  };
  std::map<int, Where> placed;  // part index -> domain and line
  const auto entries = section.entries("domains (name: {parts: [part names]})");
  if (entries.empty())
    section.fail(
        "lists no domain; give `name: {parts: [...]}` per domain, or remove the section "
        "for a single-domain run");
  std::map<std::string, Where> folded;  // lower-case name -> the first domain with it
  for (const auto& [name, entry] : entries) {
    // A domain's name becomes file and folder names (solver/io/scenario_names.h).
    if (const std::string why = file_name_problem(name); !why.empty())
      entry.fail(
          fmt::format("domain name '{}' cannot be a file name (DIR/domains/<name>.h5, "
                      "checkpoint folders): {}",
                      core::log_escape(name), why));
    std::string lower = name;
    for (char& c : lower)
      if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
    if (const auto [it, fresh] = folded.try_emplace(lower, Where{name, entry.line()}); !fresh)
      entry.fail(
          fmt::format("domain name '{}' differs from '{}' (line {}) only in letter case; "
                      "their files would be one on a case-insensitive file system: "
                      "rename one",
                      name, it->second.domain, it->second.line));
    entry.expect_keys({"parts"});
    model::Domain d;
    d.name = name;
    const auto parts = entry.required("parts", "the parts of this domain, e.g. [plate, frame]");
    const std::vector<YamlNode> items =
        parts.is_sequence() ? parts.items("part names") : std::vector<YamlNode>{parts};
    for (const auto& pn : items) {
      const int p = read_part_reference(pn, b);
      if (auto it = placed.find(p); it != placed.end())
        pn.fail(
            fmt::format("part '{}' is already in domain '{}' (line {}); a part belongs to "
                        "exactly one domain: remove it from one of them",
                        pn.text(), it->second.domain, it->second.line));
      placed[p] = {name, pn.line()};
      d.parts.push_back(p);
    }
    if (d.parts.empty())
      parts.fail("lists no part; give at least one part name or remove the domain");
    m.domains.push_back(std::move(d));
  }
  std::vector<std::string> orphans;
  for (std::size_t p = 0; p < m.parts.size(); ++p)
    if (!placed.count(static_cast<int>(p))) orphans.push_back(m.parts[p].name);
  if (!orphans.empty())
    section.fail(fmt::format(
        "part{} {} {} in no domain; add each to exactly one domain (every "
        "part must be in one)",
        orphans.size() > 1 ? "s" : "", quoted_list(orphans), orphans.size() > 1 ? "are" : "is"));
  for (const auto& rb : m.rigid_bodies) {
    if (rb.parts.empty()) continue;  // a body of nodes: checked by the decomposition
    const auto& first = placed.at(rb.parts.front());
    for (int p : rb.parts) {
      const auto& w = placed.at(p);
      if (w.domain != first.domain)
        throw InputError(
            b.file, w.line, section.path() + "." + w.domain + ".parts",
            fmt::format("rigid body '{}' has part '{}' in domain '{}' and part '{}' "
                        "in domain '{}'; a rigid body is one set of dofs: put all "
                        "its parts in one domain",
                        rb.name, m.parts[static_cast<std::size_t>(rb.parts.front())].name,
                        first.domain, m.parts[static_cast<std::size_t>(p)].name, w.domain));
    }
  }
}

}  // namespace crashlink::io::detail
