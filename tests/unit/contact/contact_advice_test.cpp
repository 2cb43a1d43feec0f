// contact::domain_advice (contact_advice.h): a single-surface contact whose parts lie in two
// domains is named before a split or multi run, with its domains and their parts; one whose parts
// share a domain, a two-pass contact and a model without domains draw nothing.
#include "solver/contact/contact_advice.h"

#include <gtest/gtest.h>

namespace crashlink::contact {
namespace {

model::Model three_parts() {
  model::Model m;
  for (const char* n : {"bar", "plate", "rib"}) {
    model::Part p;
    p.name = n;
    m.parts.push_back(p);
  }
  model::Contact self;
  self.name = "all";
  self.kind = model::ContactKind::SingleSurface;
  self.master_parts = {0, 1, 2};
  m.contacts.push_back(self);
  model::Contact pair;
  pair.name = "pair";
  pair.kind = model::ContactKind::SurfaceToSurface;
  pair.master_parts = {1};
  m.contacts.push_back(pair);
  return m;
}

TEST(ContactDomainAdvice, SingleSurfaceAcrossDomainsIsNamed) {
  model::Model m = three_parts();
  EXPECT_TRUE(domain_advice(m).empty());  // no domains: a single-domain run
  m.domains = {{"fast", {0}}, {"slow", {1, 2}}};
  const auto a = domain_advice(m);
  ASSERT_EQ(a.size(), 1u);
  EXPECT_EQ(a[0],
            "single-surface contact 'all' spans the domains 'fast' (bar), 'slow' (plate, rib): "
            "each domain computes it over its own elements, so parts of different domains do "
            "not meet and can pass through each other. Put the parts that strike each other in "
            "one domain, or give them a surface_to_surface contact of their own");
  m.contacts[0].master_parts = {1, 2};  // both in 'slow'
  EXPECT_TRUE(domain_advice(m).empty());
}

}  // namespace
}  // namespace crashlink::contact
