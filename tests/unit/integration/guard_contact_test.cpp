// Energy created by contacts counts in the guard's error (issue 21, item 5; guard.h,
// contact_creation.h), on given numbers: each interface's contact energy below zero is energy it
// created, which the balance books as negative contact energy and so cannot see.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "core/errors.h"
#include "solver/integration/contact_creation.h"
#include "solver/integration/guard.h"

namespace crashlink::integration {
namespace {

contact::ContactStep step_with_energy(double energy_J) {
  contact::ContactStep s;
  s.energy_J = energy_J;
  return s;
}

/// One node (id 7, at rest) and two interfaces, 'head_hood' and 'hood_wiper'.
model::Model two_contacts() {
  model::Model m;
  m.nodes.id = {7};
  m.nodes.x0 = {0.0, 0.0, 0.0};
  m.contacts.resize(2);
  m.contacts[0].name = "head_hood";
  m.contacts[1].name = "hood_wiper";
  return m;
}

/// E0 = 10 J at the start; the contacts put `created_J` into kinetic energy and book it as
/// negative contact energy: the balance is exactly 0, the reference 10 + created_J.
EnergyAccount balanced_account(double created_J) {
  EnergyAccount e;
  e.initial_total_J = 10.0;
  e.kinetic_J = 10.0 + created_J;
  e.contact_J = -created_J;
  e.update_reference();
  return e;
}

TEST(ContactCreation, SumsWhatEachInterfaceCreated) {
  const std::vector<contact::ContactStep> steps = {step_with_energy(1.0), step_with_energy(-0.3),
                                                   step_with_energy(0.0), step_with_energy(-0.5)};
  const ContactCreation c = contact_creation(steps);
  EXPECT_DOUBLE_EQ(c.total_J, 0.8);  // the 1 J one holds energy, it created none
  EXPECT_EQ(c.worst, 3u);
  EXPECT_EQ(c.worst_J, 0.5);
  EXPECT_EQ(c.creating, 2u);
  EXPECT_EQ(contact_creation({}).total_J, 0.0);
  EXPECT_EQ(created_energy_J(2.0), 0.0);
  EXPECT_EQ(created_energy_J(-2.0), 2.0);
  EXPECT_TRUE(std::isnan(created_energy_J(std::numeric_limits<double>::quiet_NaN())));
}

TEST(GuardContact, CreatedEnergyCountsInTheError) {
  const EnergyAccount e = balanced_account(0.48);
  EXPECT_EQ(e.balance_J(), 0.0);
  EXPECT_EQ(guarded_balance_error(e, 0.0), 0.0);  // what the balance alone sees
  EXPECT_DOUBLE_EQ(guarded_error(e, 0.0, 0.48), 0.48 / 10.48);
  // Lost and created energy do not cancel: 0.2 J lost elsewhere adds to the 0.48 J created.
  EnergyAccount lossy = e;
  lossy.kinetic_J -= 0.2;
  EXPECT_NEAR(guarded_error(lossy, 0.0, 0.48), (0.2 + 0.48) / 10.48, 1e-15);
  // The floor under the reference applies to the created part too.
  EXPECT_DOUBLE_EQ(guarded_error(e, 100.0, 0.48), 0.48 / 100.0);
}

TEST(GuardContact, AContactThatCreatesMoreThanTheToleranceStopsTheRun) {
  const model::Model m = two_contacts();
  const double v[3] = {0.0, 0.0, 0.0};
  const GuardContext ctx{1234, 2.5e-3, 1e-6, "wiper"};
  const BalanceBound bound{0.05, 0.0};
  // 0.4 J of 10.4 J (3.8 %): under the 5 % bound, the run goes on.
  EXPECT_NO_THROW(check_energy_balance(m, balanced_account(0.4), bound, v, ctx,
                                       contact_creation(std::vector<contact::ContactStep>{
                                           step_with_energy(2.0), step_with_energy(-0.4)})));
  // 0.6 J of 10.6 J (5.7 %): stopped, the contact named with what it created.
  const EnergyAccount e = balanced_account(0.6);
  const std::vector<contact::ContactStep> steps = {step_with_energy(2.0), step_with_energy(-0.6)};
  EXPECT_NO_THROW(check_energy_balance(m, e, bound, v, ctx)) << "the balance alone sees nothing";
  try {
    check_energy_balance(m, e, bound, v, ctx, contact_creation(steps));
    FAIL() << "a contact that created 5.7 % of E0 was not stopped";
  } catch (const NumericalError& err) {
    const std::string what = err.what();
    std::printf("[message] %s\n", what.c_str());
    EXPECT_EQ(what.rfind("wiper: energy error 5.66 %", 0), 0u) << what;
    EXPECT_NE(what.find("contact 'hood_wiper' created 0.6 J, 5.66 % of E0 = 10.6 J"),
              std::string::npos)
        << what;
    EXPECT_NE(what.find("cycle 1234"), std::string::npos) << what;
    EXPECT_NE(what.find("Energy was created by contact"), std::string::npos) << what;
    EXPECT_EQ(what.find("head_hood"), std::string::npos) << what;  // it created nothing
  }
}

TEST(GuardContact, WithoutCreatedEnergyTheMessageIsTheBalancesOwn) {
  const model::Model m = two_contacts();
  const double v[3] = {0.0, 3.0, 4.0};
  EnergyAccount e;
  e.initial_total_J = 10.0;
  e.kinetic_J = 11.0;  // 1 J created by the integration: an instability
  e.update_reference();
  try {
    check_energy_balance(m, e, {0.05, 0.0}, v, {}, contact_creation({}));
    FAIL() << "9.1 % was not stopped";
  } catch (const NumericalError& err) {
    const std::string what = err.what();
    EXPECT_NE(what.find("energy balance error 9.09 % exceeds the bound 5 %"), std::string::npos)
        << what;
    EXPECT_NE(what.find("Energy was created: the run went unstable."), std::string::npos) << what;
    EXPECT_NE(what.find("The fastest node is 7 (5 m/s)"), std::string::npos) << what;
    EXPECT_EQ(what.find("contact"), std::string::npos) << what;
  }
}

}  // namespace
}  // namespace crashlink::integration
